#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <span>

#include <pc/io/points.h>

namespace pc::filters {

/// The 10th, 50th and 90th percentiles of a quantity (NaN when there are no values).
struct Spread {
    double p10 = std::numeric_limits<double>::quiet_NaN();
    double median = std::numeric_limits<double>::quiet_NaN();
    double p90 = std::numeric_limits<double>::quiet_NaN();
};

/// The colours of a cloud in the terms its colour rules use (pc_info --stats): why a rule keeps
/// what it keeps. Channels, saturation and value in [0, 1] (filters::hsv).
struct ColorStats {
    std::size_t points = 0;
    Spread red, green, blue, saturation, value;
    std::size_t grey = 0;  ///< points without a hue (R = G = B), not in the histogram
    /// Points by hue in the 12 colours of the colour wheel (kHueNames), 30 degrees each and
    /// centred on 0, 30, ... (red 345..15, orange 15..45, ...). Hue is circular: no percentiles.
    std::array<std::size_t, 12> hue_histogram{};
};

inline constexpr const char* kHueNames[12] = {"red",   "orange", "yellow",  "chartreuse",
                                              "green", "spring", "cyan",    "azure",
                                              "blue",  "violet", "magenta", "rose"};

[[nodiscard]] ColorStats color_stats(std::span<const io::Rgb> colours);

}  // namespace pc::filters
