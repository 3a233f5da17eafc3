#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <pc/cameras/camera.h>
#include <pc/cameras/visibility.h>
#include <pc/core/cloud.h>

namespace pc::cameras {

/// A binary fruit mask of one view: 1 where the view's mask covers fruit.
struct Mask {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> fruit;  ///< row-major, width × height
};

/// Parameters of lift().
struct LiftParams {
    double min_ratio = 0.5;       ///< fruit iff votes / views >= this ...
    std::uint32_t min_views = 1;  ///< ... and views >= this
    VisibilityParams visibility;

    void validate() const;
};

struct LiftResult {
    std::vector<std::uint32_t> views;  ///< per point: views that see it unoccluded
    std::vector<std::uint32_t> votes;  ///< ... of those, views whose mask covers it
    std::vector<std::uint8_t> fruit;   ///< 1 iff votes / views >= min_ratio and views >= min_views
};

/// The paper's mask lifting (2.3.1): each point's majority vote over the views that see it
/// (visible_pixels()) of whether their fruit mask covers it. `mask_of(k)` gives view k's mask (it
/// is called once per view, from several threads at once; it throws pc::IoError for a mask that
/// cannot be read); a mask of another size than its camera is an IoError naming the view's
/// image. `spacing` is the point spacing in the cloud's units. `progress(done, total)`, when
/// given, is called after each view from one thread at a time.
[[nodiscard]] LiftResult lift(const XyzView& points,
                              const std::vector<View>& views,
                              const std::function<Mask(std::size_t)>& mask_of,
                              double spacing,
                              const LiftParams& params,
                              const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace pc::cameras
