#pragma once

#include <string_view>

#include <pc/io/read.h>
#include <pc/io/sink.h>

namespace pc::io {

/// Parses plain text, one point a line, numbers separated by blanks, commas or semicolons; `#`
/// and `//` lines are comments. The columns are named by a first line (plain or after `//`, as
/// CloudCompare writes "//X,Y,Z,R,G,B,Nx,Ny,Nz") when it names x, y and z (any case): r g b or
/// red green blue become packed `rgb` U 4; nx ny nz become normal_x ...; any other name a field
/// of its own (non-alphanumerics as `_`): U 4 (or I 4) when every value is a whole number
/// written without a fraction, else F 4. Without such a line: 3 (x y z), 4 (x y z intensity), 6
/// (x y z r g b) or 9 (x y z r g b nx ny nz, CloudCompare's order) columns, all F 4 but colour.
/// Colours are 0..255 integers, or 0..1 reals when any is written with a fraction or exponent.
[[nodiscard]] ReadResult parse_text(std::string_view bytes);

/// Writes `blob` as text that parse_text and CloudCompare read back: a `//X Y Z R G B Nx ...`
/// line naming the columns (fields of several elements as name_0 name_1 ...; padding left out;
/// packed colour as three 0..255 integers), then one line a point, values as the ASCII PCD
/// writer prints them (the shortest text that reads back the same).
void write_text(const Blob& blob, ByteSink& sink);

}  // namespace pc::io
