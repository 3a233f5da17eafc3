#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <pc/io/blob.h>

namespace pc::io {

/// Statistics of one element of a field over all points (non-finite values excluded).
struct ElementStats {
    double min = 0, max = 0, mean = 0;
    double stddev = 0;         ///< population standard deviation (numpy.std, PDAL's stddev)
    std::uint64_t finite = 0;  ///< values that entered the statistics
    /// numpy.percentile's 10th, 50th, 90th; NaN unless describe() was asked for percentiles.
    double p10 = std::nan(""), median = std::nan(""), p90 = std::nan("");
};

struct FieldInfo {
    std::string name;
    char type = '?';                  ///< I, U or F
    std::size_t size = 0;             ///< bytes per element
    std::uint32_t count = 1;          ///< elements per point
    bool packed_colour = false;       ///< rgb/rgba: no numeric statistics
    std::vector<ElementStats> stats;  ///< one per element; empty for `_` and packed colour
};

/// What pc_info reports, in the spirit of `pdal info`.
struct CloudInfo {
    std::uint64_t points = 0, width = 0, height = 0;
    bool organised = false;
    bool is_dense = true;
    std::vector<FieldInfo> fields;
    bool has_xyz = false;
    std::array<double, 3> bbox_min{}, bbox_max{};  ///< over points with finite x, y, z
    std::uint64_t non_finite_points = 0;           ///< points whose x, y or z is NaN or infinite
    std::string colour;  ///< "rgb", "rgba", "red green blue", "r g b" or "" when none
    std::array<float, 7> viewpoint{};
};

/// Summarises a cloud. O(points x elements); no allocation per point unless `percentiles`
/// (one array of the points' values, an element at a time).
[[nodiscard]] CloudInfo describe(const Blob& blob, bool percentiles = false);

/// The colour fields present, as in CloudInfo::colour ("" when the cloud has no colour).
[[nodiscard]] std::string colour_fields(const Blob& blob);

}  // namespace pc::io
