#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>
#include <thread>

#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/pcd.h>
#include <pc/io/read.h>

#include "support/corpus.h"
#include "support/synthetic.h"

namespace pc::io {
namespace {

using F = pcl::PCLPointField;

/// Every datatype with COUNT 1 and 3, padding, non-finite floats, rgb with a NaN bit pattern,
/// organised 3 x 2, a non-default viewpoint.
Blob every_type_cloud() {
    std::vector<test::FieldSpec> specs = {{"x", F::FLOAT32},
                                          {"y", F::FLOAT32},
                                          {"z", F::FLOAT32},
                                          {"rgb", F::FLOAT32},
                                          {"_", F::UINT8, 3}};
    const std::uint8_t types[] = {F::INT8,   F::UINT8, F::INT16,  F::UINT16,  F::INT32,
                                  F::UINT32, F::INT64, F::UINT64, F::FLOAT32, F::FLOAT64};
    for (std::uint8_t t : types) {
        specs.push_back({"t" + std::to_string(int{t}), t, 1});
        specs.push_back({"v" + std::to_string(int{t}), t, 3});
    }
    Blob b = test::make_blob(specs, 3, 2, [](std::size_t i, std::size_t k, std::uint32_t c) {
        const double base = (static_cast<double>(i) - 2.5) * 37.25 + k * 1.125 + c;
        return k < 3 ? base * 0.1 + 1e-7 * static_cast<double>(k) : base;
    });
    // A float with all mantissa bits, a subnormal, NaN and infinities.
    const float specials[] = {0.1f,
                              std::numeric_limits<float>::denorm_min(),
                              std::numeric_limits<float>::quiet_NaN(),
                              std::numeric_limits<float>::infinity(),
                              -std::numeric_limits<float>::infinity(),
                              3.4028235e38f};
    for (std::size_t i = 0; i < 6; ++i) {
        std::memcpy(&b.cloud.data[i * b.cloud.point_step + 4], &specials[i], 4);
    }
    test::set_bits(b, 0, 3, 0xFFFFFFFFu);  // white with alpha: a NaN when read as float
    test::set_bits(b, 1, 3, 0xFF7F0001u);
    b.viewpoint = {1.5f, -2, 3, 0.5f, 0.5f, 0.5f, 0.5f};
    update_is_dense(b);
    return b;
}

std::string field_bytes(const Blob& b, const std::string& name) {
    const auto* f = find_field(b, name);
    if (f == nullptr) {
        return "<missing>";
    }
    const std::size_t fs = type_size(f->datatype) * f->count;
    std::string out;
    for (std::size_t i = 0; i < b.size(); ++i) {
        out.append(reinterpret_cast<const char*>(&b.cloud.data[i * b.cloud.point_step + f->offset]),
                   fs);
    }
    return out;
}

Blob round_trip(const Blob& b, PcdEncoding e) {
    StringSink sink;
    write_pcd(b, e, sink);
    return parse_pcd(sink.out).blob;
}

class PcdRoundTrip : public ::testing::TestWithParam<PcdEncoding> {};

TEST_P(PcdRoundTrip, EveryFieldComesBackBitIdentical) {
    const Blob in = every_type_cloud();
    const Blob out = round_trip(in, GetParam());
    EXPECT_EQ(out.cloud.width, 3u);
    EXPECT_EQ(out.cloud.height, 2u);
    EXPECT_EQ(out.viewpoint, in.viewpoint);
    EXPECT_EQ(out.cloud.is_dense, in.cloud.is_dense);
    for (const auto& f : in.cloud.fields) {
        if (f.name == "_") {
            continue;
        }
        const auto* g = find_field(out, f.name);
        ASSERT_NE(g, nullptr) << f.name;
        EXPECT_EQ(g->count, f.count) << f.name;
        EXPECT_EQ(g->datatype, f.name == "rgb" ? std::uint8_t{F::UINT32} : f.datatype) << f.name;
        EXPECT_EQ(field_bytes(out, f.name), field_bytes(in, f.name)) << f.name;
    }
    if (GetParam() != PcdEncoding::kBinaryCompressed) {  // layout, padding included, is kept
        EXPECT_EQ(out.cloud.point_step, in.cloud.point_step);
        EXPECT_EQ(out.cloud.data, in.cloud.data);
    }
}

TEST_P(PcdRoundTrip, EmptyCloudStaysEmpty) {
    Blob in = test::random_xyz(0);
    const Blob out = round_trip(in, GetParam());
    EXPECT_EQ(out.size(), 0u);
    EXPECT_EQ(out.cloud.fields.size(), 3u);
}

TEST_P(PcdRoundTrip, LargeCloudRoundTrips) {
    const Blob in = test::random_xyz(100000, 9);
    EXPECT_EQ(round_trip(in, GetParam()).cloud.data, in.cloud.data);
}

INSTANTIATE_TEST_SUITE_P(Encodings,
                         PcdRoundTrip,
                         ::testing::Values(PcdEncoding::kAscii,
                                           PcdEncoding::kBinary,
                                           PcdEncoding::kBinaryCompressed),
                         [](const auto& p) {
                             return p.param == PcdEncoding::kAscii    ? std::string("Ascii")
                                    : p.param == PcdEncoding::kBinary ? std::string("Binary")
                                                                      : std::string("Compressed");
                         });

TEST(Pcd, BinaryStartComesFromACompleteHeaderOnly) {
    const auto total = [](std::string_view prefix) -> std::optional<std::uint64_t> {
        const auto s = start_binary_pcd(prefix);
        return s ? std::optional<std::uint64_t>(s->body_offset + s->body_bytes) : std::nullopt;
    };
    const std::string header =
        "VERSION .7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\n"
        "WIDTH 1000\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1000\nDATA binary\n";
    EXPECT_EQ(total(header), header.size() + 1000u * 16u);
    EXPECT_EQ(total(header + std::string(100, '\0')), header.size() + 1000u * 16u);
    EXPECT_FALSE(total(header.substr(0, header.size() - 8)));  // DATA line not yet in
    std::string ascii = header;
    ascii.replace(ascii.find("DATA binary"), 11, "DATA ascii");
    EXPECT_FALSE(total(ascii));
    std::string lying = header;
    lying.replace(lying.find("POINTS 1000"), 11, "POINTS 7");  // WIDTH x HEIGHT says 1000
    EXPECT_FALSE(total(lying));
}

/// read_cloud() of `bytes` given as a FIFO (written by another thread) or as a file: the cloud or
/// the error message.
std::string read_through(const std::string& bytes, bool fifo, Blob* out) {
    char dir[] = "/tmp/pc_pcd_pipe_XXXXXX";
    EXPECT_NE(::mkdtemp(dir), nullptr);
    const std::string path = std::string(dir) + "/in.pcd";
    std::thread writer;
    if (fifo) {
        EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0);
        writer = std::thread([&] {
            if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
                (void)std::fwrite(bytes.data(), 1, bytes.size(), f);  // EPIPE ignored
                std::fclose(f);
            }
        });
    } else {
        std::ofstream(path, std::ios::binary) << bytes;
    }
    std::string error;
    try {
        *out = read_cloud(path).blob;
    } catch (const IoError& e) {
        error = e.what();
    }
    if (writer.joinable()) {
        writer.join();
    }
    std::remove(path.c_str());
    ::rmdir(dir);
    return error;
}

