#include <random>

#include <gtest/gtest.h>
#include <pcl/io/lzf.h>

#include <pc/core/error.h>
#include <pc/io/lzf.h>

namespace pc::io {
namespace {

std::vector<std::uint8_t> sample(std::size_t n, int alphabet, unsigned seed) {
    std::mt19937 rng(seed);
    std::vector<std::uint8_t> v(n);
    for (auto& b : v) {
        b = static_cast<std::uint8_t>(rng() % alphabet);
    }
    return v;
}

TEST(Lzf, RoundTripsRandomAndRepetitiveData) {
    for (const auto& [n, alphabet] : {std::pair{0, 2},
                                      {1, 2},
                                      {2, 256},
                                      {3, 3},
                                      {1000, 256},
                                      {100000, 2},
                                      {100000, 256},
                                      {300000, 1}}) {
        const auto in = sample(n, alphabet, 42);
        const auto packed = lzf_compress(in);
        std::vector<std::uint8_t> out(in.size());
        lzf_decompress(packed, out);
        EXPECT_EQ(out, in) << "n=" << n << " alphabet=" << alphabet;
    }
}

TEST(Lzf, RepetitiveDataShrinks) {
    const auto in = sample(100000, 1, 1);
    EXPECT_LT(lzf_compress(in).size(), in.size() / 20);
}

TEST(Lzf, PclDecodesOurStream) {  // the format PCL's binary_compressed reader expects
    const auto in = sample(50000, 4, 3);
    const auto packed = lzf_compress(in);
    std::vector<std::uint8_t> out(in.size());
    const unsigned got = pcl::lzfDecompress(packed.data(), static_cast<unsigned>(packed.size()),
                                            out.data(), static_cast<unsigned>(out.size()));
    EXPECT_EQ(got, in.size());
    EXPECT_EQ(out, in);
}

TEST(Lzf, WeDecodePclStream) {
    const auto in = sample(50000, 5, 4);
    std::vector<std::uint8_t> packed(in.size() * 2 + 64);
    const unsigned n = pcl::lzfCompress(in.data(), static_cast<unsigned>(in.size()), packed.data(),
                                        static_cast<unsigned>(packed.size()));
    ASSERT_GT(n, 0u);
    packed.resize(n);
    std::vector<std::uint8_t> out(in.size());
    lzf_decompress(packed, out);
    EXPECT_EQ(out, in);
}

TEST(Lzf, RejectsCorruptStreams) {
    std::vector<std::uint8_t> out(16);
    const std::vector<std::vector<std::uint8_t>> bad = {
        {0x05, 1, 2},           // literal run of 6 with 2 bytes present
        {0x00, 7, 0x20, 0x05},  // back-reference 6 bytes back after 1 byte of output
        {0xe0},                 // long match without its length byte
        {0x20},                 // match without its offset byte
        {0x0f, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 0x00, 1},  // 17 B > 16 B
        {0x00, 1},  // decodes to 1 B, 16 B declared
    };
    for (const auto& stream : bad) {
        EXPECT_THROW(lzf_decompress(stream, out), IoError);
    }
}

}  // namespace
}  // namespace pc::io
