#pragma once
// Colours that show a result in any viewer (CloudCompare, MeshLab, Open3D): a distinct colour per
// label, or a field through the viridis colour map. pc_colorize writes them as `rgb`; pc_render
// draws with them.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <pc/io/blob.h>

namespace pc::filters {

/// 8-bit red, green, blue.
using Rgb8 = std::array<std::uint8_t, 3>;

/// A distinct colour per label: hues a golden ratio of the circle apart (neighbouring labels far
/// apart in hue), saturation 0.78, value 0.9; label 0 (noise, not fruit) grey 160.
[[nodiscard]] Rgb8 label_color(std::uint32_t label);

/// The viridis colour map at t in [0, 1] (clamped; dark blue to yellow, even in lightness and
/// readable by colour-blind viewers); NaN gives grey 160.
[[nodiscard]] Rgb8 viridis(double t);

/// Parameters of colorize().
struct ColorizeParams {
    /// "label" (label_color of the U/I field `label`), a field name, or x, y, z: through viridis.
    std::string by = "label";
    /// The values mapped to the ends of the colour map; default the field's 2nd and 98th
    /// percentiles (a few outliers do not wash out the rest).
    std::optional<std::array<double, 2>> range;
    void validate() const;
};

struct Colorized {
    std::vector<Rgb8> colors;  ///< one per point
    /// The range used (a colour bar's ends); both 0 for labels.
    double lo = 0, hi = 0;
};

/// The colour of every point. Throws pc::IoError naming the field when the cloud lacks it (or it
/// has several elements), pc::InvalidArgument for a bad range.
[[nodiscard]] Colorized colorize(const io::Blob& blob, const ColorizeParams& params);

/// `colors` packed as `rgb` U 4 words (0x00RRGGBB), for io::set_field.
[[nodiscard]] std::vector<std::uint32_t> packed(const std::vector<Rgb8>& colors);

}  // namespace pc::filters