TEST(Pcd, ABinaryCloudReadFromAPipeOrAFileEqualsTheParsedBytes) {
    std::signal(SIGPIPE, SIG_IGN);
    Blob b = test::random_xyz(300000);  // 3.6 MB: several reads of the pipe
    StringSink sink;
    write_pcd(b, PcdEncoding::kBinary, sink);
    const std::string whole = sink.out;
    const std::size_t header = whole.size() - b.cloud.data.size();
    std::string lying = whole.substr(0, header);
    for (const char* key : {"WIDTH 300000", "POINTS 300000"}) {
        lying.replace(lying.find(key), std::string(key).size(),
                      std::string(key).substr(0, 6) + "90000000");
    }
    for (const std::string& bytes : {whole, whole + "xyz", whole.substr(0, whole.size() - 7), lying,
                                     whole.substr(0, header - 3)}) {
        std::string expected_error;
        ReadResult expected;
        try {
            expected = parse_cloud(bytes);
        } catch (const IoError& e) {
            expected_error = e.what();
        }
        for (const bool fifo : {true, false}) {
            Blob got;
            const std::string error = read_through(bytes, fifo, &got);
            if (expected_error.empty()) {
                EXPECT_EQ(error, "") << (fifo ? "fifo" : "file");
                EXPECT_EQ(got.cloud.data, expected.blob.cloud.data);
                EXPECT_EQ(got.size(), expected.blob.size());
                EXPECT_EQ(got.cloud.fields.size(), expected.blob.cloud.fields.size());
            } else {  // the same problem, named after the input
                EXPECT_NE(error.find(expected_error), std::string::npos)
                    << error << " vs " << expected_error;
            }
        }
    }
}

