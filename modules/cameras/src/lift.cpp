#include <exception>
#include <string>

#include <pc/cameras/lift.h>
#include <pc/core/error.h>

#include "morton.h"

namespace pc::cameras {

void LiftParams::validate() const {
    if (!(min_ratio >= 0 && min_ratio <= 1)) {
        throw InvalidArgument("lift: min_ratio must be in [0, 1], got " + format_number(min_ratio));
    }
    if (min_views < 1) {
        throw InvalidArgument("lift: min_views must be >= 1");
    }
    visibility.validate();
}

LiftResult lift(const XyzView& points,
                const std::vector<View>& views,
                const std::function<Mask(std::size_t)>& mask_of,
                double spacing,
                const LiftParams& params,
                const std::function<void(std::size_t, std::size_t)>& progress) {
    params.validate();
    // Points in Morton order of their position: neighbours in space land on neighbouring pixels,
    // so the z-buffer's reads and writes stay in cache (in the cloud's own order, often shuffled,
    // 80 % of the time went to cache misses on the depth buffer).
    const std::vector<std::uint32_t> order = detail::morton_order(points);
    Cloud copy;  // contiguous in that order: read once per view without indirection
    copy.resize(points.size);
    for (std::size_t i = 0; i < points.size; ++i) {
        copy[i] = points[order[i]];
    }
    const XyzView sorted(copy);
    LiftResult r;
    r.views.assign(points.size, 0);
    r.votes.assign(points.size, 0);
    std::exception_ptr failure;
    std::size_t done = 0;
#pragma omp parallel
    {
        std::vector<std::uint32_t> seen(points.size, 0), voted(points.size, 0);
#pragma omp for schedule(dynamic, 1)
        for (std::int64_t kk = 0; kk < static_cast<std::int64_t>(views.size()); ++kk) {
            const auto k = static_cast<std::size_t>(kk);
            try {
                const View& view = views[k];
                const Mask mask = mask_of(k);
                if (mask.width != view.camera.width || mask.height != view.camera.height ||
                    mask.fruit.size() != static_cast<std::size_t>(mask.width) *
                                             static_cast<std::size_t>(mask.height)) {
                    throw IoError(view.image + ": mask is " + std::to_string(mask.width) + " x " +
                                  std::to_string(mask.height) + ", the camera " +
                                  std::to_string(view.camera.width) + " x " +
                                  std::to_string(view.camera.height));
                }
                const std::vector<std::int32_t> px =
                    visible_pixels(sorted, view, spacing, params.visibility);
                for (std::size_t i = 0; i < px.size(); ++i) {
                    if (px[i] >= 0) {
                        ++seen[i];  // in Morton order until the end
                        voted[i] += mask.fruit[static_cast<std::size_t>(px[i])] != 0;
                    }
                }
            } catch (...) {
#pragma omp critical(lift_failure)
                if (!failure) {
                    failure = std::current_exception();
                }
            }
#pragma omp critical(lift_progress)
            {
                ++done;
                if (progress && !failure) {
                    progress(done, views.size());
                }
            }
        }
#pragma omp critical(lift_sum)
        for (std::size_t i = 0; i < points.size; ++i) {
            r.views[order[i]] += seen[i];
            r.votes[order[i]] += voted[i];
        }
    }
    if (failure) {
        std::rethrow_exception(failure);
    }
    r.fruit.assign(points.size, 0);
    for (std::size_t i = 0; i < points.size; ++i) {
        r.fruit[i] = r.views[i] >= params.min_views &&
                     static_cast<double>(r.votes[i]) >= params.min_ratio * r.views[i];
    }
    return r;
}

}  // namespace pc::cameras
