#include <cstring>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/points.h>
#include <pc/io/read.h>
#include <pc/io/sink.h>
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

TEST(Text, CloudCompareExportWithItsHeaderKeepsColoursNormalsAndScalarFields) {
    const Blob b = parse_text(
                       "//X,Y,Z,R,G,B,Nx,Ny,Nz,Scalar field,Classification\n"
                       "1.5,2,3,255,0,10,0,0,1,0.25,2\n0,0,0,1,2,3,1,0,0,7,1\n")
                       .blob;
    ASSERT_EQ(b.size(), 2u);
    std::vector<std::string> names;
    for (const auto& f : b.cloud.fields) {
        names.push_back(f.name);
    }
    EXPECT_EQ(names, (std::vector<std::string>{"x", "y", "z", "rgb", "normal_x", "normal_y",
                                               "normal_z", "scalar_field", "classification"}));
    EXPECT_EQ(find_field(b, "normal_z")->datatype, pcl::PCLPointField::FLOAT32);  // not whole
    EXPECT_EQ(find_field(b, "scalar_field")->datatype, pcl::PCLPointField::FLOAT32);
    EXPECT_EQ(find_field(b, "classification")->datatype, pcl::PCLPointField::UINT32);
    EXPECT_EQ(labels(b, "classification"), (std::vector<std::uint32_t>{2, 1}));
    EXPECT_EQ(colours(b)[0].r, 1.0f);
    EXPECT_FLOAT_EQ(colours(b)[0].b, 10.0f / 255);
    // Without the header: CloudCompare's nine columns in its order.
    const Blob nine = parse_text("1 2 3 255 0 10 0 0 1\n").blob;
    EXPECT_NE(find_field(nine, "normal_z"), nullptr);
    // Columns in another order, named by a plain first line.
    const Blob reordered = parse_text("intensity z y x\n9 3 2 1\n").blob;
    EXPECT_EQ(xyz(reordered)[0].x, 1.0f);
    EXPECT_EQ(xyz(reordered)[0].z, 3.0f);
}

TEST(Text, RefusesWhatItCannotMakeSenseOf) {
    EXPECT_THROW((void)parse_text("1 2 3 4 5\n"), IoError);             // five unnamed columns
    EXPECT_THROW((void)parse_text("x y z r g\n1 2 3 4 5\n"), IoError);  // two of r g b
    EXPECT_THROW((void)parse_text("x y z x\n1 2 3 4\n"), IoError);      // x twice
    EXPECT_THROW((void)parse_text("x y z a a\n1 2 3 4 5\n"), IoError);  // field twice
    EXPECT_THROW((void)parse_text("x y z r g b\n1 2 3 300 0 0\n"), IoError);
}

TEST(Text, WriteAndReadBackGiveTheSameCloud) {
    // x y z, packed colour, normals, a U 4 label and an F 4 field: through text and back.
    const Blob in = parse_text(
                        "x y z r g b nx ny nz label weight\n"
                        "0.1 -2.5 3e-3 255 128 0 0 0.6 0.8 7 0.5\n1 2 3 0 0 0 1 0 0 0 -1.25\n")
                        .blob;
    StringSink text;
    write_text(in, text);
    EXPECT_EQ(text.out.substr(0, text.out.find('\n')), "//X Y Z R G B Nx Ny Nz label weight");
    const Blob back = parse_text(text.out).blob;
    ASSERT_EQ(back.cloud.fields.size(), in.cloud.fields.size());
    for (std::size_t k = 0; k < in.cloud.fields.size(); ++k) {
        EXPECT_EQ(back.cloud.fields[k].name, in.cloud.fields[k].name);
        EXPECT_EQ(back.cloud.fields[k].datatype, in.cloud.fields[k].datatype);
    }
    EXPECT_EQ(back.cloud.data, in.cloud.data);  // every bit
}

}  // namespace
}  // namespace pc::io
