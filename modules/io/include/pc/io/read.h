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

/// All bytes of one input, held without copying or zero-filling: a read-only mapping of a regular
/// file, or a heap buffer filled from a pipe. Move-only.
class InputBytes {
public:
    InputBytes() = default;
    InputBytes(InputBytes&& other) noexcept;
    InputBytes& operator=(InputBytes&& other) noexcept;
    InputBytes(const InputBytes&) = delete;
    InputBytes& operator=(const InputBytes&) = delete;
    ~InputBytes();
    [[nodiscard]] std::string_view view() const { return {data_, size_}; }

private:
    friend struct InputReader;  // read.cpp: fills the buffer
    void release();
    char* data_ = nullptr;
    std::size_t size_ = 0;
    std::size_t capacity_ = 0;  // of a heap buffer
    bool mapped_ = false;
};

/// All bytes of `path` ("-" = standard input). Rejects directories and block devices up front,
/// and inputs above `max_bytes`. Messages do not name the input; the caller adds it.
/// Throws pc::IoError.
[[nodiscard]] InputBytes read_all(const std::string& path, std::uint64_t max_bytes);

/// Parses PCD (ascii, binary, binary_compressed), PLY (ascii, binary LE/BE) or XYZ text,
/// recognised by content. Every header value is checked against the bytes present before
/// anything is allocated. Throws pc::IoError with the problem and its numbers.
[[nodiscard]] ReadResult parse_cloud(std::string_view bytes);

/// read_all + parse_cloud, with errors prefixed by the input's name (`<stdin>` for "-").
[[nodiscard]] ReadResult read_cloud(const std::string& path,
                                    std::uint64_t max_bytes = kDefaultMaxInputBytes);

/// The name used for `path` in messages: the path itself, or "<stdin>" for "-".
[[nodiscard]] std::string display_name(const std::string& path);

}  // namespace pc::io
