#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <optional>
#include <queue>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <pc/core/error.h>
#include <pc/core/labels.h>
#include <pc/core/radix_sort.h>
#include <pc/core/stats.h>
#include <pc/search/grid.h>
#include <pc/search/spacing.h>
#include <pc/segmentation/core_split.h>

namespace pc::segmentation {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
/// Step 4's tags in a core root's forest entry: the entry holds the core's size or, once numbered,
/// its part number (kValue bits; clustered points are counted below kNumbered).
constexpr std::uint32_t kRoot = 0x80000000u;
constexpr std::uint32_t kNumbered = 0x40000000u;
constexpr std::uint32_t kValue = kNumbered - 1;

/// The points' cluster ids: a 4-byte word in each of their records (read where it is, it moves
/// with its record).
struct LabelWords {
    std::uint8_t* base = nullptr;
    std::size_t stride = 0;
    std::uint32_t offset = 0;
    [[nodiscard]] std::uint32_t operator[](std::size_t k) const {
        std::uint32_t v = 0;
        std::memcpy(&v, base + k * stride + offset, sizeof v);
        return v;
    }
    void set(std::size_t k, std::uint32_t v) const {
        std::memcpy(base + k * stride + offset, &v, sizeof v);
    }
};

/// Parts the records: those `first(i)` holds for (`count` of them) go before the others, each
/// part keeping its order; `back`: the reverse. One place per record; `first` is asked once per
/// record, in order.
template <class First>
void part_records(XyzRecords& records, std::size_t count, First&& first, bool back) {
    std::vector<std::uint32_t> to(records.size);
    auto a = std::uint32_t{0}, b = static_cast<std::uint32_t>(count);
    for (std::uint32_t i = 0; i < records.size; ++i) {
        const std::uint32_t at = first(i) ? a++ : b++;
        to[back ? at : i] = back ? i : at;
    }
    permute_records(records, to);
}

/// Puts core_split's per-point arrays (`part`, `depth` and `index`) and the points' records back
/// in point order after it worked in cell order. The compacted points' cloud indices (`index`,
/// below n) rise in point order, so a point's place is the number of indices below its own: a
/// bit per cloud point and a running count per 64 of them give it without a sort. Each array
/// and the records are sorted where they are by those places (permute_records(): cache-aware,
/// where walking the permutation's cycles waits on memory at every step), the places counted
/// again before each sort, which consumes them; `index` goes last. No second array beside them.
void back_to_point_order(std::vector<std::uint32_t>& index,
                         std::size_t n,
                         std::vector<std::uint32_t>& part,
                         std::vector<float>& depth,
                         XyzRecords& records) {
    const std::size_t m = index.size();
    std::vector<std::uint64_t> bits(n / 64 + 1, 0);
    for (const std::uint32_t i : index) {
        bits[i / 64] |= std::uint64_t{1} << (i % 64);
    }
    std::vector<std::uint32_t> below(bits.size(), 0);
    for (std::size_t w = 1; w < bits.size(); ++w) {
        below[w] = below[w - 1] + static_cast<std::uint32_t>(std::popcount(bits[w - 1]));
    }
    std::vector<std::uint32_t> place(m);
    const auto count_places = [&] {
        for (std::size_t k = 0; k < m; ++k) {
            const std::uint32_t i = index[k];
            const std::uint64_t lower = bits[i / 64] & ((std::uint64_t{1} << (i % 64)) - 1);
            place[k] = below[i / 64] + static_cast<std::uint32_t>(std::popcount(lower));
        }
        return std::span<std::uint32_t>(place);
    };
    permute_records(part.data(), sizeof(std::uint32_t), count_places());
    permute_records(depth.data(), sizeof(float), count_places());
    permute_records(records, count_places());
    permute_records(index.data(), sizeof(std::uint32_t), count_places());
}

/// The fruit radius from the curvature of hollow surfaces: least-squares spheres through patches
/// (same cluster, within 8 s) around up to 2000 evenly strided points; the median radius of the
/// patches that are spherical (RMS < 0.1 × radius) and curved (radius < 40 s). Also returns the
/// points of a typical fruit: half of its sphere at the patches' median areal density. {0, 0} when
/// fewer than 20 patches qualify.
std::pair<double, double> radius_from_patches(
    const XyzView& pts,
    const LabelWords& lab,
    const std::vector<std::vector<std::uint32_t>>& members,
    double s) {
    std::vector<std::uint32_t> surface;  // positions in `pts`: a view of them, no copy
    for (const auto& m : members) {
        surface.insert(surface.end(), m.begin(), m.end());
    }
    const double reach = 8 * s;
    if (surface.size() < 20 || !(reach > 0)) {
        return {0, 0};
    }
    const XyzView view = pts.subset(surface);
    const search::Grid grid(view, reach);
    const std::size_t stride = std::max<std::size_t>(1, surface.size() / 2000);
    std::vector<double> radii, density;
    std::vector<std::uint32_t> patch;
    for (std::size_t q = 0; q < surface.size(); q += stride) {
        patch.clear();
        const std::uint32_t owner = lab[surface[q]];
        grid.for_each_within(view[q], reach, [&](std::uint32_t j, double) {
            if (lab[surface[j]] == owner) {
                patch.push_back(j);
            }
        });
        if (patch.size() < 20) {
            continue;
        }
        const Sphere f = fit_sphere(view, patch);
        if (f.ok && f.rms < 0.1 * f.radius && f.radius < 40 * s) {
            radii.push_back(f.radius);
            density.push_back(static_cast<double>(patch.size()) /
                              (3.141592653589793 * reach * reach));
        }
    }
    if (radii.size() < 20) {
        return {0, 0};
    }
    const double radius = median(radii);
    return {radius, 0.5 * median(density) * 4 * 3.141592653589793 * radius * radius};
}

/// Hollow clusters cut into spheres; see core_split().
void split_hollow_clusters(const XyzView& pts,
                           const LabelWords& lab,
                           const std::vector<std::uint8_t>& hollow,
                           const CoreSplitParams& params,
                           CoreSplitResult& r,
                           std::vector<std::uint32_t>& part,
                           std::vector<std::uint32_t>& parts) {
    const auto clusters = static_cast<std::uint32_t>(hollow.size());
    std::vector<std::vector<std::uint32_t>> members(clusters);
    for (std::size_t k = 0; k < pts.size; ++k) {
        if (hollow[lab[k]]) {
            members[lab[k]].push_back(static_cast<std::uint32_t>(k));
        }
    }
    std::vector<Sphere> fits(clusters);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t c = 0; c < static_cast<std::int64_t>(clusters); ++c) {
        fits[c] = fit_sphere(pts, members[c]);
    }
    // The fruit radius from the curvature of the surfaces (not from clusters that look like one
    // fruit: a compact bunch fits a larger sphere just as well).
    double typical = 0;
    std::tie(r.hollow_radius, typical) = radius_from_patches(pts, lab, members, r.spacing);
    if (!(r.hollow_radius > 0)) {
        return;
    }
    std::vector<std::vector<std::uint32_t>> cut(clusters);
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t c = 0; c < static_cast<std::int64_t>(clusters); ++c) {
        const Sphere& f = fits[c];
        const bool single = f.ok && f.rms < 0.15 * f.radius &&
                            f.radius <= params.spheres.radius_high * r.hollow_radius;
        if (!members[c].empty() && !single) {
            cut[c] =
                split_hollow(pts, members[c], r.hollow_radius, r.spacing, typical, params.spheres);
        }
    }
    for (std::uint32_t c = 0; c < clusters; ++c) {
        if (cut[c].empty()) {
            continue;
        }
        const std::uint32_t count = *std::max_element(cut[c].begin(), cut[c].end()) + 1;
        if (count >= 2) {
            for (std::size_t q = 0; q < members[c].size(); ++q) {
                part[members[c][q]] = cut[c][q];
            }
            parts[c] = count;
            ++r.hollow_splits;
            ++r.splits;
        }
    }
}

