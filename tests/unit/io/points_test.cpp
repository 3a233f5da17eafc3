#include <cmath>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/points.h>

#include "support/synthetic.h"

namespace pc::io {
namespace {

using F = pcl::PCLPointField;

TEST(Points, XyzConvertsDoubleCoordinates) {
    const Blob b = test::make_blob({{"z", F::FLOAT64}, {"y", F::FLOAT64}, {"x", F::FLOAT64}}, 2, 1,
                                   [](std::size_t i, std::size_t k, std::uint32_t) {
                                       return static_cast<double>(10 * i + k) + 0.5;
                                   });
    const Cloud c = xyz(b);
    EXPECT_EQ(c[1].x, 12.5f);
    EXPECT_EQ(c[1].z, 10.5f);
}

TEST(Points, XyzPointsViewFloatFieldsInPlaceInAnyOrderAndConvertOthers) {
    // F 4 fields in another order with a field between: a view of the blob's own bytes.
    const Blob floats = test::make_blob(
        {{"z", F::FLOAT32}, {"id", F::UINT16}, {"x", F::FLOAT32}, {"y", F::FLOAT32}}, 3, 1,
        [](std::size_t i, std::size_t k, std::uint32_t) {
            return static_cast<double>(10 * i + k) + 0.25;
        });
    const XyzPoints view(floats);
    ASSERT_EQ(view.view().size, 3u);
    EXPECT_EQ(view.view().base, floats.cloud.data.data());
    // F 8 fields: a converted copy, the same values as xyz().
    const Blob doubles = test::make_blob({{"x", F::FLOAT64}, {"y", F::FLOAT64}, {"z", F::FLOAT64}},
                                         3, 1, [](std::size_t i, std::size_t k, std::uint32_t) {
                                             return static_cast<double>(10 * i + k) + 0.25;
                                         });
    XyzPoints copy(doubles);
    EXPECT_NE(copy.view().base, doubles.cloud.data.data());
    for (const auto& [blob, points] :
         {std::pair<const Blob*, const XyzPoints*>{&floats, &view}, {&doubles, &copy}}) {
        const Cloud expected = xyz(*blob);
        for (std::size_t i = 0; i < 3; ++i) {
            const pcl::PointXYZ p = points->view()[i];
            EXPECT_EQ(p.x, expected[i].x);
            EXPECT_EQ(p.y, expected[i].y);
            EXPECT_EQ(p.z, expected[i].z);
        }
    }
    EXPECT_THROW(XyzPoints(test::make_blob({{"x", F::FLOAT32}}, 1, 1, [](auto...) { return 0.0; })),
                 IoError);
}

TEST(Points, XyzWithoutCoordinatesIsAnError) {
    EXPECT_THROW((void)xyz(test::make_blob({{"x", F::FLOAT32}}, 1, 1, [](auto...) { return 0.0; })),
                 IoError);
}

TEST(Points, ColoursFromPackedAndSeparateFields) {
    Blob packed = test::make_blob({{"x", F::FLOAT32}, {"rgb", F::FLOAT32}}, 1, 1,
                                  [](auto...) { return 0.0; });
    test::set_bits(packed, 0, 1, 0xFFFF8000u);  // NaN as a float: bits must be read, not the value
    const auto a = colours(packed);
    EXPECT_FLOAT_EQ(a[0].r, 1.0f);
    EXPECT_FLOAT_EQ(a[0].g, 128 / 255.0f);
    EXPECT_FLOAT_EQ(a[0].b, 0.0f);
    const Blob bytes =
        test::make_blob({{"r", F::UINT8}, {"g", F::UINT8}, {"b", F::UINT8}}, 1, 1,
                        [](std::size_t, std::size_t k, std::uint32_t) { return k * 100.0; });
    EXPECT_FLOAT_EQ(colours(bytes)[0].b, 200 / 255.0f);
    const Blob reals =
        test::make_blob({{"red", F::FLOAT32}, {"green", F::FLOAT32}, {"blue", F::FLOAT32}}, 1, 1,
                        [](auto...) { return 0.25; });
    EXPECT_FLOAT_EQ(colours(reals)[0].g, 0.25f);
    EXPECT_THROW((void)colours(test::random_xyz(2)), IoError);
}

TEST(Points, LabelsRejectNegativeAndRealValues) {
    EXPECT_THROW(
        (void)labels(test::make_blob({{"label", F::INT32}}, 1, 1, [](auto...) { return -1.0; })),
        IoError);
    EXPECT_THROW(
        (void)labels(test::make_blob({{"label", F::FLOAT32}}, 1, 1, [](auto...) { return 1.0; })),
        IoError);
    EXPECT_EQ(labels(test::make_blob({{"label", F::UINT16}}, 1, 1, [](auto...) { return 7.0; }))[0],
              7u);
}

TEST(Points, AggregateAveragesRealsAndColourAndVotesIntegers) {
    Blob b = test::make_blob({{"x", F::FLOAT32}, {"rgb", F::UINT32}, {"label", F::UINT32}}, 4, 1,
                             [](std::size_t i, std::size_t k, std::uint32_t) {
                                 const double label[] = {7, 3, 3, 9};
                                 return k == 0 ? static_cast<double>(i) : k == 1 ? 0.0 : label[i];
                             });
    test::set_bits(b, 0, 1, 0x00FF0000u);
    test::set_bits(b, 1, 1, 0x00000000u);
    test::set_bits(b, 2, 1, 0x000000FFu);
    const std::vector<std::uint32_t> group = {0, 0, 0, kNoGroup};
    const Blob out = aggregate(b, group, 1);
    ASSERT_EQ(out.size(), 1u);
    float x;
    std::uint32_t rgb, label;
    std::memcpy(&x, &out.cloud.data[0], 4);
    std::memcpy(&rgb, &out.cloud.data[4], 4);
    std::memcpy(&label, &out.cloud.data[8], 4);
    EXPECT_EQ(x, 1.0f);           // (0 + 1 + 2) / 3
    EXPECT_EQ(rgb, 0x00550055u);  // red 255/3 = 85, blue 85
    EXPECT_EQ(label, 3u);         // 3 twice, 7 once
}

TEST(Points, AggregateVotesSignedAndWideIntegersTiesToTheSmallest) {
    // Per group the most frequent value, ties to the smallest, for I 1, I 4 (negative values
    // packed beside the group must still order as numbers) and I 8 (the pair path).
    const double a[] = {-5, -5, 3, 3, -128, 7, 7, 7, 100, -100};
    Blob b = test::make_blob(
        {{"s8", F::INT8}, {"s32", F::INT32}, {"s64", F::INT64}}, 10, 1,
        [&](std::size_t i, std::size_t k, std::uint32_t) { return k == 1 ? a[i] * 1000 : a[i]; });
    // Group 0: -5, -5, 3, 3 (tie: -5); group 1: -128, 7, 7, 7 (7); group 2: 100, -100 (tie: -100).
    const std::vector<std::uint32_t> group = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2};
    const Blob out = aggregate(b, group, 3);
    const double expected[] = {-5, 7, -100};
    for (std::uint32_t g = 0; g < 3; ++g) {
        const std::uint8_t* p = &out.cloud.data[g * out.cloud.point_step];
        std::int8_t s8;
        std::int32_t s32;
        std::int64_t s64;
        std::memcpy(&s8, p, 1);
        std::memcpy(&s32, p + 1, 4);
        std::memcpy(&s64, p + 5, 8);
        EXPECT_EQ(s8, expected[g]) << "group " << g;
        EXPECT_EQ(s32, expected[g] * 1000) << "group " << g;
        EXPECT_EQ(s64, expected[g]) << "group " << g;
    }
}

}  // namespace
}  // namespace pc::io
