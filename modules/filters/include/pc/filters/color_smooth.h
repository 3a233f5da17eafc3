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

    void validate() const;
};

/// Each point's colour as the per-channel median of its own and its `k` nearest neighbours'
/// (exact kNN over the finite points, OpenMP-parallel, deterministic; a non-finite point keeps
/// its colour). An SfM or NeRF point's colour is blended from the views that saw it and varies
/// from point to point far more than the surface's does; the median over a neighbourhood gives
/// the surface's back (noise σ to about σ/2.4 with k = 8), and a point on a fruit's rim takes the
/// colour of the side most of its neighbours lie on, not a blend of the two as a mean would.
/// `colors` has one entry per point of `points`.
[[nodiscard]] std::vector<io::Rgb> smooth_colors(const XyzView& points,
                                                 std::span<const io::Rgb> colors,
                                                 const ColorSmoothParams& params);

}  // namespace pc::filters
