#pragma once

#include <string_view>

#include <pc/io/read.h>
#include <pc/io/sink.h>

namespace pc::io {

enum class PcdEncoding { kAscii, kBinary, kBinaryCompressed };

/// Parses a PCD v0.5-0.7 file held in memory (see docs/formats.md for what is accepted).
[[nodiscard]] ReadResult parse_pcd(std::string_view bytes);

/// Writes PCD v0.7. Gaps between fields become `_` padding fields (as PCL does); a packed colour
/// (`rgb`/`rgba` F 4) is declared U 4 with the same bits. ASCII floats use the shortest text that
/// reads back bit-identical (NaN payloads excepted); binary_compressed omits `_` fields, as PCL.
void write_pcd(const Blob& blob, PcdEncoding encoding, ByteSink& sink);

}  // namespace pc::io
