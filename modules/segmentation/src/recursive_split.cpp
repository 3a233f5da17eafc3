#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <pc/core/error.h>
#include <pc/core/labels.h>
#include <pc/core/names.h>
#include <pc/core/stats.h>
#include <pc/segmentation/core_split.h>
#include <pc/segmentation/kmeans.h>
#include <pc/segmentation/recursive_split.h>
#include <pc/segmentation/sphere_vote.h>

namespace pc::segmentation {

namespace {

double aabb_volume(const XyzView& cloud, const std::vector<std::uint32_t>& members) {
    float lo[3] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                   std::numeric_limits<float>::max()};
    float hi[3] = {-lo[0], -lo[1], -lo[2]};
    for (std::uint32_t i : members) {
        const pcl::PointXYZ p = cloud[i];
        const float v[3] = {p.x, p.y, p.z};
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], v[a]);
            hi[a] = std::max(hi[a], v[a]);
        }
    }
    if (members.empty()) {
        return 0;
    }
    return (double{hi[0]} - lo[0]) * (double{hi[1]} - lo[1]) * (double{hi[2]} - lo[2]);
}

}  // namespace

namespace {

constexpr std::pair<std::string_view, SplitRule> kRules[] = {{"paper", SplitRule::kPaper},
                                                             {"script", SplitRule::kScript},
                                                             {"cores", SplitRule::kCores},
                                                             {"spheres", SplitRule::kSpheres}};

}  // namespace

SplitRule parse_split_rule(const std::string& text) {
    return parse_name<SplitRule>(kRules, text, "--rule");
}

std::string split_rule_name(SplitRule rule) { return name_of<SplitRule>(kRules, rule); }

void RecursiveSplitParams::validate() const {
    if (!(size_factor >= 0) || !(volume_factor >= 0)) {
        throw InvalidArgument("recursive_split: size_factor and volume_factor must be >= 0, got " +
                              format_number(size_factor) + " and " + format_number(volume_factor));
    }
    if (!(size_band >= 0)) {
        throw InvalidArgument("recursive_split: size_band must be >= 0, got " +
                              format_number(size_band));
    }
    if (!(fruit_radius >= 0 && std::isfinite(fruit_radius))) {
        throw InvalidArgument(
            "recursive_split: fruit_radius must be >= 0 (0: from the cloud), got " +
            format_number(fruit_radius));
    }
    if (restarts < 1) {
        throw InvalidArgument("recursive_split: restarts must be >= 1, got " +
                              std::to_string(restarts));
    }
}

namespace {

RecursiveSplitResult by_cores(const XyzView& points,
                              std::vector<std::uint32_t> labels,
                              const RecursiveSplitParams& params) {
    CoreSplitResult c = core_split(points, std::move(labels),
                                   {.core_fraction = params.core_fraction,
                                    .min_cluster_size = params.min_cluster_size,
                                    .min_relative_size = params.min_relative_size});
    RecursiveSplitResult r;
    r.labels = std::move(c.labels);
    r.cluster_count = c.cluster_count;
    r.splits = c.splits;
    r.size_threshold = r.volume_threshold = std::nan("");
    r.spacing = c.spacing;
    r.fruit_radius = c.fruit_radius;
    r.hollow_radius = c.hollow_radius;
    return r;
}

RecursiveSplitResult by_spheres(const XyzView& points,
                                std::vector<std::uint32_t> labels,
                                const RecursiveSplitParams& params) {
    SphereVoteParams vp{.fruit_radius = params.fruit_radius,
                        .min_cluster_size = params.min_cluster_size,
                        .min_relative_size = params.min_relative_size};
    if (!params.branch_recheck) {
        vp.branch_below = 0;
    }
    SphereVoteResult v = sphere_vote(points, std::move(labels), vp);
    RecursiveSplitResult r;
    r.labels = std::move(v.labels);
    r.cluster_count = v.cluster_count;
    r.size_threshold = r.volume_threshold = std::nan("");
    r.spacing = v.spacing;
    r.fruit_radius = v.fruit_radius;
    r.peaks = v.peaks;
    r.solid = v.solid;
    r.claimed = v.claimed;
    r.median_part = v.median_part;
    r.measured_radius = v.measured_radius;
    r.larger_radius = v.larger_radius;
    return r;
}

}  // namespace

