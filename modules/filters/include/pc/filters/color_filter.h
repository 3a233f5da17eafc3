#pragma once

#include <optional>
#include <span>
#include <string>

#include <pc/core/cloud.h>
#include <pc/io/points.h>

namespace pc::filters {

/// An inclusive interval LO:HI. For hue (degrees) LO > HI wraps through 0, e.g. 300:30.
struct Interval {
    double lo = 0, hi = 0;
};

/// A colour in HSV: hue in degrees [0, 360), or -1 for grey (R = G = B: no hue); saturation
/// (max − min) / max (0 for black) and value max(R, G, B), channels in [0, 1].
struct Hsv {
    double h = -1, s = 0, v = 0;
};
[[nodiscard]] Hsv hsv(const io::Rgb& c);

/// Parses "LO:HI" (two numbers); throws pc::InvalidArgument naming `option`.
[[nodiscard]] Interval parse_interval(const std::string& option, const std::string& text);

/// Parameters of color_filter(). Channels are in [0, 1]. Every rule given must hold (AND).
struct ColorFilterParams {
    std::optional<double> min_mean;      ///< keep iff (R+G+B)/3 > min_mean (strict; author script)
    std::optional<double> min_value;     ///< keep iff HSV value max(R,G,B) > min_value (strict)
    std::optional<Interval> hue_deg;     ///< keep iff hue in [lo, hi] degrees; grey never matches
    std::optional<Interval> saturation;  ///< keep iff HSV saturation in [lo, hi] (0..1)
    std::optional<Interval> value;       ///< keep iff HSV value in [lo, hi] (0..1)
    bool invert = false;                 ///< keep exactly the points the rules reject

    void validate() const;
};

struct ColorFilterResult {
    Indices kept;  ///< ascending
};

/// The rules of `params` on a colour's HSV (value, saturation, hue; not min_mean, not invert).
[[nodiscard]] bool hsv_passes(const Hsv& colour, const ColorFilterParams& params);

/// Keeps points by colour. A NaN channel fails every rule. O(n).
[[nodiscard]] ColorFilterResult color_filter(std::span<const io::Rgb> colours,
                                             const ColorFilterParams& params);

}  // namespace pc::filters
