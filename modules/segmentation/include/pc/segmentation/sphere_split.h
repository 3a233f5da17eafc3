#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::segmentation {

/// A sphere; `rms` is the root mean square of |‖p − centre‖ − radius| over the fitted points.
struct Sphere {
    std::array<double, 3> centre{};
    double radius = 0;
    double rms = 0;
    bool ok = false;  ///< false when the points do not determine a sphere
};

/// Least-squares algebraic sphere fit (‖p‖² = 2 c·p + d) of cloud[members]; needs >= 4 points
/// not on one plane.
[[nodiscard]] Sphere fit_sphere(const XyzView& cloud, std::span<const std::uint32_t> members);
[[nodiscard]] inline Sphere fit_sphere(const Cloud& cloud, std::span<const std::uint32_t> members) {
    return fit_sphere(XyzView(cloud), members);
}

/// Parameters of split_hollow(); lengths are multiples of the fruit radius R and the spacing s.
struct HollowSplitParams {
    double radius_low = 0.75, radius_high = 1.33;  ///< accepted sphere radii, × R
    double band = 0.15;                            ///< inlier band, × R (at least 1.5 s)
    double min_inliers = 0.25;  ///< a sphere needs this × the points of a typical single fruit
    std::uint32_t iterations = 300;  ///< RANSAC samples per sphere
    std::uint64_t seed = 0;
};

/// Splits a hollow cluster (surface points only) into spheres of about the fruit radius R,
/// detected one after another by RANSAC (four points near a random seed point) and refitted by
/// least squares; every point then goes to the sphere whose surface is nearest. Returns the part
/// (0-based) of each member, all 0 when fewer than two spheres are found. `typical_points` is the
/// size of a single-fruit cluster. Deterministic for a seed.
[[nodiscard]] std::vector<std::uint32_t> split_hollow(const XyzView& cloud,
                                                      std::span<const std::uint32_t> members,
                                                      double fruit_radius,
                                                      double spacing,
                                                      double typical_points,
                                                      const HollowSplitParams& params);
[[nodiscard]] inline std::vector<std::uint32_t> split_hollow(const Cloud& cloud,
                                                             std::span<const std::uint32_t> members,
                                                             double fruit_radius,
                                                             double spacing,
                                                             double typical_points,
                                                             const HollowSplitParams& params) {
    return split_hollow(XyzView(cloud), members, fruit_radius, spacing, typical_points, params);
}

}  // namespace pc::segmentation