/// Parts whose points lie on one sphere of about the fruit radius are pieces of one fruit that
/// occlusion cut apart: parts whose fitted spheres (RMS < 0.15 × radius, radius within
/// 0.75..1.33 R) have centres closer than R / 2 are joined. `labels` are 1..count (0 = noise).
void merge_hollow_fragments(const XyzView& pts,
                            std::vector<std::uint32_t>& labels,
                            std::uint32_t count,
                            double fruit_radius,
                            std::uint32_t& merged) {
    std::vector<std::vector<std::uint32_t>> members(std::size_t{count} + 1);
    for (std::size_t k = 0; k < labels.size(); ++k) {
        members[labels[k]].push_back(static_cast<std::uint32_t>(k));
    }
    std::vector<Sphere> fits(members.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t l = 1; l < static_cast<std::int64_t>(members.size()); ++l) {
        const Sphere f = fit_sphere(pts, members[l]);
        if (f.ok && f.rms < 0.15 * f.radius && f.radius >= 0.75 * fruit_radius &&
            f.radius <= 1.33 * fruit_radius) {
            fits[l] = f;
        }
    }
    std::vector<std::uint32_t> order;
    for (std::uint32_t l = 1; l < members.size(); ++l) {
        if (fits[l].ok) {
            order.push_back(l);
        }
    }
    std::sort(order.begin(), order.end(),
              [&](auto a, auto b) { return fits[a].centre[0] < fits[b].centre[0]; });
    std::vector<std::uint32_t> parent(members.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const double reach = 0.5 * fruit_radius;
    for (std::size_t a = 0; a < order.size(); ++a) {
        for (std::size_t b = a + 1; b < order.size(); ++b) {
            const auto& x = fits[order[a]].centre;
            const auto& y = fits[order[b]].centre;
            if (y[0] - x[0] > reach) {
                break;
            }
            const double d2 = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                              (x[2] - y[2]) * (x[2] - y[2]);
            if (d2 < reach * reach) {
                const auto ra = find_root(parent, order[a]), rb = find_root(parent, order[b]);
                if (ra != rb) {
                    parent[std::max(ra, rb)] = std::min(ra, rb);
                    ++merged;
                }
            }
        }
    }
    for (auto& l : labels) {
        l = l == 0 ? 0 : find_root(parent, l);
    }
}

/// Solid pieces of one fruit that poor masks cut apart: two parts (with some depth) are joined
/// while every point of their union lies within `extent` of the union's centroid (they fit in
/// one fruit), nearest centroids first. Whole touching fruit never fit: their union spans 2 R.
void merge_solid_fragments(const XyzView& pts,
                           const std::vector<float>& depth,
                           std::vector<std::uint32_t>& labels,
                           std::uint32_t count,
                           double extent,
                           std::uint32_t& merged) {
    std::vector<std::vector<std::uint32_t>> members(std::size_t{count} + 1);
    std::vector<std::uint8_t> solid(std::size_t{count} + 1, 0);
    for (std::size_t k = 0; k < labels.size(); ++k) {
        members[labels[k]].push_back(static_cast<std::uint32_t>(k));
        solid[labels[k]] |= depth[k] > 0;
    }
    std::vector<Eigen::Vector3d> sum(members.size(), Eigen::Vector3d::Zero());
    std::vector<std::uint32_t> order;
    for (std::uint32_t l = 1; l < members.size(); ++l) {
        for (auto k : members[l]) {
            const pcl::PointXYZ p = pts[k];
            sum[l] += Eigen::Vector3d(p.x, p.y, p.z);
        }
        if (solid[l] && !members[l].empty()) {
            order.push_back(l);
        }
    }
    const auto centroid = [&](std::uint32_t l) {
        return Eigen::Vector3d(sum[l] / static_cast<double>(members[l].size()));
    };
    std::sort(order.begin(), order.end(),
              [&](auto a, auto b) { return centroid(a).x() < centroid(b).x(); });
    std::vector<std::tuple<double, std::uint32_t, std::uint32_t>> pairs;
    for (std::size_t a = 0; a < order.size(); ++a) {
        const Eigen::Vector3d ca = centroid(order[a]);
        for (std::size_t b = a + 1; b < order.size(); ++b) {
            const Eigen::Vector3d cb = centroid(order[b]);
            if (cb.x() - ca.x() > 2 * extent) {
                break;
            }
            const double d = (ca - cb).norm();
            if (d < 2 * extent) {
                pairs.emplace_back(d, std::min(order[a], order[b]), std::max(order[a], order[b]));
            }
        }
    }
    std::sort(pairs.begin(), pairs.end());
    std::vector<std::uint32_t> parent(members.size());
    std::iota(parent.begin(), parent.end(), 0u);
    for (const auto& [d, a0, b0] : pairs) {
        const auto a = find_root(parent, a0), b = find_root(parent, b0);
        if (a == b) {
            continue;
        }
        const Eigen::Vector3d c =
            (sum[a] + sum[b]) / static_cast<double>(members[a].size() + members[b].size());
        bool fits = true;
        for (const auto* set : {&members[a], &members[b]}) {
            for (auto k : *set) {
                const pcl::PointXYZ p = pts[k];
                fits =
                    fits && (Eigen::Vector3d(p.x, p.y, p.z) - c).squaredNorm() <= extent * extent;
            }
        }
        if (fits) {
            const auto keep = std::min(a, b), gone = std::max(a, b);
            parent[gone] = keep;
            sum[keep] += sum[gone];
            members[keep].insert(members[keep].end(), members[gone].begin(), members[gone].end());
            members[gone].clear();
            ++merged;
        }
    }
    for (auto& l : labels) {
        l = l == 0 ? 0 : find_root(parent, l);
    }
}

}  // namespace

