// Internal: points in Morton order of their position (cache-friendly projection).
#pragma once

#include <cstdint>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::cameras::detail {

/// Positions 0..n−1 of `points` sorted by the Morton code of their cell in a 1024³ grid over
/// their bounding box (non-finite points first, in their order). Deterministic.
[[nodiscard]] std::vector<std::uint32_t> morton_order(const XyzView& points);

}  // namespace pc::cameras::detail