TEST(Pcd, GapsBetweenFieldsBecomePaddingFields) {
    Blob b = test::random_xyz(2);
    b.cloud.point_step = 16;  // PointXYZ layout: 4 bytes of padding after z
    b.cloud.data.resize(32);
    StringSink sink;
    write_pcd(b, PcdEncoding::kBinary, sink);
    EXPECT_NE(sink.out.find("FIELDS x y z _\nSIZE 4 4 4 1\nTYPE F F F U\nCOUNT 1 1 1 4\n"),
              std::string::npos);
    EXPECT_EQ(parse_pcd(sink.out).blob.cloud.point_step, 16u);
}

TEST(Pcd, EdgeCasesLoadWithTheirPointCount) {
    for (const auto& e : test::edge_corpus()) {
        if (e.name.rfind("text_", 0) == 0) {
            continue;
        }
        ReadResult r;
        ASSERT_NO_THROW(r = parse_pcd(e.bytes)) << e.name;
        EXPECT_EQ(r.blob.size(), e.points) << e.name;
    }
}

TEST(Pcd, BinaryBodySpellingDataReadsTheFloat) {
    for (const auto& e : test::edge_corpus()) {
        if (e.name == "binary_spelling_DATA") {
            const Blob b = parse_pcd(e.bytes).blob;
            float x;
            std::memcpy(&x, b.cloud.data.data(), 4);
            EXPECT_EQ(x, 13.265934f);
        }
    }
}

TEST(Pcd, AsciiReadsNanAndInfinity) {
    const Blob b = parse_pcd(test::xyz_header("1", "ascii") + "nan -inf +1.5\n").blob;
    float v[3];
    std::memcpy(v, b.cloud.data.data(), 12);
    EXPECT_TRUE(std::isnan(v[0]));
    EXPECT_EQ(v[1], -std::numeric_limits<float>::infinity());
    EXPECT_EQ(v[2], 1.5f);
    EXPECT_FALSE(b.cloud.is_dense);
}

TEST(Pcd, TrailingBytesAreANoteNotAnError) {
    const ReadResult r =
        parse_pcd(test::xyz_header("1", "binary") + test::floats({1, 2, 3}) + "xx");
    ASSERT_EQ(r.notes.size(), 1u);
    EXPECT_NE(r.notes[0].find("2 trailing bytes"), std::string::npos);
}

TEST(Pcd, TruncationMessageGivesTheNumbers) {
    try {
        (void)parse_pcd(test::xyz_header("100", "binary") + std::string(600, '\0'));
        FAIL();
    } catch (const IoError& e) {
        EXPECT_STREQ(e.what(),
                     "truncated binary body: header declares 100 points x 12 B = 1200 B, 600 B "
                     "present");
    }
}

}  // namespace
}  // namespace pc::io
