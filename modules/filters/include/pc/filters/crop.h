#pragma once

#include <array>
#include <limits>

#include <pc/core/cloud.h>

namespace pc::filters {

/// Parameters of crop(): an axis-aligned box, both ends included.
struct CropParams {
    static constexpr double kInf = std::numeric_limits<double>::infinity();
    std::array<double, 3> min{-kInf, -kInf, -kInf};  ///< lower corner x,y,z (included)
    std::array<double, 3> max{kInf, kInf, kInf};     ///< upper corner x,y,z (included)
    bool invert = false;                             ///< keep the points outside the box instead

    void validate() const;
};

struct CropResult {
    Indices kept;  ///< ascending
};

/// Keeps points with min <= p <= max on every axis. Non-finite points are outside the box
/// (dropped, or kept with invert). O(n).
[[nodiscard]] CropResult crop(const XyzView& points, const CropParams& params);
[[nodiscard]] inline CropResult crop(const Cloud& cloud, const CropParams& params) {
    return crop(XyzView(cloud), params);
}

}  // namespace pc::filters
