#include <algorithm>
#include <cstring>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include <pc/core/radix_sort.h>

#include "support/clouds.h"

namespace pc {
namespace {

TEST(RadixSort, PermuteRecordsMovesWholeRecordsToTheirPlaces) {
    const Cloud c = test::uniform(70000, 1.0f, 35);
    std::vector<std::uint32_t> to(c.size());
    std::iota(to.begin(), to.end(), 0u);
    std::shuffle(to.begin(), to.end(), std::mt19937(5));
    for (const std::size_t stride : {12u, 16u, 20u, 44u}) {
        std::vector<std::uint8_t> bytes = test::records_of(c, stride);
        const std::vector<std::uint8_t> original = bytes;
        std::vector<std::uint32_t> places = to;
        XyzRecords records{bytes.data(), stride, c.size(), 0};
        permute_records(records, places);
        for (std::size_t i = 0; i < c.size(); ++i) {
            ASSERT_EQ(0, std::memcmp(&bytes[to[i] * stride], &original[i * stride], stride))
                << "stride " << stride << ", record " << i;
        }
        EXPECT_TRUE(std::is_sorted(places.begin(), places.end()));
    }
    // An array of 4-byte values, as records of one word.
    std::vector<std::uint32_t> values(c.size()), places = to;
    std::iota(values.begin(), values.end(), 0u);
    permute_records(values.data(), sizeof(std::uint32_t), places);
    for (std::size_t i = 0; i < c.size(); ++i) {
        ASSERT_EQ(values[to[i]], i);
    }
    EXPECT_THROW(permute_records(values.data(), 6, places), std::logic_error);
    std::vector<std::uint8_t> bytes = test::records_of(c, 16);
    std::vector<std::uint32_t> short_places(c.size() - 1);
    XyzRecords too_many{bytes.data(), 16, c.size(), 0};
    EXPECT_THROW(permute_records(too_many, short_places), std::logic_error);
}

TEST(RadixSort, FlagSortWithTagsOrdersByKeyLikeAStableSortUpToTies) {
    // Repeated keys (the grid's cell keys), 32- and 64-bit, more records than a cached bucket:
    // the keys come out ascending and every record stays with its key and tag.
    std::mt19937_64 rng(7);
    for (const int bits : {10, 40}) {
        const std::size_t n = 50000;
        std::vector<std::uint64_t> keys(n);
        std::vector<std::uint32_t> tags(n), words(2 * n);
        for (std::size_t i = 0; i < n; ++i) {
            keys[i] = rng() >> (64 - bits);
            tags[i] = static_cast<std::uint32_t>(i);
            words[2 * i] = static_cast<std::uint32_t>(i);
            words[2 * i + 1] = static_cast<std::uint32_t>(keys[i]);
        }
        const std::vector<std::uint64_t> original = keys;
        flag_sort(reinterpret_cast<std::uint8_t*>(words.data()), 8, keys.data(), tags.data(), n);
        EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
        for (std::size_t s = 0; s < n; ++s) {
            ASSERT_EQ(words[2 * s], tags[s]);       // the record moved with its tag
            ASSERT_EQ(original[tags[s]], keys[s]);  // and with its key
            ASSERT_EQ(words[2 * s + 1], static_cast<std::uint32_t>(keys[s]));
        }
    }
}

TEST(RadixSort, PairsAreSortedStably) {
    // LSD radix: equal keys keep their input order (the grid's copy relies on it), also on
    // two threads (2^16 pairs and more).
    std::mt19937 rng(3);
    const std::size_t n = 100000;
    std::vector<std::uint32_t> keys(n), idx(n), k2(n), i2(n);
    for (std::size_t i = 0; i < n; ++i) {
        keys[i] = rng() % 5000;
        idx[i] = static_cast<std::uint32_t>(i);
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> want(n);
    for (std::size_t i = 0; i < n; ++i) {
        want[i] = {keys[i], idx[i]};
    }
    std::stable_sort(want.begin(), want.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    const auto [sorted, order] = radix_sort_pairs(keys.data(), idx.data(), k2.data(), i2.data(), n);
    for (std::size_t i = 0; i < n; ++i) {
        ASSERT_EQ(sorted[i], want[i].first) << i;
        ASSERT_EQ(order[i], want[i].second) << i;
    }
}

}  // namespace
}  // namespace pc
