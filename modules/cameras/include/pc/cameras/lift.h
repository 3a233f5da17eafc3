#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <pc/cameras/camera.h>
#include <pc/cameras/join_instances.h>
#include <pc/cameras/visibility.h>
#include <pc/core/cloud.h>

namespace pc::cameras {

/// The fruit mask of one view: 0 where no fruit; elsewhere the fruit's 2D instance id (a binary
/// mask: any non-zero value).
struct Mask {
    int width = 0;
    int height = 0;
    std::vector<std::uint16_t> id;  ///< row-major, width × height
};

/// Parameters of lift().
struct LiftParams {
    double min_ratio = 0.5;        ///< fruit iff votes / views >= this ...
    std::uint32_t min_views = 1;   ///< ... and views >= this
    bool instances = false;        ///< the masks' ids are instances: join them into `label`
    std::uint32_t sightings = 16;  ///< instances: about this many views' sightings kept a point
    VisibilityParams visibility;
    JoinParams join;

    void validate() const;
};

struct LiftResult {
    std::vector<std::uint32_t> views;  ///< per point: views that see it unoccluded
    std::vector<std::uint32_t> votes;  ///< ... of those, views whose mask covers it
    std::vector<std::uint8_t> fruit;   ///< 1 iff votes / views >= min_ratio and views >= min_views
    std::vector<std::uint32_t> label;  ///< with `instances`: join_instances() over the fruit
    std::size_t doubtful = 0;          ///< ... and its fruit points with a doubtful label
};

/// The paper's mask lifting (2.3.1): each point's majority vote over the views that see it
/// (visible_pixels()) of whether their fruit mask covers it. `mask_of(k)` gives view k's mask (it
/// is called once per view, from several threads at once; it throws pc::IoError for a mask that
/// cannot be read); a mask of another size than its camera is an IoError naming the view's
/// image. `spacing` is the point spacing in the cloud's units. `progress(done, total)`, when
/// given, is called after each view from one thread at a time. With `instances`, a second pass
/// over the views keeps about `sightings` sightings (12 bytes each) of every fruit point in its
/// views' instances, drawn at random among the views that see it, and join_instances() makes
/// `label` from them.
[[nodiscard]] LiftResult lift(const XyzView& points,
                              const std::vector<View>& views,
                              const std::function<Mask(std::size_t)>& mask_of,
                              double spacing,
                              const LiftParams& params,
                              const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace pc::cameras
