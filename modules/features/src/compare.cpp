#include <algorithm>
#include <cmath>
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
    s.points = d.size();
    if (d.empty()) {
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

}  // namespace

void CompareParams::validate() const {
    if (!(tau > 0) || !std::isfinite(tau)) {
        throw InvalidArgument("compare: tau must be > 0, got " + format_number(tau));
    }
    if (!(voxel > 0) || !std::isfinite(voxel)) {
        throw InvalidArgument("compare: voxel must be > 0, got " + format_number(voxel));
    }
}

CompareResult compare(const Cloud& a, const Cloud& b, const CompareParams& params) {
    params.validate();
    CompareResult r;
    r.a_to_b = direction(a, b, params.tau);
    r.b_to_a = direction(b, a, params.tau);
    r.chamfer = r.a_to_b.mean + r.b_to_a.mean;
    r.precision = r.a_to_b.within_tau;
    r.recall = r.b_to_a.within_tau;
    r.fscore =
        r.precision + r.recall > 0 ? 2 * r.precision * r.recall / (r.precision + r.recall) : 0.0;
    const auto va = voxels(a, params.voxel), vb = voxels(b, params.voxel);
    std::vector<std::tuple<std::int64_t, std::int64_t, std::int64_t>> shared;
    std::set_intersection(va.begin(), va.end(), vb.begin(), vb.end(), std::back_inserter(shared));
    r.b_voxels = vb.size();
    r.shared_voxels = shared.size();
    r.interior_coverage =
        vb.empty() ? 0.0 : static_cast<double>(shared.size()) / static_cast<double>(vb.size());
    return r;
}

}  // namespace pc::features
