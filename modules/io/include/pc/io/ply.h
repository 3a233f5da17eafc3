#pragma once

#include <string_view>

#include <pc/io/read.h>
#include <pc/io/sink.h>

namespace pc::io {

/// Parses the vertex element of a PLY 1.0 file (ascii, binary little/big endian). Other elements
/// (faces) are walked and skipped. uchar red/green/blue(/alpha) become packed `rgb` (`rgba`) U 4;
/// nx ny nz become normal_x/y/z; `scalar_NAME` (CloudCompare's scalar fields) becomes NAME unless
/// the file has NAME too; every other property keeps its name and type (double stays F8).
/// 3D Gaussian splatting files (f_dc_0..2) also get `rgb` from the SH DC term.
[[nodiscard]] ReadResult parse_ply(std::string_view bytes);

/// Writes a vertex-only PLY. Packed rgb/rgba become uchar red green blue (alpha), normal_x/y/z
/// become nx ny nz, COUNT > 1 fields become name_0..name_{n-1}, `_` padding is dropped. With
/// `scalar_prefix`, every field but x y z, normals, colour and intensity is written as
/// `scalar_NAME`: CloudCompare then loads each as a scalar field without asking (the reader
/// strips the prefix again).
void write_ply(const Blob& blob, bool binary, ByteSink& sink, bool scalar_prefix = false);

}  // namespace pc::io
