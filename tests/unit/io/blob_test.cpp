#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/blob.h>

#include "support/synthetic.h"

namespace pc::io {
namespace {

using F = pcl::PCLPointField;

TEST(Blob, KeepPointsCompactsInPlaceKeepingEveryField) {
    Blob b = test::make_blob(
        {{"x", F::FLOAT32}, {"id", F::UINT16}}, 5, 1,
        [](std::size_t i, std::size_t k, std::uint32_t) { return k == 0 ? i * 0.5 : i + 100.0; });
    const Blob original = b;
    const std::uint8_t* storage = b.cloud.data.data();
    const std::vector<std::uint32_t> idx = {1, 3, 4};
    keep_points(b, idx);
    ASSERT_EQ(b.size(), 3u);
    EXPECT_EQ(b.cloud.data.data(), storage);  // compacted where it was, not copied
    EXPECT_EQ(b.cloud.data.size(), 3u * b.cloud.point_step);
    EXPECT_EQ(b.cloud.row_step, 3u * b.cloud.point_step);
    EXPECT_EQ(b.cloud.fields.size(), 2u);
    for (std::size_t j = 0; j < idx.size(); ++j) {
        EXPECT_EQ(
            0, std::memcmp(&b.cloud.data[j * b.cloud.point_step],
                           &original.cloud.data[idx[j] * b.cloud.point_step], b.cloud.point_step));
    }
    keep_points(b, {});
    EXPECT_EQ(b.size(), 0u);
}

TEST(Blob, KeepFlaggedKeepsTheSameRowsAsTheIndicesOfItsFlags) {
    // Oracle: keep_points() with the indices whose flag matches; any non-zero flag counts as set.
    const std::vector<std::uint8_t> flags = {0, 2, 0, 1, 1, 0, 0};
    for (const bool keep_set : {true, false}) {
        Blob b = test::make_blob({{"x", F::FLOAT32}, {"id", F::UINT16}}, flags.size(), 1,
                                 [](std::size_t i, std::size_t k, std::uint32_t) {
                                     return k == 0 ? i * 0.5 : i + 100.0;
                                 });
        Blob expected = b;
        std::vector<std::uint32_t> idx;
        for (std::uint32_t i = 0; i < flags.size(); ++i) {
            if ((flags[i] != 0) == keep_set) {
                idx.push_back(i);
            }
        }
        keep_points(expected, idx);
        const std::uint8_t* storage = b.cloud.data.data();
        keep_flagged(b, flags, keep_set);
        EXPECT_EQ(b.cloud.data.data(), storage);
        EXPECT_EQ(b.cloud.data, expected.cloud.data);
        EXPECT_EQ(b.cloud.width, expected.cloud.width);
        EXPECT_EQ(b.cloud.height, 1u);
        EXPECT_EQ(b.cloud.row_step, expected.cloud.row_step);
    }
    Blob b = test::random_xyz(3);
    EXPECT_THROW(keep_flagged(b, std::vector<std::uint8_t>(2, 0), true), Error);
}

TEST(Blob, CopyPointsTakesAnyOrderAndLeavesTheSourceAlone) {
    const Blob b = test::make_blob(
        {{"x", F::FLOAT32}, {"id", F::UINT16}}, 5, 1,
        [](std::size_t i, std::size_t k, std::uint32_t) { return k == 0 ? i * 0.5 : i + 100.0; });
    const Blob original = b;
    const std::vector<std::uint32_t> idx = {4, 0, 4};
    const Blob c = copy_points(b, idx);
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(c.cloud.fields.size(), 2u);
    EXPECT_EQ(c.cloud.row_step, 3u * c.cloud.point_step);
    for (std::size_t j = 0; j < idx.size(); ++j) {
        EXPECT_EQ(0, std::memcmp(&c.cloud.data[j * c.cloud.point_step],
                                 &b.cloud.data[idx[j] * b.cloud.point_step], b.cloud.point_step));
    }
    EXPECT_EQ(b.cloud.data, original.cloud.data);
    EXPECT_EQ(copy_points(b, {}).size(), 0u);
    EXPECT_THROW((void)copy_points(b, std::vector<std::uint32_t>{5}), Error);
}

TEST(Blob, AppendPointsJoinsCloudsOfOneLayoutOnly) {
    const auto make = [](std::size_t n, double base) {
        return test::make_blob({{"x", F::FLOAT32}, {"id", F::UINT16}}, n, 1,
                               [&](std::size_t i, std::size_t k, std::uint32_t) {
                                   return k == 0 ? base + i * 0.5 : base + i;
                               });
    };
    Blob a = make(3, 0);
    const Blob b = make(2, 100), whole = make(5, 0);
    ASSERT_TRUE(append_points(a, b));
    ASSERT_EQ(a.size(), 5u);
    EXPECT_EQ(a.cloud.height, 1u);
    EXPECT_EQ(a.cloud.row_step, 5u * a.cloud.point_step);
    const std::size_t step = a.cloud.point_step;
    EXPECT_EQ(0, std::memcmp(a.cloud.data.data(), whole.cloud.data.data(), 3 * step));
    EXPECT_EQ(0, std::memcmp(a.cloud.data.data() + 3 * step, b.cloud.data.data(), 2 * step));
    // another field list: nothing appended
    const Blob other = test::make_blob({{"x", F::FLOAT32}, {"id", F::UINT32}}, 2, 1,
                                       [](std::size_t, std::size_t, std::uint32_t) { return 1.0; });
    const Blob before = a;
    EXPECT_FALSE(append_points(a, other));
    EXPECT_EQ(a.cloud.data, before.cloud.data);
    EXPECT_EQ(a.size(), 5u);
    Blob empty = empty_like(b);
    ASSERT_TRUE(append_points(empty, b));
    EXPECT_EQ(empty.cloud.data, b.cloud.data);
}

TEST(Blob, KeepPointsRejectsOutOfRangeRepeatedAndUnorderedIndices) {
    for (const std::vector<std::uint32_t>& idx : {std::vector<std::uint32_t>{3}, {1, 1}, {2, 0}}) {
        Blob b = test::random_xyz(3);
        EXPECT_THROW(keep_points(b, idx), Error);
    }
}

TEST(Blob, SetFieldAppendsThenOverwritesInPlace) {
    Blob b = test::random_xyz(4);
    const Blob original = b;
    const std::vector<std::uint32_t> a = {1, 2, 3, 4}, c = {9, 8, 7, 6};
    set_field(b, "label", a);
    ASSERT_NE(find_field(b, "label"), nullptr);
    const std::size_t old_step = original.cloud.point_step;
    EXPECT_EQ(b.cloud.point_step, old_step + 4);
    EXPECT_EQ(b.cloud.row_step, 4 * (old_step + 4));
    for (std::size_t i = 0; i < 4; ++i) {  // every point moved intact to its wider slot
        EXPECT_EQ(0, std::memcmp(&b.cloud.data[i * (old_step + 4)],
                                 &original.cloud.data[i * old_step], old_step));
    }
    const std::size_t fields = b.cloud.fields.size();
    set_field(b, "label", c);
    EXPECT_EQ(b.cloud.fields.size(), fields);
    EXPECT_EQ(b.cloud.point_step, old_step + 4);
    const auto* f = find_field(b, "label");
    EXPECT_EQ(f->datatype, F::UINT32);
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(value_as_double(&b.cloud.data[i * b.cloud.point_step + f->offset], f->datatype),
                  c[i]);
    }
    EXPECT_THROW(set_field(b, "label", std::span(a).first(3)), Error);
}

TEST(Blob, RemoveFieldUndoesSetFieldAndClosesAGapInTheMiddle) {
    Blob b =
        test::make_blob({{"x", F::FLOAT32}, {"id", F::UINT16}, {"w", F::FLOAT64}}, 5, 1,
                        [](std::size_t i, std::size_t k, std::uint32_t) { return i * 10.0 + k; });
    const Blob original = b;
    set_field(b, "tmp", std::vector<std::uint32_t>{1, 2, 3, 4, 5});
    remove_field(b, "tmp");
    EXPECT_EQ(b.cloud.data, original.cloud.data);  // set then removed: the same bytes
    EXPECT_EQ(b.cloud.point_step, original.cloud.point_step);
    EXPECT_EQ(b.cloud.fields.size(), original.cloud.fields.size());
    remove_field(b, "absent");  // nothing to do
    EXPECT_EQ(b.cloud.data, original.cloud.data);
    remove_field(b, "id");  // from the middle: w moves down over it
    ASSERT_EQ(b.cloud.fields.size(), 2u);
    const auto* w = find_field(b, "w");
    ASSERT_NE(w, nullptr);
    EXPECT_EQ(b.cloud.point_step, original.cloud.point_step - 2);
    EXPECT_EQ(b.cloud.row_step, 5 * b.cloud.point_step);
    EXPECT_EQ(b.cloud.data.size(), 5u * b.cloud.point_step);
    check_layout(b);
    for (std::size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(value_as_double(&b.cloud.data[i * b.cloud.point_step + w->offset], w->datatype),
                  i * 10.0 + 2);
        EXPECT_EQ(value_as_double(&b.cloud.data[i * b.cloud.point_step], F::FLOAT32), i * 10.0);
    }
}

TEST(Blob, SetFieldGrowsWithinTheRoomReservedByTheReaders) {
    Blob b = test::random_xyz(1000);
    std::vector<std::uint8_t> exact = b.cloud.data;  // a vector with no spare room
    reserve_points(b, b.size());
    const std::uint8_t* storage = b.cloud.data.data();
    set_field(b, "label", std::vector<std::uint32_t>(1000, 7));
    EXPECT_EQ(b.cloud.data.data(), storage);
    for (std::size_t i = 0; i < 1000; ++i) {
        EXPECT_EQ(0, std::memcmp(&b.cloud.data[i * b.cloud.point_step],
                                 &exact[i * (b.cloud.point_step - 4)], b.cloud.point_step - 4));
    }
}

TEST(Blob, SetFieldReplacesFieldOfAnotherType) {
    Blob b = test::make_blob({{"x", F::FLOAT32}, {"label", F::INT16}, {"y", F::FLOAT32}}, 2, 1,
                             [](auto...) { return 1.0; });
    const std::vector<std::uint32_t> v = {5, 6};
    set_field(b, "label", v);
    EXPECT_EQ(b.cloud.fields.size(), 3u);
    EXPECT_EQ(find_field(b, "label")->datatype, F::UINT32);
    EXPECT_NE(find_field(b, "y"), nullptr);
}

TEST(Blob, IsDenseFollowsEveryFloatField) {
    Blob b =
        test::make_blob({{"x", F::FLOAT32}, {"i", F::FLOAT64}}, 3, 1, [](auto...) { return 1.0; });
    update_is_dense(b);
    EXPECT_TRUE(b.cloud.is_dense);
    const double nan = std::nan("");
    std::memcpy(&b.cloud.data[2 * b.cloud.point_step + 4], &nan, 8);
    update_is_dense(b);
    EXPECT_FALSE(b.cloud.is_dense);
}

TEST(Blob, IsDenseSeesAnInfinityFarIntoTheCloud) {
    // Past the first block of points the check works on; -Inf in a float32 element.
    Blob b = test::make_blob({{"x", F::FLOAT32}, {"y", F::FLOAT32}}, 9000, 1,
                             [](auto...) { return 0.5; });
    update_is_dense(b);
    EXPECT_TRUE(b.cloud.is_dense);
    const float inf = -std::numeric_limits<float>::infinity();
    std::memcpy(&b.cloud.data[8999 * b.cloud.point_step + 4], &inf, 4);
    update_is_dense(b);
    EXPECT_FALSE(b.cloud.is_dense);
}

}  // namespace
}  // namespace pc::io
