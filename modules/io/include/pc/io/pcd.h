#pragma once

#include <optional>
#include <string_view>

#include <pc/io/read.h>
#include <pc/io/sink.h>

namespace pc::io {

enum class PcdEncoding { kAscii, kBinary, kBinaryCompressed };

/// Parses a PCD v0.5-0.7 file held in memory (see docs/formats.md for what is accepted).
[[nodiscard]] ReadResult parse_pcd(std::string_view bytes);

/// The start of a binary PCD read from a stream: the cloud with every header value set (fields,
/// sizes, viewpoint, header notes, format) and no data yet, where the body starts in the input and
/// how many bytes it has. Lets a pipe reader put the body straight into the cloud's memory.
struct PcdStart {
    ReadResult result;
    std::uint64_t body_offset = 0;
    std::uint64_t body_bytes = 0;
};
/// A PcdStart when `prefix` holds a complete, valid binary header; nullopt otherwise (any other
/// encoding, a header not yet complete, or one that parse_pcd would refuse).
[[nodiscard]] std::optional<PcdStart> start_binary_pcd(std::string_view prefix);

/// Writes PCD v0.7. Gaps between fields become `_` padding fields (as PCL does); a packed colour
/// (`rgb`/`rgba` F 4) is declared U 4 with the same bits. ASCII floats use the shortest text that
/// reads back bit-identical (NaN payloads excepted); binary_compressed omits `_` fields, as PCL.
void write_pcd(const Blob& blob, PcdEncoding encoding, ByteSink& sink);

}  // namespace pc::io
