#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <pc/core/cloud.h>
#include <pc/io/points.h>

namespace pc::filters {

/// Parameters of smooth_colors().
struct ColorSmoothParams {
    std::uint32_t k = 8;  ///< neighbours whose colours join the point's own (1..64)
    /// Smooth only where the colours' noise (SmoothedColors::noise, 0..1 a channel) reaches this;
    /// 0: always. kNoisyColours is the `auto` choice.
    double min_noise = 0;

    void validate() const;
};

/// Colour noise from which smooth_colors() smooths under `auto`: 10 of 255 a channel. Read on
/// clean colours: 4.4-13.3 of 255 on the matrix's pc_synth scenes (±8 levels and ±8 % brightness
/// a point) and 7.4 on a real SfM apple tree (2.66M points); with N(0, 12) added, 14.8; with
/// N(0, 25), 27-28 (docs/robustness-history.md).
inline constexpr double kNoisyColours = 10.0 / 255;
/// The `auto` smoothing: K = 8 where the noise reaches kNoisyColours (the dense preset's).
inline constexpr ColorSmoothParams kAutoColorSmooth{.k = 8, .min_noise = kNoisyColours};

struct SmoothedColors {
    /// The colours' point-to-point noise, as a normal σ a channel (0..1): the median, over up to
    /// 20000 points of whole blocks of the cloud (chosen by hash, their neighbourhoods complete)
    /// and their three channels, of the distance from a point's colour to the median of its k
    /// nearest neighbours', over 0.6745 (a normal's median absolute deviation). 0 for a cloud of
    /// fewer than k + 1 finite points.
    double noise = 0;
    /// Each point's colour as the per-channel median of its own and its k nearest neighbours';
    /// empty where `noise` is under min_noise (the colours are clean enough as they are).
    std::vector<io::Rgb> colors;
};

/// Each point's colour as the per-channel median of its own and its `k` nearest neighbours'
/// (exact kNN over the finite points, OpenMP-parallel, deterministic; a non-finite point keeps
/// its colour), where the colours are noisy. An SfM or NeRF point's colour is blended from the
/// views that saw it and may vary from point to point far more than the surface's does; the
/// median over a neighbourhood gives the surface's back (noise σ to about σ/2.4 with k = 8), and
/// a point on a fruit's rim takes the colour of the side most of its neighbours lie on, not a
/// blend of the two as a mean would. `colors` has one entry per point of `points`.
[[nodiscard]] SmoothedColors smooth_colors(const XyzView& points,
                                           std::span<const io::Rgb> colors,
                                           const ColorSmoothParams& params);

}  // namespace pc::filters
