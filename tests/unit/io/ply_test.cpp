#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/ply.h>
#include <pc/io/text.h>

#include "support/corpus.h"

namespace pc::io {
namespace {

using F = pcl::PCLPointField;

template <class T>
void put(std::string& s, T v, bool big_endian = false) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof v);
    if (big_endian) {
        std::reverse(b, b + sizeof v);
    }
    s.append(b, sizeof v);
}

template <class T>
T get(const Blob& b, std::size_t i, const std::string& name, std::size_t element = 0) {
    const auto* f = find_field(b, name);
    EXPECT_NE(f, nullptr) << name;
    T v{};
    if (f != nullptr) {
        std::memcpy(&v, &b.cloud.data[i * b.cloud.point_step + f->offset + element * sizeof(T)],
                    sizeof v);
    }
    return v;
}

/// What Open3D's write_point_cloud (and so nerfstudio's ns-export) writes.
std::string open3d_ply(bool big_endian = false) {
    std::string s = "ply\nformat " +
                    std::string(big_endian ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\ncomment Created by Open3D\nelement vertex 2\nproperty double x\n"
                    "property double y\nproperty double z\nproperty double nx\nproperty double ny\n"
                    "property double nz\nproperty uchar red\nproperty uchar green\n"
                    "property uchar blue\nend_header\n";
    const double rows[2][6] = {{0.123456789012345, -1.5, 2e-9, 0, 0, 1},
                               {1e6 + 0.25, 3, -4, 1, 0, 0}};
    const std::uint8_t colours[2][3] = {{255, 128, 0}, {1, 2, 3}};
    for (int i = 0; i < 2; ++i) {
        for (double v : rows[i]) {
            put(s, v, big_endian);
        }
        s.append(reinterpret_cast<const char*>(colours[i]), 3);
    }
    return s;
}

TEST(Ply, Open3dDoublePlyKeepsExactCoordinatesAndPacksColour) {
    for (bool be : {false, true}) {
        const ReadResult r = parse_ply(open3d_ply(be));
        const Blob& b = r.blob;
        ASSERT_EQ(b.size(), 2u);
        EXPECT_EQ(find_field(b, "x")->datatype, F::FLOAT64);
        EXPECT_EQ(get<double>(b, 0, "x"), 0.123456789012345);
        EXPECT_EQ(get<double>(b, 1, "x"), 1e6 + 0.25);
        EXPECT_EQ(get<double>(b, 1, "z"), -4.0);
        EXPECT_EQ(get<double>(b, 0, "normal_z"), 1.0);
        EXPECT_EQ(find_field(b, "rgb")->datatype, F::UINT32);
        EXPECT_EQ(get<std::uint32_t>(b, 0, "rgb"), 0xFF8000u);
        EXPECT_EQ(get<std::uint32_t>(b, 1, "rgb"), 0x010203u);
        EXPECT_EQ(find_field(b, "red"), nullptr);
    }
}

TEST(Ply, AsciiWithFacesSkipsTheFaces) {
    const std::string s =
        "ply\r\nformat ascii 1.0\r\ncomment x\r\nelement vertex 3\r\nproperty float x\r\n"
        "property float y\r\nproperty float z\r\nproperty uchar red\r\nproperty uchar green\r\n"
        "property uchar blue\r\nproperty uchar alpha\r\nelement face 1\r\n"
        "property list uchar int vertex_indices\r\nend_header\r\n"
        "0 0 0 10 20 30 40\r\n1 0 0 0 0 0 255\r\n0 1 0 1 1 1 1\r\n3 0 1 2\r\n";
    const Blob b = parse_ply(s).blob;
    ASSERT_EQ(b.size(), 3u);
    EXPECT_EQ(get<std::uint32_t>(b, 0, "rgba"), 0x280A141Eu);
    EXPECT_EQ(get<float>(b, 1, "x"), 1.0f);
}

TEST(Ply, BinaryFacesAfterVerticesAreWalked) {
    std::string s = test::ply_header("binary_little_endian", "1",
                                     "property float x\nproperty float y\nproperty float z\n");
    s.insert(s.find("end_header"), "element face 2\nproperty list uchar int vertex_indices\n");
    s += test::floats({1, 2, 3});
    for (int face = 0; face < 2; ++face) {
        s += '\x03';
        for (int k = 0; k < 3; ++k) {
            put<std::int32_t>(s, 0);
        }
    }
    EXPECT_EQ(parse_ply(s).blob.size(), 1u);
    EXPECT_THROW((void)parse_ply(s + "x"), IoError);
    EXPECT_THROW((void)parse_ply(s.substr(0, s.size() - 1)), IoError);
}

TEST(Ply, VerticesAfterAnotherElementAreBoundedByTheBytesLeft) {
    // The body holds as many bytes as the vertices alone need (the first bound), but an element
    // before them takes some: the vertex rows would be read past the end (a fuzzer's find,
    // caught by AddressSanitizer).
    const std::string header =
        "ply\nformat binary_little_endian 1.0\nelement extra 2\nproperty float a\n"
        "element vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
        "end_header\n";
    const std::string whole = header + test::floats({9, 9, 1, 2, 3, 4, 5, 6});
    const Blob b = parse_ply(whole).blob;
    ASSERT_EQ(b.size(), 2u);
    EXPECT_EQ(get<float>(b, 1, "z"), 6.0f);
    try {
        (void)parse_ply(header + test::floats({9, 9, 1, 2, 3, 4}));
        ADD_FAILURE() << "a truncated body was read";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    }
}

TEST(Ply, GaussianSplattingKeepsAllAttributesAndDerivesColour) {
    std::vector<std::string> names = {"x",  "y",      "z",      "nx",    "ny",
                                      "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
    for (int k = 0; k < 45; ++k) {
        names.push_back("f_rest_" + std::to_string(k));
    }
    for (const char* n :
         {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"}) {
        names.push_back(n);
    }
    ASSERT_EQ(names.size(), 62u);
    std::string props;
    for (const auto& n : names) {
        props += "property float " + n + "\n";
    }
    std::string s = test::ply_header("binary_little_endian", "1", props);
    const float c0 = 0.28209479177387814f;
    for (std::size_t k = 0; k < names.size(); ++k) {
        const float v = names[k] == "f_dc_0"   ? 0.5f / c0
                        : names[k] == "f_dc_1" ? -0.5f / c0
                        : names[k] == "f_dc_2" ? 0.0f
                                               : static_cast<float>(k) * 0.25f;
        put(s, v);
    }
    const Blob b = parse_ply(s).blob;
    EXPECT_EQ(b.cloud.fields.size(), 63u);  // 62 properties + derived rgb
    EXPECT_EQ(get<float>(b, 0, "opacity"), 54 * 0.25f);
    EXPECT_EQ(get<float>(b, 0, "f_rest_44"), 53 * 0.25f);
    EXPECT_EQ(get<std::uint32_t>(b, 0, "rgb"), 0xFF0080u);  // r = 1, g = 0, b = 0.5 -> 128
}

TEST(Ply, WriteThenReadKeepsFieldsAndColour) {
    const Blob in = parse_ply(open3d_ply()).blob;
    for (bool binary : {true, false}) {
        StringSink sink;
        write_ply(in, binary, sink);
        EXPECT_NE(sink.out.find("property uchar red"), std::string::npos);
        EXPECT_NE(sink.out.find("property double nx"), std::string::npos);
        const Blob out = parse_ply(sink.out).blob;
        EXPECT_EQ(out.cloud.data, in.cloud.data);
        EXPECT_EQ(out.cloud.fields.size(), in.cloud.fields.size());
    }
}

TEST(Ply, ScalarPrefixForCloudCompareRoundTrips) {
    // x y z, colour, normals stay; a label and an intensity: CloudCompare loads `scalar_label`
    // (and intensity) as scalar fields by itself; reading strips the prefix again.
    const Blob in =
        parse_text("x y z r g b nx ny nz label intensity\n1 2 3 255 0 0 0 0 1 7 0.5\n").blob;
    StringSink sink;
    write_ply(in, true, sink, true);
    EXPECT_NE(sink.out.find("property uint scalar_label\n"), std::string::npos) << sink.out;
    EXPECT_NE(sink.out.find("property float intensity\n"), std::string::npos);
    EXPECT_NE(sink.out.find("property float nx\n"), std::string::npos);
    EXPECT_EQ(sink.out.find("scalar_x"), std::string::npos);
    const Blob back = parse_ply(sink.out).blob;
    EXPECT_EQ(back.cloud.data, in.cloud.data);
    ASSERT_NE(find_field(back, "label"), nullptr);
    // A file with both label and scalar_label keeps both names.
    const Blob both = parse_ply(test::ply_header("ascii", "1",
                                                 "property float x\nproperty float y\n"
                                                 "property float z\nproperty uint label\n"
                                                 "property uint scalar_label\n") +
                                "0 0 0 1 2\n")
                          .blob;
    EXPECT_NE(find_field(both, "scalar_label"), nullptr);
}

TEST(Ply, EmptyVertexElementIsAnEmptyCloud) {
    EXPECT_EQ(parse_ply(test::ply_header("ascii", "0",
                                         "property float x\nproperty float y\n"
                                         "property float z\n"))
                  .blob.size(),
              0u);
}

}  // namespace
}  // namespace pc::io
