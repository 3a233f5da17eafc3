#include <exception>
#include <functional>
#include <limits>
#include <string>
#include <utility>

#include <pc/cameras/lift.h>
#include <pc/core/error.h>
#include <pc/search/grid.h>

#include "morton.h"

namespace pc::cameras {

void LiftParams::validate() const {
    if (!(min_ratio >= 0 && min_ratio <= 1)) {
        throw InvalidArgument("lift: min_ratio must be in [0, 1], got " + format_number(min_ratio));
    }
    if (min_views < 1) {
        throw InvalidArgument("lift: min_views must be >= 1");
    }
    if (sightings < 2) {
        throw InvalidArgument("lift: sightings must be >= 2, got " + std::to_string(sightings));
    }
    visibility.validate();
    join.validate();
}

namespace {

/// Pairs of fruit points next to each other: each fruit point with its kTouching nearest fruit
/// points within 4 spacings (join_instances' fragments; 2 spacings and 6 neighbours left more
/// slivers apart, docs/views.md).
std::vector<std::pair<std::uint32_t, std::uint32_t>> touching_fruit(
    const XyzView& points, const std::vector<std::uint8_t>& fruit, double spacing) {
    constexpr std::size_t kTouching = 12;
    Cloud copy;
    std::vector<std::uint32_t> index;
    for (std::size_t i = 0; i < points.size; ++i) {
        if (fruit[i] != 0) {
            copy.push_back(points[i]);
            index.push_back(static_cast<std::uint32_t>(i));
        }
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    if (copy.size() < 2) {
        return pairs;
    }
    const search::Grid grid(copy, search::Grid::suggest_cell(copy, 16));
    constexpr auto kAbsent = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> near(copy.size() * kTouching, kAbsent);
    const double reach2 = 16 * spacing * spacing;
    grid.all_knn(kTouching, [&](std::uint32_t i, const std::vector<std::uint32_t>& idx,
                                const std::vector<double>& d2) {
        for (std::size_t k = 0; k < idx.size(); ++k) {
            if (d2[k] <= reach2) {
                near[i * kTouching + k] = idx[k];
            }
        }
    });
    for (std::size_t j = 0; j < near.size(); ++j) {
        if (near[j] != kAbsent) {
            pairs.emplace_back(index[j / kTouching], index[near[j]]);
        }
    }
    return pairs;
}

/// Where the views are: a mask of each, checked against its camera, and the pixel of every point
/// it sees (visible_pixels), one view at a time per thread. `visit(local, k, mask, pixels)` runs
/// for each view with the thread's own `local` (from `make_local()`), which `merge(local)` hands
/// back one thread at a time at the end. The first failure is rethrown after every view is done.
template <class MakeLocal, class Visit, class Merge>
void over_views(const XyzView& sorted,
                const std::vector<View>& views,
                const std::function<Mask(std::size_t)>& mask_of,
                double spacing,
                const LiftParams& params,
                const std::function<void()>& view_done,
                MakeLocal make_local,
                Visit visit,
                Merge merge) {
    std::exception_ptr failure;
#pragma omp parallel
    {
        auto local = make_local();
#pragma omp for schedule(dynamic, 1)
        for (std::int64_t kk = 0; kk < static_cast<std::int64_t>(views.size()); ++kk) {
            const auto k = static_cast<std::size_t>(kk);
            try {
                const View& view = views[k];
                const Mask mask = mask_of(k);
                if (mask.width != view.camera.width || mask.height != view.camera.height ||
                    mask.id.size() != static_cast<std::size_t>(mask.width) *
                                          static_cast<std::size_t>(mask.height)) {
                    throw IoError(view.image + ": mask is " + std::to_string(mask.width) + " x " +
                                  std::to_string(mask.height) + ", the camera " +
                                  std::to_string(view.camera.width) + " x " +
                                  std::to_string(view.camera.height));
                }
                visit(local, k, mask, visible_pixels(sorted, view, spacing, params.visibility));
            } catch (...) {
#pragma omp critical(lift_failure)
                if (!failure) {
                    failure = std::current_exception();
                }
            }
#pragma omp critical(lift_progress)
            if (!failure) {
                view_done();
            }
        }
#pragma omp critical(lift_merge)
        merge(local);
    }
    if (failure) {
        std::rethrow_exception(failure);
    }
}

/// A number in [0, 1) that looks random but is fixed by the point and the view (splitmix64).
double sample(std::uint32_t point, std::size_t view) {
    std::uint64_t z = ((std::uint64_t{point} << 32) | view) + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
}

}  // namespace

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
    const std::size_t total = views.size() * (params.instances ? 2 : 1);
    std::size_t done = 0;
    const auto view_done = [&] {
        ++done;
        if (progress) {
            progress(done, total);
        }
    };
    LiftResult r;
    r.views.assign(points.size, 0);
    r.votes.assign(points.size, 0);
    struct Counts {
        std::vector<std::uint32_t> seen, voted;  // in Morton order until merged
    };
    over_views(
        sorted, views, mask_of, spacing, params, view_done,
        [&] {
            return Counts{std::vector<std::uint32_t>(points.size, 0),
                          std::vector<std::uint32_t>(points.size, 0)};
        },
        [](Counts& c, std::size_t, const Mask& mask, const std::vector<std::int32_t>& px) {
            for (std::size_t i = 0; i < px.size(); ++i) {
                if (px[i] >= 0) {
                    ++c.seen[i];
                    c.voted[i] += mask.id[static_cast<std::size_t>(px[i])] != 0;
                }
            }
        },
        [&](const Counts& c) {
            for (std::size_t i = 0; i < points.size; ++i) {
                r.views[order[i]] += c.seen[i];
                r.votes[order[i]] += c.voted[i];
            }
        });
    r.fruit.assign(points.size, 0);
    for (std::size_t i = 0; i < points.size; ++i) {
        r.fruit[i] = r.views[i] >= params.min_views &&
                     static_cast<double>(r.votes[i]) >= params.min_ratio * r.views[i];
    }
    if (!params.instances) {
        return r;
    }
    // A second pass keeps about `sightings` sightings of each fruit point, drawn at random among
    // the views that see it: 1M fruit points seen by 100 views each would otherwise hold 100M.
    std::vector<Sighting> sightings;
    over_views(
        sorted, views, mask_of, spacing, params, view_done, [] { return std::vector<Sighting>{}; },
        [&](std::vector<Sighting>& mine, std::size_t k, const Mask& mask,
            const std::vector<std::int32_t>& px) {
            for (std::size_t i = 0; i < px.size(); ++i) {
                const std::uint32_t p = order[i];
                if (px[i] < 0 || r.fruit[p] == 0) {
                    continue;
                }
                const std::uint16_t id = mask.id[static_cast<std::size_t>(px[i])];
                if (id != 0 && sample(p, k) * r.views[p] < params.sightings) {
                    mine.push_back({p, static_cast<std::uint32_t>(k), id});
                }
            }
        },
        [&](const std::vector<Sighting>& mine) {
            sightings.insert(sightings.end(), mine.begin(), mine.end());
        });
    JoinResult joined = join_instances(std::move(sightings), r.fruit,
                                       touching_fruit(points, r.fruit, spacing), params.join);
    r.label = std::move(joined.labels);
    r.doubtful = joined.doubtful;
    return r;
}

}  // namespace pc::cameras
