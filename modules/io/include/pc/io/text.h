#pragma once

#include <string_view>

#include <pc/io/read.h>

namespace pc::io {

/// Parses plain text with 3 (x y z), 4 (x y z intensity) or 6 (x y z r g b) numbers per line,
/// separated by blanks, commas or semicolons. `#` and `//` lines and one leading line of column
/// names are skipped. x y z (and intensity) become F 4; colours become packed `rgb` U 4, read as
/// 0..255 integers, or as 0..1 reals when any colour value has a decimal point or exponent.
[[nodiscard]] ReadResult parse_text(std::string_view bytes);

}  // namespace pc::io
