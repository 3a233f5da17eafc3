#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <pc/io/blob.h>

namespace pc::io {

/// Upper bound on the bytes read from one input, so an endless device cannot hang a tool.
inline constexpr std::uint64_t kDefaultMaxInputBytes = std::uint64_t{16} << 30;

/// A parsed input: the cloud, what it was ("pcd binary", "ply binary_little_endian", "xyz text"),
/// and notes about tolerated oddities (trailing bytes, legacy headers) for `-v`.
struct ReadResult {
    Blob blob;
    std::string format;
    std::vector<std::string> notes;
};

/// Parses PCD (ascii, binary, binary_compressed), PLY (ascii, binary LE/BE) or XYZ text,
/// recognised by content. Every header value is checked against the bytes present before
/// anything is allocated. Throws pc::IoError with the problem and its numbers.
[[nodiscard]] ReadResult parse_cloud(std::string_view bytes);

/// Reads `path` ("-" = standard input) and parses it as parse_cloud() does, with errors prefixed
/// by the input's name (`<stdin>` for "-"). Directories and block devices are refused up front, and
/// inputs above `max_bytes`. A binary PCD's body is read straight into the cloud (one copy in
/// memory); anything else is mapped (a regular file) or buffered (a pipe), then parsed.
[[nodiscard]] ReadResult read_cloud(const std::string& path,
                                    std::uint64_t max_bytes = kDefaultMaxInputBytes);

/// The name used for `path` in messages: the path itself, or "<stdin>" for "-".
[[nodiscard]] std::string display_name(const std::string& path);

}  // namespace pc::io
