#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace pc::io {

/// LZF (Marc Lehmann's liblzf stream format, as in PCD binary_compressed). Greedy, 3-byte hash.
[[nodiscard]] std::vector<std::uint8_t> lzf_compress(std::span<const std::uint8_t> in);

/// Decodes `in` into exactly `out.size()` bytes. Every back-reference and literal run is bounds
/// checked; throws pc::IoError if the stream is corrupt or does not produce exactly out.size()
/// bytes.
void lzf_decompress(std::span<const std::uint8_t> in, std::span<std::uint8_t> out);

}  // namespace pc::io
