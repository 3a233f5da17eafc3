#include <cstring>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/read.h>
#include <pc/io/text.h>

namespace pc::io {
namespace {

std::uint32_t rgb_of(const Blob& b, std::size_t i) {
    std::uint32_t v;
    std::memcpy(&v, &b.cloud.data[i * b.cloud.point_step + find_field(b, "rgb")->offset], 4);
    return v;
}

TEST(Text, ThreeColumnsAreXyz) {
    const Blob b = parse_text("1 2 3\n4\t5\t6\n\n# c\n7,8,9\n").blob;
    ASSERT_EQ(b.size(), 3u);
    float v[3];
    std::memcpy(v, &b.cloud.data[2 * b.cloud.point_step], 12);
    EXPECT_EQ(v[2], 9.0f);
}

TEST(Text, IntegerColoursAreBytes) {
    const Blob b = parse_text("//X Y Z R G B\n0 0 0 255 128 0\n").blob;
    EXPECT_EQ(rgb_of(b, 0), 0xFF8000u);
}

TEST(Text, RealColoursAreZeroToOne) {
    const Blob b = parse_text("0 0 0 1.0 0.5 0\n").blob;
    EXPECT_EQ(rgb_of(b, 0), 0xFF8000u);
}

TEST(Text, FourthColumnIsIntensity) {
    const Blob b = parse_text("0 0 0 0.25\n").blob;
    ASSERT_NE(find_field(b, "intensity"), nullptr);
}

TEST(Text, IsRecognisedByContent) {
    EXPECT_EQ(parse_cloud("x y z\n1 2 3\n").format, "xyz text");
    EXPECT_EQ(parse_cloud("-1.5e3 2 3\n").format, "xyz text");
}

}  // namespace
}  // namespace pc::io