RecursiveSplitResult recursive_split(const XyzView& cloud,
                                     std::vector<std::uint32_t> labels,
                                     const RecursiveSplitParams& params) {
    params.validate();
    if (params.rule == SplitRule::kCores) {
        return by_cores(cloud, std::move(labels), params);
    }
    if (params.rule == SplitRule::kSpheres) {
        return by_spheres(cloud, std::move(labels), params);
    }
    const std::size_t n = cloud.size;
    if (labels.size() != n) {
        throw InvalidArgument("recursive_split: labels must be one per point (" +
                              std::to_string(n) + "), got " + std::to_string(labels.size()));
    }
    // Gather clusters (finite members only).
    std::uint32_t max_label = 0;
    for (std::uint32_t l : labels) {
        max_label = std::max(max_label, l);
    }
    std::vector<std::vector<std::uint32_t>> clusters(std::size_t{max_label} + 1);
    for (std::uint32_t i = 0; i < n; ++i) {
        if (labels[i] != 0 && is_finite(cloud[i])) {
            clusters[labels[i]].push_back(i);
        }
    }
    std::vector<std::vector<std::uint32_t>> queue;
    for (auto& c : clusters) {
        if (!c.empty()) {
            queue.push_back(std::move(c));
        }
    }
    RecursiveSplitResult r;
    // Thresholds, once, from the input clusters.
    std::vector<double> sizes, volumes;
    for (const auto& c : queue) {
        sizes.push_back(static_cast<double>(c.size()));
        volumes.push_back(aabb_volume(cloud, c));
    }
    double med_size = std::nan(""), med_volume = std::nan("");
    if (params.rule == SplitRule::kPaper) {
        std::vector<double> s = sizes, v = volumes;
        med_size = median(s);
        med_volume = median(v);
    } else {
        std::vector<double> big;
        for (double s : sizes) {
            if (s > params.median_min_points) {
                big.push_back(s);
            }
        }
        med_size = median(big);
        std::vector<double> band;
        for (std::size_t k = 0; k < sizes.size(); ++k) {
            if (std::abs(sizes[k] - med_size) <= params.size_band * med_size) {
                band.push_back(volumes[k]);
            }
        }
        med_volume = median(band);
    }
    r.size_threshold = params.size_factor * med_size;
    r.volume_threshold = params.volume_factor * med_volume;
    const bool can_split = std::isfinite(r.size_threshold) && std::isfinite(r.volume_threshold);

    std::vector<std::uint32_t> out(n, 0);
    std::uint32_t next_label = 0;
    std::vector<pcl::PointXYZ> pts;
    while (!queue.empty()) {
        std::vector<std::uint32_t> c = std::move(queue.back());
        queue.pop_back();
        const bool violates = can_split && static_cast<double>(c.size()) > r.size_threshold &&
                              aabb_volume(cloud, c) > r.volume_threshold && c.size() >= 2;
        if (violates) {
            pts.clear();
            for (std::uint32_t i : c) {
                pts.push_back(cloud[i]);
            }
            const std::uint64_t mix = params.seed ^ (0x9E3779B97F4A7C15ull * (c.front() + 1));
            const KMeansResult km = kmeans(pts, {.k = 2, .restarts = params.restarts, .seed = mix});
            std::vector<std::uint32_t> a, b;
            for (std::size_t k = 0; k < c.size(); ++k) {
                (km.assignment[k] == 0 ? a : b).push_back(c[k]);
            }
            if (!a.empty() && !b.empty()) {
                ++r.splits;
                queue.push_back(std::move(a));
                queue.push_back(std::move(b));
                continue;
            }
        }
        ++next_label;
        for (std::uint32_t i : c) {
            out[i] = next_label;
        }
    }
    r.cluster_count = renumber_by_size(out, params.min_cluster_size);
    r.labels = std::move(out);
    return r;
}

}  // namespace pc::segmentation