void CoreSplitParams::validate() const {
    const auto in = [](double v, double lo, double hi) { return v >= lo && v <= hi; };
    if (!in(core_fraction, 0.01, 0.99) || !in(boundary_radius, 1, 20) ||
        !in(boundary_offset, 0.01, 0.99) || !in(link, 1, 10) || !in(min_core_fraction, 0, 1) ||
        !in(min_relative_size, 0, 1) || !in(isotropy, 0, 1) || !in(fragment_extent, 0.1, 10)) {
        throw InvalidArgument(
            "core_split: core_fraction must be in [0.01, 0.99], boundary_radius in [1, 20], "
            "boundary_offset in [0.01, 0.99], link in [1, 10], min_core_fraction, "
            "min_relative_size "
            "and isotropy in [0, 1], fragment_extent in [0.1, 10]; got " +
            format_number(core_fraction) + ", " + format_number(boundary_radius) + ", " +
            format_number(boundary_offset) + ", " + format_number(link) + ", " +
            format_number(min_core_fraction) + ", " + format_number(min_relative_size) + ", " +
            format_number(isotropy) + ", " + format_number(fragment_extent));
    }
}

namespace {

/// The clustered points (a label other than 0, finite), in point order: point k is cloud point
/// index[k]; label l is cluster dense[l] (kNone: no clustered point), numbered 0..clusters-1 in
/// order of first appearance.
struct Clustered {
    std::vector<std::uint32_t> index, dense;
    std::uint32_t clusters = 0;
};

Clustered number_clusters(const XyzView& cloud, std::span<const std::uint32_t> label) {
    const std::size_t n = cloud.size;
    std::uint32_t max_label = 0;
    std::size_t clustered = 0;  // counted first: growing the index would leave 2x behind
    for (std::uint32_t i = 0; i < n; ++i) {
        max_label = std::max(max_label, label[i]);
        clustered += label[i] != 0 && is_finite(cloud[i]);
    }
    if (clustered > kValue) {
        throw InvalidArgument("core_split: at most 2^30 - 1 clustered points, got " +
                              std::to_string(clustered));
    }
    Clustered c;
    c.dense.assign(std::size_t{max_label} + 1, kNone);
    c.index.reserve(clustered);
    for (std::uint32_t i = 0; i < n; ++i) {
        const std::uint32_t l = label[i];
        if (l != 0 && is_finite(cloud[i])) {
            if (c.dense[l] == kNone) {
                c.dense[l] = c.clusters++;
            }
            c.index.push_back(i);
        }
    }
    return c;
}

/// The labels over the whole cloud from each clustered point's `local` label, and the depths;
/// parts smaller than the size limits become noise, the rest are numbered by size.
CoreSplitResult finish(std::size_t n,
                       const Clustered& c,
                       std::vector<std::uint32_t>&& local,
                       std::vector<float>&& depth,
                       const CoreSplitParams& params,
                       CoreSplitResult&& r) {
    r.depth.assign(n, 0.0f);
    for (std::size_t k = 0; k < depth.size(); ++k) {
        r.depth[c.index[k]] = depth[k];
    }
    std::vector<float>().swap(depth);
    std::vector<std::uint32_t> out(n, 0);
    std::uint32_t top = 0;
    for (std::size_t k = 0; k < local.size(); ++k) {
        out[c.index[k]] = local[k];
        top = std::max(top, local[k]);
    }
    std::vector<std::uint32_t>().swap(local);
    std::uint32_t min_size = params.min_cluster_size;
    if (params.min_relative_size > 0) {
        std::vector<double> sizes(std::size_t{top} + 1, 0.0);
        for (auto l : out) {
            sizes[l] += 1;
        }
        std::vector<double> present;
        for (std::size_t l = 1; l < sizes.size(); ++l) {
            if (sizes[l] > 0) {
                present.push_back(sizes[l]);
            }
        }
        if (!present.empty()) {
            min_size = std::max(
                min_size,
                static_cast<std::uint32_t>(std::ceil(params.min_relative_size * median(present))));
        }
    }
    r.cluster_count = renumber_by_size(out, min_size);
    r.labels = std::move(out);
    return r;
}

/// core_split() over the clustered points' records `recs` (point k at record k, in point order;
/// sorted in cell order while it works, back in point order when it returns), each holding its
/// cluster (0..clusters-1) in the word at `label_offset`: each clustered point's label (1..,
/// before the size limits), its depth (`depth`) and the rest of `r`.
std::vector<std::uint32_t> split_clustered(XyzRecords& recs,
                                           std::uint32_t label_offset,
                                           std::size_t n,
                                           Clustered& points,
                                           std::vector<float>& depth,
                                           const CoreSplitParams& params,
                                           CoreSplitResult& r) {
    std::vector<std::uint32_t>& index = points.index;
    const LabelWords lab{recs.base, recs.stride, label_offset};
    const std::uint32_t clusters = points.clusters;
    const std::size_t m = index.size();
    const XyzView pts = recs.view();
    r.spacing = search::median_spacing(pts);
    const double s = r.spacing, rb = params.boundary_radius * s, link = params.link * s;
    const double cell = std::max(rb, link);
    // The points are renumbered in the search grid's cell order, so that the points a search
    // finds, and their entries in every per-point array, lie near each other in memory (in
    // point order, the core joining, the depths and the flood waited on memory: 1M -> 4M points
    // took 5x longer). The grid sorts the records themselves (no copy of the coordinates) and
    // serves steps 1 to 5. Where order decides a result (the flood's seeds, the cores' part
    // numbers, the sampled patches and the member lists), point order is used; the arrays and
    // the records return to it after step 5.
    std::optional<search::Grid> near;
    if (r.spacing > 0) {
        near.emplace(recs, cell);
        near->order_cells_by_index();  // equal cells in point order: the flood's ties as before
        std::vector<std::uint32_t> moved(m);  // the cluster ids moved with their records
        for (std::uint32_t q = 0; q < m; ++q) {
            moved[q] = index[near->index_of(q)];
        }
        index.swap(moved);
        near->renumber_by_position();
    }
    std::vector<std::uint32_t> part;  // part within the cluster, 0-based (the flood's result)
    std::vector<std::uint32_t> parts(clusters, 1);
    std::vector<std::uint8_t> hollow;  // per cluster, set once the depths are known
    depth.assign(m, 0.0f);  // per compacted point: distance to the nearest boundary point
    if (r.spacing > 0) {
        // 1. Boundary: neighbours of the same cluster lie mostly to one side. Swept cell by cell:
        //    the neighbour cells are found once per cell, not once per point.
        std::vector<std::uint8_t> boundary(m, 0);
        const double rb2 = rb * rb;
        const search::Grid& grid = *near;
        grid.sweep_cells([&](std::uint32_t c, const std::vector<std::uint32_t>& nb) {
            for (std::uint32_t sp = grid.cell_begin(c); sp < grid.cell_end(c); ++sp) {
                const std::uint32_t k = grid.index_of(sp);
                const float* p = grid.point(sp);
                // Offsets from p: their mean (one-sidedness) and their second moments (flatness).
                double sx = 0, sy = 0, sz = 0, xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
                std::size_t count = 0;
                for (std::uint32_t nc : nb) {
                    for (std::uint32_t t = grid.cell_begin(nc); t < grid.cell_end(nc); ++t) {
                        const float* q = grid.point(t);
                        const double ox = double{q[0]} - p[0], oy = double{q[1]} - p[1],
                                     oz = double{q[2]} - p[2];
                        if (ox * ox + oy * oy + oz * oz > rb2 || lab[t] != lab[k]) {
                            continue;
                        }
                        sx += ox;
                        sy += oy;
                        sz += oz;
                        xx += ox * ox;
                        xy += ox * oy;
                        xz += ox * oz;
                        yy += oy * oy;
                        yz += oy * oz;
                        zz += oz * oz;
                        ++count;
                    }
                }
                if (count < 8) {
                    boundary[k] = 1;
                    continue;
                }
                const double inv = 1.0 / static_cast<double>(count);
                const Eigen::Vector3d mean(sx * inv, sy * inv, sz * inv);
                Eigen::Matrix3d second;
                second << xx, xy, xz, xy, yy, yz, xz, yz, zz;
                const Eigen::Matrix3d cov = second * inv - mean * mean.transpose();
                const Eigen::Vector3d ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>()
                                               .computeDirect(cov, Eigen::EigenvaluesOnly)
                                               .eigenvalues();
                // A solid's interior: neighbours all around (centred) and in every direction
                // (isotropic).
                boundary[k] =
                    mean.norm() > params.boundary_offset * rb || ev[0] < params.isotropy * ev[2];
            }
        });
        // 2. Depth: distance to the nearest boundary point. The records are parted for it, the
        //    boundary points' first (each part in cell order): a grid sorts the boundary part in
        //    place (no copy of it), the interior part is looked up in order, and the records go
        //    back to cell order (where the search grid, kept for step 4, finds them).
        const auto e =
            static_cast<std::size_t>(std::count(boundary.begin(), boundary.end(), std::uint8_t{1}));
        if (e > 0 && e < m) {
            const auto on_boundary = [&](std::uint32_t k) { return boundary[k] != 0; };
            part_records(recs, e, on_boundary, false);
            XyzRecords edge = recs;
            edge.size = e;
            {  // the boundary records back in their order when the grid goes
                const search::Grid edges(edge, search::Grid::suggest_cell(edge.view(), 16));
                // The j-th interior point (record e + j) gets its depth in depth[j] first.
#pragma omp parallel
                {
                    std::vector<std::uint32_t> idx;
                    std::vector<double> d2;
#pragma omp for schedule(dynamic, 4096)
                    for (std::int64_t j = 0; j < static_cast<std::int64_t>(m - e); ++j) {
                        edges.knn_point(pts[e + static_cast<std::size_t>(j)], 1, idx, d2);
                        depth[static_cast<std::size_t>(j)] =
                            d2.empty() ? 0.0f : static_cast<float>(std::sqrt(d2[0]));
                    }
                }
            }
            // Spread to each point's own entry, from the last: entry j is read before any entry
            // at or below it is written.
            for (std::size_t k = m, left = m - e; k-- > 0;) {
                depth[k] = boundary[k] ? 0.0f : depth[--left];
            }
            part_records(recs, e, on_boundary, true);
        }
        // 3. Hollow clusters (under 5 % interior points: surfaces, where only contact zones look
        //    inside) and the fruit radius: the median over solid clusters of their greatest depth.
        std::vector<std::uint8_t>().swap(boundary);
        std::vector<double> deepest(clusters, 0.0), inside(clusters, 0.0), size(clusters, 0.0);
        for (std::size_t k = 0; k < m; ++k) {
            deepest[lab[k]] = std::max(deepest[lab[k]], double{depth[k]});
            inside[lab[k]] += depth[k] > 0;
            size[lab[k]] += 1;
        }
        hollow.assign(clusters, 0);
        std::vector<double> solid_depths;
        for (std::uint32_t c = 0; c < clusters; ++c) {
            hollow[c] = inside[c] < 0.05 * size[c];
            if (!hollow[c]) {
                solid_depths.push_back(deepest[c]);
            }
        }
        if (!solid_depths.empty()) {
            std::vector<double> copy = solid_depths;
            // The best-kept fruit: what a whole fruit measures when many are fragments.
            r.largest_depth = percentile(copy, 98);
            r.fruit_radius = median(solid_depths);
        }
        const double core_depth = params.core_fraction * r.fruit_radius;
        // 4. Cores: deep points joined through `link` (union-find); small ones are dropped.
        const auto point_at = [&](std::size_t k) {
            const float* p = grid.point(static_cast<std::uint32_t>(k));
            return pcl::PointXYZ(p[0], p[1], p[2]);
        };
        std::vector<std::uint32_t> parent(m);
        std::iota(parent.begin(), parent.end(), 0u);
        const auto is_core = [&](std::size_t k) {
            return core_depth > 0 && !hollow[lab[k]] && depth[k] >= core_depth;
        };
        for (std::size_t k = 0; k < m; ++k) {
            if (is_core(k)) {
                // Each pair once (from its lower point): the sets, and their smallest members as
                // roots, do not depend on the order of the unions.
                const auto later_core = [&](std::uint32_t j) {
                    return j > k && lab[j] == lab[k] && is_core(j);
                };
                grid.for_each_within_if(
                    point_at(k), link, later_core, [&](std::uint32_t j, double) {
                        const auto a = find_root(parent, static_cast<std::uint32_t>(k)),
                                   b = find_root(parent, j);
                        parent[std::max(a, b)] = std::min(a, b);
                    });
            }
        }
        // Every entry is pointed at its root (ascending: a root is its set's smallest member,
        // as unions link the larger root under the smaller). A core root's own entry then holds
        // kRoot | the core's size, and once numbered kRoot | kNumbered | its part number within
        // its cluster: no per-root table beside the forest.
        for (std::size_t k = 0; k < m; ++k) {
            parent[k] = parent[parent[k]];
        }
        const auto root_of = [&](std::size_t k) {
            return (parent[k] & kRoot) != 0 ? static_cast<std::uint32_t>(k) : parent[k];
        };
        for (std::size_t k = 0; k < m; ++k) {
            if (is_core(k)) {
                std::uint32_t& info = parent[root_of(k)];
                info = ((info & kRoot) != 0 ? info : kRoot) + 1;
            }
        }
        const double ideal = 4.0 / 3.0 * 3.141592653589793 * std::pow(core_depth / s, 3);
        const auto min_core =
            static_cast<std::uint32_t>(std::max(1.0, std::floor(params.min_core_fraction * ideal)));
        // Within its cluster, a core's part number is its rank by its first point in point order
        // (the points are in cell order here): the kept cores are listed, their entries holding
        // their place in the list meanwhile.
        std::vector<std::pair<std::uint32_t, std::uint32_t>> kept;  // first cloud index, root
        for (std::size_t k = 0; k < m; ++k) {
            if ((parent[k] & kRoot) != 0 && (parent[k] & kValue) >= min_core) {
                parent[k] = kRoot | kNumbered | static_cast<std::uint32_t>(kept.size());
                kept.emplace_back(kNone, static_cast<std::uint32_t>(k));
            }
        }
        for (std::size_t k = 0; k < m; ++k) {
            const std::uint32_t info = is_core(k) ? parent[root_of(k)] : 0;
            if ((info & kNumbered) != 0) {
                auto& first = kept[info & kValue].first;
                first = std::min(first, index[k]);
            }
        }
        std::sort(kept.begin(), kept.end(), [&](const auto& a, const auto& b) {
            return std::pair(lab[a.second], a.first) < std::pair(lab[b.second], b.first);
        });
        std::vector<std::uint32_t> cores(clusters, 0);
        for (const auto& [first, root] : kept) {
            parent[root] = kRoot | kNumbered | cores[lab[root]]++;
        }
        std::vector<std::pair<std::uint32_t, std::uint32_t>>().swap(kept);
        // 5. Marker watershed from the cores of clusters with two or more, deepest points first.
        //    Clusters never exchange points, so each floods on its own, in parallel (the order
        //    within a cluster, hence the result, is the same as one flood over all of them).
        //    Each point's part so far (kNone: none yet) is written over the forest, descending:
        //    a root's entry is read by its members, all above it, before it is replaced.
        const auto seeded = [&](std::size_t k) { return cores[lab[k]] >= 2 && is_core(k); };
        std::vector<std::uint32_t> seed_start(std::size_t{clusters} + 1,
                                              0);  // seeds per cluster, flat
        for (std::size_t k = m; k-- > 0;) {
            const std::uint32_t info = parent[root_of(k)];
            parent[k] = seeded(k) && (info & kNumbered) != 0 ? info & kValue : kNone;
            seed_start[lab[k] + 1] += parent[k] != kNone;
        }
        std::vector<std::uint32_t> assigned = std::move(parent);
        std::partial_sum(seed_start.begin(), seed_start.end(), seed_start.begin());
        std::vector<std::uint32_t> seeds(seed_start.back());
        {
            std::vector<std::uint32_t> at(seed_start.begin(), seed_start.end() - 1);
            for (std::size_t k = 0; k < m; ++k) {  // in cell order: put in point order by the flood
                if (assigned[k] != kNone) {
                    seeds[at[lab[k]]++] = static_cast<std::uint32_t>(k);
                }
            }
        }
#pragma omp parallel for schedule(dynamic, 1)
        for (std::int64_t c = 0; c < static_cast<std::int64_t>(clusters); ++c) {
            using Item =
                std::tuple<float, std::uint64_t, std::uint32_t>;  // depth, ~sequence, point
            std::priority_queue<Item> heap;
            std::uint64_t seq = 0;
            // Seeded in point order (cloud indices rise with it): equal depths pop first-seeded
            // first.
            const auto first = seeds.begin() + seed_start[static_cast<std::size_t>(c)];
            const auto last = seeds.begin() + seed_start[static_cast<std::size_t>(c) + 1];
            std::sort(first, last,
                      [&](std::uint32_t a, std::uint32_t b) { return index[a] < index[b]; });
            for (std::uint32_t q = seed_start[static_cast<std::size_t>(c)];
                 q < seed_start[static_cast<std::size_t>(c) + 1]; ++q) {
                const std::uint32_t k = seeds[q];
                heap.emplace(depth[k], ~seq++, k);
            }
            while (!heap.empty()) {
                const std::uint32_t k = std::get<2>(heap.top());
                heap.pop();
                // The cluster test first: other clusters' entries belong to other threads.
                const auto unreached_yet = [&](std::uint32_t j) {
                    return lab[j] == lab[k] && assigned[j] == kNone;
                };
                grid.for_each_within_if(point_at(k), link, unreached_yet,
                                        [&](std::uint32_t j, double) {
                                            assigned[j] = assigned[k];
                                            heap.emplace(depth[j], ~seq++, j);
                                        });
            }
        }
        // Points the flood could not reach (apart by more than `link`): the part of the nearest
        // assigned point of their cluster, found by repeating the search with growing steps
        // (kept aside: `assigned` must not see them). Not found at all: part 0.
        std::vector<std::pair<std::uint32_t, std::uint32_t>> unreached;  // point, part
        for (std::size_t k = 0; k < m; ++k) {
            if (cores[lab[k]] >= 2 && assigned[k] == kNone) {
                unreached.emplace_back(static_cast<std::uint32_t>(k), 0);
            }
        }
        for (double step = 2 * link; step <= grid.cell() && !unreached.empty(); step *= 2) {
            bool left = false;
            for (auto& [k, to] : unreached) {
                double best = std::numeric_limits<double>::infinity();
                grid.for_each_within(point_at(k), step, [&](std::uint32_t j, double d2) {
                    if (assigned[j] != kNone && lab[j] == lab[k] &&
                        (d2 < best || (d2 == best && assigned[j] < to))) {
                        best = d2;
                        to = assigned[j];
                    }
                });
                left = left || best == std::numeric_limits<double>::infinity();
            }
            if (!left) {
                break;
            }
        }
        near.reset();  // searched for the last time: freed before the hollow clusters' lists
        part = std::move(assigned);  // the flood's parts; unassigned points: part 0
        for (auto& v : part) {
            v = v == kNone ? 0 : v;
        }
        for (const auto& [k, to] : unreached) {
            part[k] = to;
        }
        std::vector<std::pair<std::uint32_t, std::uint32_t>>().swap(unreached);
        std::vector<std::uint32_t>().swap(seeds);
        back_to_point_order(index, n, part, depth, recs);
        for (std::uint32_t c = 0; c < clusters; ++c) {
            parts[c] = std::max(1u, cores[c]);
            r.splits += cores[c] >= 2;
        }
        if (params.hollow) {
            split_hollow_clusters(pts, lab, hollow, params, r, part, parts);
        }
    }
    // Labels: cluster c's parts get consecutive numbers, then renumbered by size.
    std::vector<std::uint32_t> first(clusters + 1, 0);
    for (std::uint32_t c = 0; c < clusters; ++c) {
        first[c + 1] = first[c] + parts[c];
    }
    if (part.size() != m) {
        part.assign(m, 0);  // no spacing: no parts
    }
    std::vector<std::uint32_t> local = std::move(part);  // the labels, on the compacted points
    for (std::size_t k = 0; k < m; ++k) {
        local[k] = first[lab[k]] + std::min(local[k], parts[lab[k]] - 1) + 1;
    }
    if (r.hollow_radius > 0) {
        merge_hollow_fragments(pts, local, first[clusters], r.hollow_radius, r.merged_fragments);
    }
    if (r.largest_depth > 0 && params.merge_fragments) {
        merge_solid_fragments(pts, depth, local, first[clusters],
                              params.fragment_extent * (r.largest_depth + 1.5 * r.spacing),
                              r.merged_fragments);
    }
    return local;
}

}  // namespace

