#include <pc/features/extent.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include <pc/core/error.h>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace pc::features {

namespace {

/// Volume and area of the convex hull of `xyz` (n x 3, row-major); false when qhull finds the
/// input degenerate (flat or too few points).
bool convex_hull(std::vector<double>& xyz, double& volume, double& area) {
    const int n = static_cast<int>(xyz.size() / 3);
    if (n < 4) {
        return false;
    }
    FILE* sink = std::fopen("/dev/null", "w");  // qhull reports degenerate input on its errfile
    qhT qh_storage;
    qhT* qh = &qh_storage;
    qh_zero(qh, sink);
    char options[] = "qhull Qt FA";
    const int status = qh_new_qhull(qh, 3, n, xyz.data(), False, options, nullptr, sink);
    const bool ok = status == 0;
    if (ok) {
        volume = qh->totvol;
        area = qh->totarea;
    }
    qh_freeqhull(qh, !qh_ALL);
    int curlong = 0, totlong = 0;
    qh_memfreeshort(qh, &curlong, &totlong);
    if (sink != nullptr) {
        std::fclose(sink);
    }
    return ok && volume > 0;
}

}  // namespace

Extent extent(const XyzView& cloud, std::span<const std::uint32_t> indices) {
    Extent e;
    std::vector<double> xyz;
    const std::size_t count = indices.empty() ? cloud.size : indices.size();
    xyz.reserve(3 * count);
    for (std::size_t k = 0; k < count; ++k) {
        const pcl::PointXYZ p = cloud[indices.empty() ? k : indices[k]];
        if (!is_finite(p)) {
            continue;
        }
        xyz.insert(xyz.end(), {double{p.x}, double{p.y}, double{p.z}});
    }
    e.points = xyz.size() / 3;
    if (e.points == 0) {
        return e;
    }
    e.min = {xyz[0], xyz[1], xyz[2]};
    e.max = e.min;
    for (std::size_t i = 0; i < e.points; ++i) {
        for (int a = 0; a < 3; ++a) {
            const double v = xyz[3 * i + a];
            e.centroid[a] += v;
            e.min[a] = std::min(e.min[a], v);
            e.max[a] = std::max(e.max[a], v);
        }
    }
    for (int a = 0; a < 3; ++a) {
        e.centroid[a] /= static_cast<double>(e.points);
    }
    e.aabb_volume = (e.max[0] - e.min[0]) * (e.max[1] - e.min[1]) * (e.max[2] - e.min[2]);
    double sum = 0;
    for (std::size_t i = 0; i < e.points; ++i) {
        const double dx = xyz[3 * i] - e.centroid[0], dy = xyz[3 * i + 1] - e.centroid[1],
                     dz = xyz[3 * i + 2] - e.centroid[2];
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        sum += r;
        e.max_radius = std::max(e.max_radius, r);
    }
    e.mean_radius = sum / static_cast<double>(e.points);
    e.degenerate = !convex_hull(xyz, e.hull_volume, e.hull_area);
    if (e.degenerate) {
        e.hull_volume = e.hull_area = 0;
    }
    e.equivalent_diameter = 2 * std::cbrt(3 * e.hull_volume / (4 * std::numbers::pi));
    return e;
}

std::vector<LabelledExtent> extent_per_label(const XyzView& cloud,
                                             std::span<const std::uint32_t> labels) {
    if (labels.size() != cloud.size) {
        throw InvalidArgument("extent_per_label: labels must be one per point (" +
                              std::to_string(cloud.size) + "), got " +
                              std::to_string(labels.size()));
    }
    std::map<std::uint32_t, std::vector<std::uint32_t>> members;
    for (std::uint32_t i = 0; i < labels.size(); ++i) {
        if (labels[i] != 0) {
            members[labels[i]].push_back(i);
        }
    }
    std::vector<LabelledExtent> out;
    for (const auto& [label, idx] : members) {
        out.push_back({label, extent(cloud, idx)});
    }
    return out;
}

}  // namespace pc::features
