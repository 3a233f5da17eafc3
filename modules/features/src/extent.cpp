#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <string>

#include <pc/core/error.h>
#include <pc/features/extent.h>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace pc::features {

namespace {

/// Runs qhull with `options` on `xyz` (n x 3, row-major) and, when it succeeds, calls read(qh)
/// before qhull's memory is freed; false when qhull finds the input degenerate (flat or too few
/// points).
template <class Read>
bool with_qhull(std::vector<double>& xyz, const char* options, Read&& read) {
    const int n = static_cast<int>(xyz.size() / 3);
    if (n < 4) {
        return false;
    }
    FILE* sink = std::fopen("/dev/null", "w");  // qhull reports degenerate input on its errfile
    qhT qh_storage;
    qhT* qh = &qh_storage;
    qh_zero(qh, sink);
    std::string command = options;  // qh_new_qhull takes a writable string
    const bool ok = qh_new_qhull(qh, 3, n, xyz.data(), False, command.data(), nullptr, sink) == 0;
    if (ok) {
        read(qh);
    }
    qh_freeqhull(qh, !qh_ALL);
    int curlong = 0, totlong = 0;
    qh_memfreeshort(qh, &curlong, &totlong);
    if (sink != nullptr) {
        std::fclose(sink);
    }
    return ok;
}

/// Volume and area of the convex hull of `xyz`; false when degenerate.
bool convex_hull(std::vector<double>& xyz, double& volume, double& area) {
    const bool ok = with_qhull(xyz, "qhull Qt FA", [&](qhT* qh) {
        volume = qh->totvol;
        area = qh->totarea;
    });
    return ok && volume > 0;
}

/// Facet planes (outward normal n, offset o: n . p + o < 0 inside) of the convex hull of `xyz`;
/// empty when qhull finds it degenerate.
std::vector<std::array<double, 4>> hull_planes(std::vector<double>& xyz) {
    std::vector<std::array<double, 4>> planes;
    with_qhull(xyz, "qhull Qt", [&](qhT* qh) {
        facetT* facet;
        FORALLfacets {
            planes.push_back({facet->normal[0], facet->normal[1], facet->normal[2], facet->offset});
        }
    });
    return planes;
}

}  // namespace

Extent extent(const XyzView& cloud, std::span<const std::uint32_t> indices) {
    Extent e;
    const std::size_t count = indices.empty() ? cloud.size : indices.size();
    const auto point = [&](std::size_t k) { return cloud[indices.empty() ? k : indices[k]]; };
    // Two passes over the points where they are: centroid and box, then the radii.
    for (std::size_t k = 0; k < count; ++k) {
        const pcl::PointXYZ p = point(k);
        if (!is_finite(p)) {
            continue;
        }
        const double v[3] = {p.x, p.y, p.z};
        if (e.points == 0) {
            e.min = {v[0], v[1], v[2]};
            e.max = e.min;
        }
        ++e.points;
        for (int a = 0; a < 3; ++a) {
            e.centroid[a] += v[a];
            e.min[a] = std::min(e.min[a], v[a]);
            e.max[a] = std::max(e.max[a], v[a]);
        }
    }
    if (e.points == 0) {
        return e;
    }
    for (int a = 0; a < 3; ++a) {
        e.centroid[a] /= static_cast<double>(e.points);
    }
    e.aabb_volume = (e.max[0] - e.min[0]) * (e.max[1] - e.min[1]) * (e.max[2] - e.min[2]);
    double sum = 0;
    // The points extreme along 26 directions (axes, face and space diagonals) span a polytope
    // inside the hull; a point well inside it is no hull vertex, so qhull gets only the others
    // (the same hull, a fraction of the points and memory on solid clouds).
    std::array<double, 26 * 3> extreme{};
    std::array<double, 26> best;
    best.fill(-std::numeric_limits<double>::infinity());
    int dirs[26][3];
    for (int d = 0, i = 0; i < 27; ++i) {
        if (i != 13) {
            dirs[d][0] = i / 9 - 1;
            dirs[d][1] = i / 3 % 3 - 1;
            dirs[d][2] = i % 3 - 1;
            ++d;
        }
    }
    for (std::size_t k = 0; k < count; ++k) {
        const pcl::PointXYZ p = point(k);
        if (!is_finite(p)) {
            continue;
        }
        const double v[3] = {p.x, p.y, p.z};
        const double dx = v[0] - e.centroid[0], dy = v[1] - e.centroid[1],
                     dz = v[2] - e.centroid[2];
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        sum += r;
        e.max_radius = std::max(e.max_radius, r);
        for (int d = 0; d < 26; ++d) {
            const double s = dirs[d][0] * v[0] + dirs[d][1] * v[1] + dirs[d][2] * v[2];
            if (s > best[d]) {
                best[d] = s;
                std::copy(v, v + 3, &extreme[3 * d]);
            }
        }
    }
    e.mean_radius = sum / static_cast<double>(e.points);
    std::vector<double> inner(extreme.begin(), extreme.end());
    const std::vector<std::array<double, 4>> planes = hull_planes(inner);
    // Kept unless inside every plane by more than a margin far above the planes' rounding.
    double scale = 0;
    for (int a = 0; a < 3; ++a) {
        scale = std::max({scale, std::abs(e.min[a]), std::abs(e.max[a])});
    }
    const double margin = 1e-9 * scale;
    std::vector<double> xyz;
    for (std::size_t k = 0; k < count; ++k) {
        const pcl::PointXYZ p = point(k);
        if (!is_finite(p)) {
            continue;
        }
        const double v[3] = {p.x, p.y, p.z};
        bool inside = !planes.empty();
        for (const auto& pl : planes) {
            if (pl[0] * v[0] + pl[1] * v[1] + pl[2] * v[2] + pl[3] > -margin) {
                inside = false;
                break;
            }
        }
        if (!inside) {
            xyz.insert(xyz.end(), {v[0], v[1], v[2]});
        }
    }
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