CoreSplitResult core_split(const XyzView& cloud,
                           std::vector<std::uint32_t> labels,
                           const CoreSplitParams& params) {
    params.validate();
    const std::size_t n = cloud.size;
    if (labels.size() != n) {
        throw InvalidArgument("core_split: labels must be one per point (" + std::to_string(n) +
                              "), got " + std::to_string(labels.size()));
    }
    Clustered c = number_clusters(cloud, labels);
    // The clustered points as records of their coordinates and cluster, in point order: the
    // grids sort this copy.
    constexpr std::size_t kStride = 4 * sizeof(float);
    const std::size_t m = c.index.size();
    std::vector<float> copy(4 * m);
    const LabelWords cluster{reinterpret_cast<std::uint8_t*>(copy.data()), kStride,
                             3 * sizeof(float)};
    for (std::size_t k = 0; k < m; ++k) {
        const pcl::PointXYZ p = cloud[c.index[k]];
        copy[4 * k] = p.x;
        copy[4 * k + 1] = p.y;
        copy[4 * k + 2] = p.z;
        cluster.set(k, c.dense[labels[c.index[k]]]);
    }
    std::vector<std::uint32_t>().swap(labels);  // copied into the records: freed before the steps
    std::vector<std::uint32_t>().swap(c.dense);
    CoreSplitResult r;
    std::vector<float> depth;
    XyzRecords records(cluster.base, kStride, m, 0);
    std::vector<std::uint32_t> local =
        split_clustered(records, cluster.offset, n, c, depth, params, r);
    std::vector<float>().swap(copy);
    return finish(n, c, std::move(local), std::move(depth), params, std::move(r));
}

}  // namespace pc::segmentation
