#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include <pc/core/error.h>
#include <pc/core/stats.h>
#include <pc/features/compare.h>
#include <pc/search/grid.h>

namespace pc::features {

namespace {

DirectionStats direction(const Cloud& from, const Cloud& to, double tau) {
    DirectionStats s;
    std::vector<double> d;
    d.reserve(from.size());
    bool to_empty = true;
    for (const auto& p : to.points) {
        to_empty = to_empty && !is_finite(p);
    }
    if (!to_empty) {
        const search::Grid grid(to, search::Grid::suggest_cell(to));
#pragma omp parallel
        {
            std::vector<std::uint32_t> idx;
            std::vector<double> d2;
            std::vector<double> local;
#pragma omp for schedule(static) nowait
            for (std::int64_t i = 0; i < static_cast<std::int64_t>(from.size()); ++i) {
                grid.knn_point(from[i], 1, idx, d2);
                if (!d2.empty()) {
                    local.push_back(std::sqrt(d2[0]));
                }
            }
#pragma omp critical
            d.insert(d.end(), local.begin(), local.end());
        }
    }
    for (const auto& p : from.points) {
        s.points += is_finite(p);
    }
    if (d.empty()) {  // nothing to measure to (or from): distances undefined, not 0
        s.mean = s.median = s.rms = s.max = std::numeric_limits<double>::quiet_NaN();
        return s;
    }
    std::sort(d.begin(), d.end());  // thread order must not change the sums
    double sum = 0, sq = 0;
    std::size_t within = 0;
    for (double v : d) {
        sum += v;
        sq += v * v;
        within += v <= tau;
    }
    const auto n = static_cast<double>(d.size());
    s.mean = sum / n;
    s.rms = std::sqrt(sq / n);
    s.max = d.back();
    s.within_tau = static_cast<double>(within) / n;
    s.median = median(d);
    return s;
}

std::vector<std::tuple<std::int64_t, std::int64_t, std::int64_t>> voxels(const Cloud& c, double v) {
    std::vector<std::tuple<std::int64_t, std::int64_t, std::int64_t>> out;
    out.reserve(c.size());
    for (const auto& p : c.points) {
        if (is_finite(p)) {
            out.emplace_back(static_cast<std::int64_t>(std::floor(p.x / v)),
                             static_cast<std::int64_t>(std::floor(p.y / v)),
                             static_cast<std::int64_t>(std::floor(p.z / v)));
        }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

/// The finite points' bounding box (min, max); min > max when there is none.
std::pair<pcl::PointXYZ, pcl::PointXYZ> bounds(const Cloud& c) {
    constexpr float kInf = std::numeric_limits<float>::infinity();
    pcl::PointXYZ lo(kInf, kInf, kInf), hi(-kInf, -kInf, -kInf);
    for (const auto& p : c.points) {
        if (is_finite(p)) {
            lo = pcl::PointXYZ(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
            hi = pcl::PointXYZ(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
        }
    }
    return {lo, hi};
}

double box_overlap(const Cloud& a, const Cloud& b) {
    const auto [alo, ahi] = bounds(a);
    const auto [blo, bhi] = bounds(b);
    double f = 1;
    for (int k = 0; k < 3; ++k) {
        const double lo = std::max(alo.data[k], blo.data[k]);
        const double hi = std::min(ahi.data[k], bhi.data[k]);
        const double shorter =
            std::min(double(ahi.data[k]) - alo.data[k], double(bhi.data[k]) - blo.data[k]);
        if (!(hi >= lo)) {
            return 0;  // disjoint on this axis, or a cloud without points
        }
        f *= shorter > 0 ? (hi - lo) / shorter : 1.0;
    }
    return f;
}

}  // namespace

std::vector<std::string> compare_warnings(const CompareResult& r, const CompareParams& params) {
    std::vector<std::string> w;
    if (r.a_to_b.points == 0 || r.b_to_a.points == 0) {
        w.push_back(std::string(r.a_to_b.points == 0 ? "A" : "B") +
                    " has no finite point: distances are undefined (null), scores 0");
        return w;
    }
    if (r.box_overlap < 0.25) {
        w.push_back("the clouds barely overlap (their bounding boxes share " +
                    format_number(std::round(r.box_overlap * 1000) / 10) +
                    " % of the smaller one): are they in one frame? (pc_transform --nerfstudio)");
    } else if (r.fscore < 0.01) {
        w.push_back("almost no point lies within tau = " + format_number(params.tau) +
                    " of the other cloud (F-score " + format_number(r.fscore) +
                    "): is tau in the clouds' units, and are they in one frame?");
    }
    return w;
}

void CompareParams::validate() const {
    if (!(tau > 0) || !std::isfinite(tau)) {
        throw InvalidArgument("compare: tau must be > 0, got " + format_number(tau));
    }
    if (!(voxel > 0) || !std::isfinite(voxel)) {
        throw InvalidArgument("compare: voxel must be > 0, got " + format_number(voxel));
    }
}

CompareResult compare(const Cloud& a,
                      const Cloud& b,
                      const CompareParams& params,
                      const std::function<void(const std::string&)>& progress) {
    params.validate();
    const auto say = [&](const std::string& what) {
        if (progress) {
            progress(what);
        }
    };
    CompareResult r;
    r.a_to_b = direction(a, b, params.tau);
    say("A to B: " + std::to_string(r.a_to_b.points) + " distances");
    r.b_to_a = direction(b, a, params.tau);
    say("B to A: " + std::to_string(r.b_to_a.points) + " distances");
    r.chamfer = r.a_to_b.mean + r.b_to_a.mean;
    r.precision = r.a_to_b.within_tau;
    r.recall = r.b_to_a.within_tau;
    r.fscore =
        r.precision + r.recall > 0 ? 2 * r.precision * r.recall / (r.precision + r.recall) : 0.0;
    r.box_overlap = box_overlap(a, b);
    const auto va = voxels(a, params.voxel), vb = voxels(b, params.voxel);
    std::vector<std::tuple<std::int64_t, std::int64_t, std::int64_t>> shared;
    std::set_intersection(va.begin(), va.end(), vb.begin(), vb.end(), std::back_inserter(shared));
    r.b_voxels = vb.size();
    r.shared_voxels = shared.size();
    r.interior_coverage =
        vb.empty() ? 0.0 : static_cast<double>(shared.size()) / static_cast<double>(vb.size());
    say("coverage: " + std::to_string(r.shared_voxels) + " of " + std::to_string(r.b_voxels) +
        " voxels of B");
    return r;
}

}  // namespace pc::features
