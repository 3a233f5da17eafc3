#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>

#include <pc/core/error.h>
#include <pc/core/labels.h>
#include <pc/core/stats.h>
#include <pc/search/grid.h>
#include <pc/search/spacing.h>
#include <pc/segmentation/sphere_vote.h>

namespace pc::segmentation {

namespace {

using V3 = Eigen::Vector3d;

V3 vec(const pcl::PointXYZ& p) { return {p.x, p.y, p.z}; }
pcl::PointXYZ point(const V3& v) {
    return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

/// The sampled points: positions in the cloud, their view and their DBSCAN labels.
struct Sample {
    std::vector<std::uint32_t> at;
    XyzView view;
    std::vector<std::uint32_t> label;
};

/// Unit normals and their weights 1 − λ₁/λ₂ (0: no normal) of the sampled points.
struct Normals {
    std::vector<V3> n;
    std::vector<float> w;
    std::vector<float> offset;  ///< |neighbourhood centroid − point| / h (half a ball: 3/8)
    /// The point moved along its plane to above its neighbourhood's centroid: where the normal
    /// belongs when sampling is uneven (a plane fitted to a patch denser on one side is the
    /// surface's tangent plane at the centroid, not at the point)
    std::vector<V3> foot;
    double scale = 0;
};

/// Normals of every `every`-th sampled point (the others get weight 0), from all the sample's
/// points, whatever their cluster: DBSCAN may cut one fruit into slices (scan lines, the sparse
/// side of an SfM fruit), and a plane fitted to a slice alone lies across it.
Normals fit_normals(const Sample& s, double h, std::size_t every = 1) {
    const search::Grid grid(s.view, h);
    Normals out{std::vector<V3>(s.view.size, V3::Zero()), std::vector<float>(s.view.size, 0.0f),
                std::vector<float>(s.view.size, 0.0f), std::vector<V3>(s.view.size, V3::Zero()), h};
#pragma omp parallel for schedule(dynamic, 256)
    for (std::int64_t ii = 0; ii < static_cast<std::int64_t>(s.view.size); ii += every) {
        const auto i = static_cast<std::uint32_t>(ii);
        const pcl::PointXYZ p = s.view[i];
        const V3 o = vec(p);
        V3 sum = V3::Zero();
        Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
        int n = 0;
        grid.for_each_within(p, h, [&](std::uint32_t j, double) {
            const V3 q = vec(s.view[j]) - o;
            sum += q;
            m += q * q.transpose();
            ++n;
        });
        if (n < 6) {
            continue;
        }
        const V3 c = sum / n;
        const Eigen::Matrix3d cov = m / n - c * c.transpose();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
        const V3 l = es.eigenvalues();
        if (!(l(1) > 0)) {
            continue;
        }
        out.n[i] = es.eigenvectors().col(0);
        out.foot[i] = o + c - c.dot(out.n[i]) * out.n[i];
        out.w[i] = static_cast<float>(std::clamp(1.0 - l(0) / l(1), 0.0, 1.0));
        out.offset[i] = static_cast<float>(c.norm() / h);
    }
    return out;
}

/// Every `stride`-th of the points `at` (positions in `points`), with their labels. The view
/// points into `at`: rebuild it (points.subset) after copying or moving the sample.
Sample thinned(const XyzView& points,
               const std::vector<std::uint32_t>& at,
               const std::vector<std::uint32_t>& labels,
               std::size_t stride) {
    Sample s;
    for (std::size_t k = 0; k < at.size(); k += std::max<std::size_t>(stride, 1)) {
        s.at.push_back(at[k]);
        s.label.push_back(labels[at[k]]);
    }
    s.view = points.subset(s.at);
    return s;
}

/// The outer layer of solid fruit (neighbourhoods within 3 spacings lying to one side: half a
/// ball has offset 3/8): a surface the rest of the method treats like any other.
Sample shell_of(const XyzView& points,
                const Sample& s,
                const std::vector<std::uint32_t>& labels,
                double spacing) {
    const Normals nb = fit_normals(s, 3 * spacing);
    std::vector<std::uint32_t> outer;
    for (std::size_t i = 0; i < s.view.size; ++i) {
        if (nb.offset[i] > 0.2f) {
            outer.push_back(s.at[i]);
        }
    }
    return thinned(points, outer, labels, 1);
}

/// About one in `m` of the sample's points, with their labels, picked by a hash of their place
/// in it (a stride over a lattice's points can keep whole planes of it).
Sample one_in(const XyzView& points,
              const Sample& s,
              const std::vector<std::uint32_t>& labels,
              std::size_t m) {
    std::vector<std::uint32_t> kept;
    for (std::size_t k = 0; k < s.at.size(); ++k) {
        if ((k * 0x9E3779B97F4A7C15ULL >> 32) % m == 0) {
            kept.push_back(s.at[k]);
        }
    }
    return thinned(points, kept, labels, 1);
}

/// The mean number of the sample's points within `h` of 64 of them, spread through it.
double mean_neighbours(const Sample& s, double h) {
    const search::Grid grid(s.view, h);
    const std::size_t step = std::max<std::size_t>(1, s.view.size / 64);
    std::size_t found = 0, asked = 0;
    for (std::uint32_t i = 0; i < s.view.size; i += step, ++asked) {
        grid.for_each_within(s.view[i], h, [&](std::uint32_t, double) { ++found; });
    }
    return asked == 0 ? 0.0 : static_cast<double>(found) / static_cast<double>(asked);
}

/// The most neighbours, on average, the solid test fits each of its neighbourhoods to.
constexpr double kSolidNeighbours = 1000;

bool differs(double a, double b) { return std::abs(std::log(a / b)) > std::log(1.3); }

/// A solid cloud: more than 15 % of the points with a neighbourhood have one that is isotropic
/// (the inside of solid fruit); surfaces, even noisy ones, stay under 6 % down to 2 spacings a
/// radius.
bool is_solid(const Normals& nm) {
    std::size_t with = 0, iso = 0;
    for (std::size_t i = 0; i < nm.w.size(); ++i) {
        if (nm.offset[i] > 0 || nm.w[i] > 0) {
            ++with;
            iso += nm.w[i] < 0.3f;
        }
    }
    return with > 0 && static_cast<double>(iso) > 0.15 * static_cast<double>(with);
}

/// The mode of positive values on a log scale (bins of 5 %, smoothed over five), refined as the
/// median of the values within 15 % of it; 0 without values.
double log_mode(std::vector<double>& v) {
    if (v.empty()) {
        return 0;
    }
    const double lo = std::log(*std::min_element(v.begin(), v.end()));
    std::vector<double> bins;
    for (double x : v) {
        const auto b = static_cast<std::size_t>((std::log(x) - lo) / 0.05);
        if (b >= bins.size()) {
            bins.resize(b + 1, 0.0);
        }
        bins[b] += 1;
    }
    std::size_t best = 0;
    double best_sum = -1;
    for (std::size_t b = 0; b < bins.size(); ++b) {
        double sum = 0;
        for (std::size_t k = b >= 2 ? b - 2 : 0; k <= std::min(bins.size() - 1, b + 2); ++k) {
            sum += bins[k];
        }
        if (sum > best_sum) {
            best_sum = sum;
            best = b;
        }
    }
    const double mode = std::exp(lo + 0.05 * (static_cast<double>(best) + 0.5));
    std::vector<double> near;
    for (double x : v) {
        if (std::abs(std::log(x / mode)) < 0.15) {
            near.push_back(x);
        }
    }
    return near.empty() ? mode : median(near);
}

/// The second moment of the normals within `around` of `at` (`grid`, a cell of `around` or
/// more), each counted with weight(j) (0: left out): its eigenvalues, ascending, and the total
/// weight. The normals' spread: on a sphere the two smaller eigenvalues are alike; a branch's
/// normals lie across its axis, in one plane (the smallest about 0).
struct Spread {
    V3 eigenvalues = V3::Zero();
    double weight = 0;
};
template <class Weight>
Spread normal_spread(const pcl::PointXYZ& at,
                     double around,
                     const search::Grid& grid,
                     const Normals& nm,
                     Weight weight) {
    Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
    Spread out;
    grid.for_each_within(at, around, [&](std::uint32_t j, double) {
        if (const double w = weight(j); w > 0) {
            moment += w * nm.n[j] * nm.n[j].transpose();
            out.weight += w;
        }
    });
    if (out.weight > 0) {
        out.eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(moment / out.weight,
                                                                         Eigen::EigenvaluesOnly)
                              .eigenvalues();
    }
    return out;
}

/// A normal that measures R: weight this or more (a neighbourhood of six points or more, flat
/// enough for a plane).
constexpr float kClearNormal = 0.5f;

/// The share of a sample's normals that measure R (kClearNormal).
double usable(const Normals& nm) {
    const auto n =
        std::count_if(nm.w.begin(), nm.w.end(), [](float w) { return w >= kClearNormal; });
    return nm.w.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(nm.w.size());
}

/// R measured again from smaller neighbourhoods is kept only where at least this share of the
/// first fit's usable normals are usable in it: in random volumes at 2-3 voxels a radius the
/// floor of 2 spacings holds a handful of a solid's points, a plane is found in under a third
/// as many neighbourhoods (0.19 against 0.62 in matrix scene 990; lattices 0.58-0.66 against
/// 0.29-0.37, a smaller neighbourhood being flatter), and those lines met 1.4-1.6 times as far.
constexpr double kUsableRefit = 0.5;

/// Where the normal lines of nearby points (same cluster, h/2..h apart, both with clear normals)
/// meet: on a sphere both at distance R. The mode of those distances; 0 with fewer than 50 pairs.
/// With `feet` the lines start at the normals' feet (also h/2 apart or more): on SfM density
/// gradients and scan stripes the lines through the points themselves met 10-20 % too far out.
/// Not for the thick outer layer of solids (there the feet moved inward and R halved).
/// With `one_way` > 0 a point whose neighbours' normals spread one way only (the smallest
/// eigenvalue of their second moment under one_way × the middle one: a branch's side, curved
/// around its axis alone) is left out; `two_way`, where given, gets the cloud indices
/// (Sample::at) of the points looked at and not left out.
double radius_from_normals(const Sample& s,
                           const Normals& nm,
                           bool feet,
                           double one_way = 0,
                           std::vector<std::uint32_t>* two_way = nullptr) {
    const double h = nm.scale;
    const search::Grid grid(s.view, h);
    const auto one_way_only = [&](const pcl::PointXYZ& p) {
        const Spread sp = normal_spread(
            p, h, grid, nm, [&](std::uint32_t j) { return nm.w[j] >= kClearNormal ? 1.0 : 0.0; });
        return sp.weight >= 5 && sp.eigenvalues(0) < one_way * sp.eigenvalues(1);
    };
    const std::size_t stride = std::max<std::size_t>(1, s.view.size / 20000);
    std::vector<double> dist;
    const double min_sin2 = std::pow(std::sin(5.0 * 3.141592653589793 / 180), 2);
    for (std::size_t i = 0; i < s.view.size; i += stride) {
        if (nm.w[i] < kClearNormal) {
            continue;
        }
        const pcl::PointXYZ p = s.view[i];
        if (one_way > 0 && one_way_only(p)) {
            continue;
        }
        if (two_way != nullptr) {
            two_way->push_back(s.at[i]);
        }
        int pairs = 0;
        grid.for_each_within(p, h, [&](std::uint32_t j, double d2) {
            if (pairs >= 4 || s.label[j] != s.label[i] || nm.w[j] < kClearNormal ||
                d2 < 0.25 * h * h) {
                return;
            }
            const V3 w0 = feet ? V3(nm.foot[i] - nm.foot[j]) : V3(vec(p) - vec(s.view[j]));
            if (feet && w0.squaredNorm() < 0.25 * h * h) {
                return;
            }
            const V3 &a = nm.n[i], &b = nm.n[j];
            const double ab = a.dot(b), denom = 1 - ab * ab;
            if (denom < min_sin2) {
                return;
            }
            const double d = a.dot(w0), e = b.dot(w0);
            const double t = (ab * e - d) / denom, u = (e - ab * d) / denom;
            const double gap = (w0 + t * a - u * b).norm();
            if (gap < 0.2 * std::abs(t) &&
                std::abs(std::abs(t) - std::abs(u)) < 0.2 * std::abs(t)) {
                dist.push_back(0.5 * (std::abs(t) + std::abs(u)));
                ++pairs;
            }
        });
    }
    return dist.size() < 50 ? 0.0 : log_mode(dist);
}

/// Points the other clusters must hold for the largest to be left out of rough_size().
constexpr std::size_t kOthersHold = 100;

/// A first, rough fruit size: the RMS distance of a cluster's points from its centroid, the
/// median over clusters of 10 sampled points or more; over points (each counts its cluster's)
/// when DBSCAN left fragments, so that the many small pieces of each fruit do not set it (an SfM
/// fruit 20 spacings wide, its far side ten times sparser, came apart into 590 pieces for 50
/// fruit and this size was a fifth of theirs). One cluster holding more than half of those points
/// would set it alone: it is left out when the others hold kOthersHold points or more (a tree's
/// trunk and branches in one piece, 69-94 % of the points, made it 4-27 times the fruit's).
double rough_size(const Sample& s, bool fragments) {
    std::unordered_map<std::uint32_t, std::vector<V3>> by;
    for (std::size_t i = 0; i < s.view.size; ++i) {
        by[s.label[i]].push_back(vec(s.view[i]));
    }
    std::vector<double> rms;
    std::vector<std::size_t> held;
    for (const auto& [label, c] : by) {
        if (c.size() < 10) {
            continue;
        }
        V3 mean = V3::Zero();
        for (const V3& p : c) {
            mean += p;
        }
        mean /= static_cast<double>(c.size());
        double sum = 0;
        for (const V3& p : c) {
            sum += (p - mean).squaredNorm();
        }
        rms.push_back(std::sqrt(sum / static_cast<double>(c.size())));
        held.push_back(c.size());
    }
    if (rms.empty() || !fragments) {
        return rms.empty() ? 0.0 : median(rms);
    }
    const std::size_t largest =
        static_cast<std::size_t>(std::max_element(held.begin(), held.end()) - held.begin());
    const std::size_t total = std::accumulate(held.begin(), held.end(), std::size_t{0});
    const std::size_t others = total - held[largest];
    std::vector<double> per_point;
    for (std::size_t k = 0; k < rms.size(); ++k) {
        if (k != largest || held[k] <= others || others < kOthersHold) {
            per_point.insert(per_point.end(), held[k], rms[k]);
        }
    }
    return median(per_point);
}

/// floor(v) as an integer, clamped far beyond any key's range (no overflow for huge or tiny
/// cells); cells outside the range of key_of() are never looked up as neighbours of real ones.
std::int64_t cell_index(double v) {
    return static_cast<std::int64_t>(std::clamp(std::floor(v), -1e15, 1e15));
}

std::uint64_t key_of(std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto u = [](std::int64_t v) {
        return static_cast<std::uint64_t>(v + (std::int64_t{1} << 20)) & 0x1fffff;
    };
    return u(x) | (u(y) << 21) | (u(z) << 42);
}

/// The points that fit normals are thinned only where a cube of vote_cell × h spans at least
/// this many spacings (the strided sample it replaced thinned from about 8.5 × 0.3 spacings).
constexpr double kThinFrom = 2.5;

/// The first of the points `at` in each occupied cube of side `cell` (an axis needing more than
/// 2^20 cells gets larger cubes), with their labels: a sample as dense everywhere on a surface,
/// however unevenly it was sampled (a strided sample keeps the density differences: an SfM
/// fruit sampled a fifth as densely as its neighbours kept too few points for normals).
Sample one_per_cell(const XyzView& points,
                    const std::vector<std::uint32_t>& at,
                    const std::vector<std::uint32_t>& labels,
                    double cell) {
    V3 lo = V3::Constant(std::numeric_limits<double>::infinity());
    V3 hi = -lo;
    for (const std::uint32_t i : at) {
        lo = lo.cwiseMin(vec(points[i]));
        hi = hi.cwiseMax(vec(points[i]));
    }
    cell = std::max(cell, (hi - lo).maxCoeff() / double((1 << 20) - 2));  // key_of()'s range
    Sample s;
    std::unordered_set<std::uint64_t> seen;
    for (const std::uint32_t i : at) {
        const V3 c = (vec(points[i]) - lo) / cell;
        if (seen.insert(key_of(cell_index(c.x()), cell_index(c.y()), cell_index(c.z()))).second) {
            s.at.push_back(i);
            s.label.push_back(labels[i]);
        }
    }
    s.view = points.subset(s.at);
    return s;
}

struct Peak {
    V3 centre;
    double support = 0;
    double radius = 0;
};

/// A peak is sharp (a fruit's centre, not a stretch of the diffuse shell the wrong-side votes
/// make) where its support, the votes within its radius r, is at least kSharp × the votes within
/// 2 r: a round fruit's votes meet in a point (about 1), a shell's patch is a disc (1/4).
constexpr double kSharp = 0.45;
/// ... or, in the final fit only (Votes::peaks' `lines`), where R spans kLinePeaks sample
/// spacings or more, at least kSharpLine × them where the votes within 2 r lie along a line
/// (their second moment's middle eigenvalue at most kLineFlat × the largest): a long fruit's
/// votes lie on its axis, whose ball of r holds about half of the ball of 2 r's, and at 3-5
/// spacings they read 0.3-0.45 (the 40 of 120 solid bananas of scene 3785 that had no centre
/// and went to a neighbour's: their candidates' flatness 0.16-0.38, the shell's 0.37-0.79). At
/// 2 spacings the few votes in a ball read as a line by chance. In every fit (session 53) the
/// extra centres changed which R, solid reading or colour class won the claims' comparisons
/// (round fruit at 2-5 spacings lost: 2598 olive 138 -> 57 of 165); in the final fit they change
/// nothing that was judged (docs/robustness-history.md, sessions 53 and 55).
constexpr double kSharpLine = 0.3;
constexpr double kLineFlat = 0.25;
constexpr double kLinePeaks = 3;

/// A point votes where its normal's weight (1 − λ₁/λ₂) is above this: its surroundings are flat
/// enough for a normal.
constexpr float kVotes = 0.2f;

/// A branch is curved one way, a fruit two ways: the normals of a branch's points all lie across
/// its axis, in one plane, and their second moment has a smallest eigenvalue of about 0 (noise),
/// where a fruit's, even an elongated one's, has its ends. Over 12 scenes of the matrix's
/// stripes (the part where the bark gets the most centres: 6 beside wood, 6 of elongated fruit
/// alone), among the normals within kCurvedAround fruit radii of each centre kept, the fruit's
/// smallest eigenvalue was 0.008-0.27 (8 of 1138 under 0.02, SphereVoteParams::min_two_way), the
/// bark's 0-0.27 (122 of 283 under it); within one radius an elongated fruit's middle reads as a
/// branch.
constexpr double kCurvedAround = 2.0;

/// R measured without the branches (SphereVoteParams::branch_below) is taken only where it is
/// under the first R by this factor: a tree's branches are several times thicker than its fruit.
constexpr double kThicker = 2.0;

/// The points within `around` of `centre` (`grid`, a cell of `around` or more) whose normals
/// are reliable lie on a surface curved one way only (their second moment's smallest eigenvalue
/// under `two_way`): a branch, not a fruit.
bool curved_one_way(
    const V3& centre, double around, double two_way, const search::Grid& grid, const Normals& nm) {
    const Spread sp = normal_spread(point(centre), around, grid, nm, [&](std::uint32_t j) {
        return nm.w[j] > kVotes ? static_cast<double>(nm.w[j]) : 0.0;
    });
    return sp.weight > 0 && sp.eigenvalues(0) < two_way;
}

/// Votes sorted into cubic cells (flat arrays, cells found by binary search), and the peaks of
/// their density.
class Votes {
public:
    /// Votes in cells `cell` wide from `origin`, room made for `expected` of them.
    Votes(double cell, const V3& origin, std::size_t expected) : cell_(cell), origin_(origin) {
        entries_.reserve(expected);
    }

    void add(const V3& at, float w, std::uint32_t voter) {
        const std::array<std::int64_t, 3> c{coord(at.x(), 0), coord(at.y(), 1), coord(at.z(), 2)};
        if (std::abs(c[0]) >= (1 << 20) || std::abs(c[1]) >= (1 << 20) ||
            std::abs(c[2]) >= (1 << 20)) {
            return;  // beyond the key's range: far outside the cloud
        }
        entries_.push_back({key_of(c[0], c[1], c[2]), at.cast<float>(), w, voter});
    }

    /// Sorts the votes into their cells; call once, after the last add().
    void finish() {
        std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
            return a.key < b.key || (a.key == b.key && a.voter < b.voter);
        });
        for (std::uint32_t v = 0; v < entries_.size(); ++v) {
            if (keys_.empty() || keys_.back() != entries_[v].key) {
                index_.emplace(entries_[v].key, static_cast<std::uint32_t>(keys_.size()));
                keys_.push_back(entries_[v].key);
                begin_.push_back(v);
                sum_.push_back(0);
            }
            sum_.back() += entries_[v].w;
        }
        begin_.push_back(static_cast<std::uint32_t>(entries_.size()));
    }

    /// Fruit centres: local maxima of the 3x3x3 cell sums, refined by mean shift within
    /// peak_radius × R, sharp (most of the votes within twice that lie within it, or, with
    /// `lines`, many of them and on a line: kSharp, kSharpLine), peak_separation × R apart,
    /// strongest first, each supported by at least min_support × the typical fruit's votes that
    /// no stronger fruit explains, from more than one side (max_alignment), on a surface curved
    /// two ways (min_two_way). The votes' voters are the points of `s`, `nm` their normals.
    std::vector<Peak> peaks(const SphereVoteParams& params,
                            const Sample& s,
                            double fruit_radius,
                            const Normals& nm,
                            bool lines = false) const {
        const double radius = params.peak_radius * fruit_radius,
                     separation = params.peak_separation * fruit_radius;
        std::vector<double> box(keys_.size(), 0.0);
        for (std::size_t c = 0; c < keys_.size(); ++c) {
            for_cells(keys_[c], 1, [&](std::size_t n) { box[c] += sum_[n]; });
        }
        std::vector<std::pair<double, std::size_t>> candidates;
        for (std::size_t c = 0; c < keys_.size(); ++c) {
            bool top = true;
            for_cells(keys_[c], 1, [&](std::size_t n) {
                top = top && (box[n] < box[c] || (box[n] == box[c] && n >= c));
            });
            if (top) {
                candidates.emplace_back(box[c], c);
            }
        }
        std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
            return a.first > b.first || (a.first == b.first && a.second < b.second);
        });
        std::vector<Peak> found;
        // Candidates far below the strongest, or in a cell a refined peak already covers (they
        // climb to the same centre), are not refined.
        std::vector<std::uint8_t> covered(keys_.size(), 0);
        const int reach = static_cast<int>(std::ceil(radius / cell_));
        for (const auto& [b, c] : candidates) {
            if (b < 0.02 * candidates.front().first || covered[c]) {
                continue;
            }
            Peak p = refine(c, radius);
            for_cells(
                key_of(coord(p.centre.x(), 0), coord(p.centre.y(), 1), coord(p.centre.z(), 2)),
                reach, [&](std::size_t n) { covered[n] = 1; });
            if (p.support > 0) {
                found.push_back(p);
            }
        }
        std::sort(found.begin(), found.end(), [](const Peak& a, const Peak& b) {
            return a.support > b.support ||
                   (a.support == b.support &&
                    std::lexicographical_compare(a.centre.data(), a.centre.data() + 3,
                                                 b.centre.data(), b.centre.data() + 3));
        });
        // Sharp (kSharp; with `lines`, also kSharpLine on a line of votes). Asked only of peaks
        // that could be kept (it reads 8 times the cells of a support).
        std::vector<std::int8_t> sharp(found.size(), -1);
        const auto is_sharp = [&](std::size_t k) {
            if (sharp[k] < 0) {
                const V3& c = found[k].centre;
                const double around = gather(c, 2 * radius);
                sharp[k] = found[k].support >= kSharp * around ||
                                   (lines && found[k].support >= kSharpLine * around &&
                                    flatness(c, 2 * radius) <= kLineFlat)
                               ? 1
                               : 0;
            }
            return sharp[k] == 1;
        };
        // The typical fruit: the median support of the sharp peaks above a tenth of the strongest
        // sharp one.
        std::size_t top = 0;
        while (top < found.size() && !is_sharp(top)) {
            ++top;
        }
        if (top == found.size()) {
            return {};
        }
        std::vector<double> strong;
        for (std::size_t k = top; k < found.size() && found[k].support >= 0.1 * found[top].support;
             ++k) {
            if (is_sharp(k)) {
                strong.push_back(found[k].support);
            }
        }
        const double need = params.min_support * median(strong);
        // Strongest first; each accepted fruit explains away the points on and inside its sphere,
        // whose votes (the wrong-side shell, scattered normals) then support nothing else.
        const search::Grid grid(s.view, kCurvedAround * fruit_radius);
        std::vector<std::uint8_t> explained(s.view.size, 0);
        std::vector<Peak> kept;
        for (std::size_t k = 0; k < found.size() && found[k].support >= need; ++k) {
            const Peak& candidate = found[k];
            if (!is_sharp(k)) {
                continue;
            }
            bool apart = true;
            for (const Peak& q : kept) {
                apart = apart && (candidate.centre - q.centre).norm() >= separation;
            }
            if (!apart) {
                continue;
            }
            Peak p = candidate;
            p.support = 0;
            V3 towards = V3::Zero();  // the voters' directions to the centre, summed
            for_votes_within(p.centre, radius, [&](const Entry& e) {
                if (!explained[e.voter]) {
                    p.support += e.w;
                    towards += e.w * (p.centre - vec(s.view[e.voter])).normalized();
                }
            });
            // A fruit is seen from several sides; a flat patch (a piece of leaf) votes from one
            // direction only (its normals are parallel) and is no fruit.
            if (p.support < need || towards.norm() > params.max_alignment * p.support) {
                continue;
            }
            if (curved_one_way(p.centre, kCurvedAround * fruit_radius, params.min_two_way, grid,
                               nm)) {
                continue;
            }
            p.radius = voter_radius(p.centre, radius, s, fruit_radius);
            grid.for_each_within(point(p.centre), std::min(1.15 * p.radius, 1.7 * fruit_radius),
                                 [&](std::uint32_t j, double) { explained[j] = 1; });
            kept.push_back(p);
        }
        return kept;
    }

    /// Whether the votes fill the segment from `a` to `b`: each of the slabs (about `radius`
    /// long) between the balls of `radius` around either end holds, within `radius` of the line,
    /// votes of at least `need` × the weaker end ball's weight per unit volume. A long fruit's
    /// votes lie along its axis (a prolate spheroid's normals meet the axis all along its middle)
    /// and fill every slab; two fruit side by side or in a row leave the stretch between their
    /// centres nearly empty. The slabs are read from the middle out, and the first too light
    /// ends the reading (the middle one, for most pairs of round fruit).
    [[nodiscard]] bool line(const V3& a, const V3& b, double radius, double need) const {
        const V3 axis = b - a;
        const double d = axis.norm();
        const double inner = d - 2 * radius;
        const double ends = std::min(gather(a, radius), gather(b, radius)) / (4.0 / 3 * radius);
        if (!(inner > 0) || !(ends > 0)) {
            return false;
        }
        const V3 u = axis / d;
        const auto slabs = static_cast<std::size_t>(std::max(1.0, std::round(inner / radius)));
        const double length = inner / static_cast<double>(slabs);
        const double around = std::sqrt(0.25 * length * length + radius * radius);
        // the middle slab first, then outwards
        std::vector<std::size_t> order(slabs);
        std::iota(order.begin(), order.end(), std::size_t{0});
        const auto off_middle = [&](std::size_t k) {
            return std::abs(2 * static_cast<double>(k) - static_cast<double>(slabs - 1));
        };
        std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
            return off_middle(x) < off_middle(y);
        });
        for (const std::size_t k : order) {
            double w = 0;
            for_votes_within(
                a + (radius + (static_cast<double>(k) + 0.5) * length) * u, around,
                [&](const Entry& e) {
                    const V3 q = e.at.cast<double>() - a;
                    const double t = q.dot(u) - radius;
                    if (t >= 0 && t < inner &&
                        std::min(slabs - 1, static_cast<std::size_t>(t / length)) == k &&
                        (q - q.dot(u) * u).squaredNorm() <= radius * radius) {
                        w += e.w;
                    }
                });
            if (!(w / length >= need * ends)) {  // (the common factor pi radius^2 cancels)
                return false;
            }
        }
        return true;
    }
    /// The votes within `radius` of `at` spread along `u` at least `need` times as far as across
    /// it (their weighted second moments about `at`, across per direction).
    [[nodiscard]] bool along(const V3& at, const V3& u, double radius, double need) const {
        double on = 0, off = 0;
        for_votes_within(at, radius, [&](const Entry& e) {
            const V3 q = e.at.cast<double>() - at;
            const double t = q.dot(u);
            on += e.w * t * t;
            off += e.w * (q.squaredNorm() - t * t);
        });
        return on > 0 && on >= need * 0.5 * off;
    }

private:
    struct Entry {
        std::uint64_t key;
        Eigen::Vector3f at;
        float w;
        std::uint32_t voter;
    };

    [[nodiscard]] std::int64_t coord(double v, int a) const {
        return cell_index((v - origin_(a)) / cell_);
    }
    static std::array<std::int64_t, 3> unkey(std::uint64_t k) {
        const auto v = [](std::uint64_t u) {
            return static_cast<std::int64_t>(u & 0x1fffff) - (std::int64_t{1} << 20);
        };
        return {v(k), v(k >> 21), v(k >> 42)};
    }
    /// f(cell) for the existing cells within `reach` cells of cell key k.
    template <class F>
    void for_cells(std::uint64_t k, int reach, F&& f) const {
        const auto c = unkey(k);
        for (int dx = -reach; dx <= reach; ++dx) {
            for (int dy = -reach; dy <= reach; ++dy) {
                for (int dz = -reach; dz <= reach; ++dz) {
                    const std::uint64_t n = key_of(c[0] + dx, c[1] + dy, c[2] + dz);
                    const auto it = index_.find(n);
                    if (it != index_.end()) {
                        f(it->second);
                    }
                }
            }
        }
    }
    template <class F>
    void for_votes_within(const V3& at, double radius, F&& f) const {
        const int reach = static_cast<int>(std::ceil(radius / cell_));
        const Eigen::Vector3f a = at.cast<float>();
        const float r2 = static_cast<float>(radius * radius);
        for_cells(key_of(coord(at.x(), 0), coord(at.y(), 1), coord(at.z(), 2)), reach,
                  [&](std::size_t c) {
                      for (std::uint32_t v = begin_[c]; v < begin_[c + 1]; ++v) {
                          if ((entries_[v].at - a).squaredNorm() <= r2) {
                              f(entries_[v]);
                          }
                      }
                  });
    }
    /// The votes within `radius` of `at`: the middle eigenvalue of their weighted second moment
    /// about it over the largest (about 0 on a line, 1 on a disc or in a ball).
    [[nodiscard]] double flatness(const V3& at, double radius) const {
        Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
        for_votes_within(at, radius, [&](const Entry& e) {
            const V3 q = e.at.cast<double>() - at;
            m += e.w * q * q.transpose();
        });
        const V3 ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues();
        return ev(2) > 0 ? ev(1) / ev(2) : 1;
    }
    [[nodiscard]] double gather(const V3& at, double radius) const {
        double sum = 0;
        for_votes_within(at, radius, [&](const Entry& e) { sum += e.w; });
        return sum;
    }
    /// Mean shift from the cell's 3x3x3 box to the weighted mean of the votes within `radius`.
    [[nodiscard]] Peak refine(std::size_t c, double radius) const {
        V3 at = V3::Zero();
        double sum = 0;
        for_cells(keys_[c], 1, [&](std::size_t n) {
            for (std::uint32_t v = begin_[n]; v < begin_[n + 1]; ++v) {
                at += entries_[v].w * entries_[v].at.cast<double>();
                sum += entries_[v].w;
            }
        });
        Peak p{at / sum, sum, 0};
        for (int it = 0; it < 4; ++it) {
            V3 next = V3::Zero();
            double w = 0;
            for_votes_within(p.centre, radius, [&](const Entry& e) {
                next += e.w * e.at.cast<double>();
                w += e.w;
            });
            if (!(w > 0)) {
                return {p.centre, 0, 0};
            }
            p = {next / w, w, 0};
        }
        return p;
    }
    /// The median distance from the centre of the voters whose votes are within `radius` of it,
    /// clamped to 0.7..1.4 R.
    [[nodiscard]] double voter_radius(const V3& centre,
                                      double radius,
                                      const Sample& s,
                                      double fruit_radius) const {
        std::vector<double> d;
        for_votes_within(centre, radius, [&](const Entry& e) {
            d.push_back((vec(s.view[e.voter]) - centre).norm());
        });
        const double r = d.empty() ? fruit_radius : median(d);
        return std::clamp(r, 0.7 * fruit_radius, 1.4 * fruit_radius);
    }

    double cell_;
    V3 origin_;
    std::vector<Entry> entries_;                              ///< sorted by cell after finish()
    std::vector<std::uint64_t> keys_;                         ///< the occupied cells, ascending
    std::unordered_map<std::uint64_t, std::uint32_t> index_;  ///< cell key -> its place in keys_
    std::vector<std::uint32_t> begin_;  ///< cell c's votes: entries_[begin_[c], begin_[c + 1])
    std::vector<double> sum_;           ///< cell c's total weight
};

/// True when the points are a sheet (a leaf, the ground): the smallest standard deviation under
/// `sheet` × the middle one, and that thickness not a bowl's (a cap of a fruit: a quadric over
/// the sheet's plane explains most of it; a leaf's is noise or lattice steps).
bool flat(const XyzView& points, const std::vector<std::uint32_t>& at, double sheet) {
    if (at.size() < 10) {
        return false;
    }
    V3 mean = V3::Zero();
    for (auto i : at) {
        mean += vec(points[i]);
    }
    mean /= static_cast<double>(at.size());
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    for (auto i : at) {
        const V3 q = vec(points[i]) - mean;
        m += q * q.transpose();
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(m);
    const V3 l = es.eigenvalues();
    if (!(l(0) < sheet * sheet * l(1))) {
        return false;
    }
    // w = quadric(u, v) by least squares in the frame of the principal axes
    Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
    const V3 eu = es.eigenvectors().col(2) / std::sqrt(l(2) / static_cast<double>(at.size()));
    const V3 ev = es.eigenvectors().col(1) / std::sqrt(l(1) / static_cast<double>(at.size()));
    const V3 ew = es.eigenvectors().col(0);
    for (auto i : at) {
        const V3 q = vec(points[i]) - mean;
        const double u = q.dot(eu), v = q.dot(ev), w = q.dot(ew);
        Eigen::Matrix<double, 6, 1> f;
        f << u * u, v * v, u * v, u, v, 1.0;
        a += f * f.transpose();
        b += f * w;
    }
    const Eigen::Matrix<double, 6, 1> c = a.ldlt().solve(b);
    const double explained = c.dot(b);  // the fit's share of sum w² (least squares: c·Aᵀw)
    return !(explained > 0.5 * l(0));
}

/// The sample without the points of the clusters (of `members`) that are sheets (flat(): leaves,
/// the ground); empty when none is, or when fewer than 10 points would remain.
Sample without_sheets(const XyzView& points,
                      const std::vector<std::uint32_t>& members,
                      const std::vector<std::uint32_t>& labels,
                      const Sample& s,
                      double sheet) {
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> by;
    for (const std::uint32_t i : members) {
        by[labels[i]].push_back(i);
    }
    std::unordered_set<std::uint32_t> sheets;
    for (const auto& [label, at] : by) {
        if (flat(points, at, sheet)) {
            sheets.insert(label);
        }
    }
    std::vector<std::uint32_t> rest;
    for (std::size_t k = 0; k < s.at.size(); ++k) {
        if (sheets.count(s.label[k]) == 0) {
            rest.push_back(s.at[k]);
        }
    }
    return sheets.empty() || rest.size() < 10 ? Sample{} : thinned(points, rest, labels, 1);
}

/// The peaks' centres hashed into cubes `cell` wide (from the first centre): for_each_near()
/// visits the peaks in the 27 cubes around a point, every peak within `cell` of it among them.
class CentreGrid {
public:
    CentreGrid(const std::vector<Peak>& peaks, double cell)
        : cell_(cell), origin_(peaks.front().centre) {
        for (std::uint32_t j = 0; j < peaks.size(); ++j) {
            cells_[key(peaks[j].centre, 0, 0, 0)].push_back(j);
        }
    }

    template <typename F>
    void for_each_near(const V3& p, F&& f) const {
        for (int dx = -1; dx <= 1; ++dx) {
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = cells_.find(key(p, dx, dy, dz));
                    if (it != cells_.end()) {
                        for (const std::uint32_t j : it->second) {
                            f(j);
                        }
                    }
                }
            }
        }
    }

private:
    std::uint64_t key(const V3& p, int dx, int dy, int dz) const {
        const auto at = [&](int a) { return cell_index((p(a) - origin_(a)) / cell_); };
        return key_of(at(0) + dx, at(1) + dy, at(2) + dz);
    }

    double cell_;
    V3 origin_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

/// Every clustered point to the peak nearest relative to its radius, within `reach` (label
/// 1 + the peak); the rest keep their cluster (label 1 + peaks + the cluster's), unless that rest
/// is a sheet (leaves, ground: no fruit; label 0). In place.
void assign(const XyzView& points,
            const std::vector<std::uint32_t>& members,
            std::vector<std::uint32_t>& labels,
            const std::vector<Peak>& peaks,
            const SphereVoteParams& params,
            double R) {
    const double reach = params.reach;
    const CentreGrid near(peaks, reach * 1.4 * R);
    const auto count = static_cast<std::uint32_t>(peaks.size());
    std::vector<std::uint32_t>& out = labels;  // each point reads its own label, then writes it
#pragma omp parallel for schedule(static)
    for (std::int64_t kk = 0; kk < static_cast<std::int64_t>(members.size()); ++kk) {
        const std::uint32_t i = members[static_cast<std::size_t>(kk)];
        const V3 p = vec(points[i]);
        double best = reach;
        std::uint32_t to = count + labels[i];
        near.for_each_near(p, [&](std::uint32_t j) {
            const double d = (p - peaks[j].centre).norm() / peaks[j].radius;
            if (d < best || (d == best && j + 1 < to)) {
                best = d;
                to = j + 1;
            }
        });
        out[i] = to;
    }
    std::map<std::uint32_t, std::vector<std::uint32_t>> rest;
    for (auto i : members) {
        if (out[i] > count) {
            rest[out[i]].push_back(i);
        }
    }
    for (const auto& [label, at] : rest) {
        if (flat(points, at, params.sheet)) {
            for (auto i : at) {
                out[i] = 0;
            }
        }
    }
}

/// Centres closer than this × R are not joined by their votes' line (Votes::line): at 2-3
/// spacings a radius the vote balls of two fruit spread into the stretch between them (of the
/// pairs of different fruit traced in 84 matrix scenes whose line read 0.3 or more, 125 of 144
/// were under 2 R apart; docs/robustness-history.md, session 49).
constexpr double kLineNear = 2;
/// ... but from kLineNearFine × R where R spans kLineFine spacings of the sample or more: there
/// the balls' votes stay apart, and a long fruit's centres lie 1-2 R apart as often as 2-4 R
/// (3780, banana-like SfM at 5.7 spacings: 60 of the 119 pairs of one finger's centres, 40
/// joined by the line from 2 R, 92 from 1 R, with 1 pair of two fingers either way; with
/// kAlong below, the 68 banana- and eggplant-like scenes of the matrix 0.637 -> 0.647, none
/// down by 0.02, the 3222 fast scenes ±0; docs/robustness-history.md, session 52).
constexpr double kLineFine = 4;
constexpr double kLineNearFine = 1;
/// ... where the votes within kAlongWithin × R of each of the two centres also spread along the
/// line between them at least kAlong times as far as across it (per direction): a long fruit's
/// votes lie on its axis, a round fruit's in a round ball. Without this, the line from 1 R
/// joined touching round fruit in bunches (1008 lychee: 129 -> 121 of 133; 1426 and 1382
/// blueberries, 1285 lychee, 1837 dates side by side: over 1995 fast scenes 36 down, 14 up,
/// 0.9581 -> 0.9577), with it they count as before and 3780 140 of 120 (136 without it, 164
/// from 2 R); at 1.5 the same, at 4 3780 160.
constexpr double kAlong = 2;
constexpr double kAlongWithin = 0.5;

/// The pairs of `peaks` (j < k, sorted) kLineNear (kLineNearFine, where R spans kLineFine
/// sample spacings `ss` or more, with kAlong) to join_line_far × R apart whose `votes` fill the
/// line between them (Votes::line at least join_line).
std::vector<std::pair<std::uint32_t, std::uint32_t>> line_pairs(const std::vector<Peak>& peaks,
                                                                const Votes& votes,
                                                                double R,
                                                                double ss,
                                                                const SphereVoteParams& params) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> lines;
    if (peaks.empty()) {
        return lines;
    }
    const double line_near = R >= kLineFine * ss ? kLineNearFine : kLineNear;
    const double far = params.join_line_far * R;
    const CentreGrid near(peaks, far);
    // The votes around `a` lie along the line to `b` (kAlong).
    const auto along = [&](const V3& a, const V3& b) {
        return votes.along(a, (b - a).normalized(), kAlongWithin * R, kAlong);
    };
    for (std::uint32_t j = 0; j < peaks.size(); ++j) {
        const V3& c = peaks[j].centre;
        near.for_each_near(c, [&](std::uint32_t k) {
            const double d = (peaks[k].centre - c).norm();
            if (k > j && d >= line_near * R && d < far &&
                (d >= kLineNear * R || (along(c, peaks[k].centre) && along(peaks[k].centre, c))) &&
                votes.line(c, peaks[k].centre, params.peak_radius * R, params.join_line)) {
                lines.emplace_back(j, k);
            }
        });
    }
    std::sort(lines.begin(), lines.end());
    return lines;
}

/// Elongated fruit (pears, lemons, dates: spheroids of aspect up to about 1.8) give two peaks on
/// their long axis, where the normals of either end meet, or one peak and a leftover end beyond
/// reach. Two parts, each a fruit around a centre or a leftover piece of a cluster (around its
/// centroid), are one fruit when the points of both form one convex body: across the line
/// between their centres, the body's width where two fruit would touch (the point dividing the
/// line in the ratio of their radii; halfway for a leftover) is at least `convex` × the width
/// interpolated between the widths at the two centres (a convex profile lies above its chords);
/// two touching spheres narrow there to a waist (about half). A width is the median distance
/// from the line of the points in a slab ±0.1 R across it (at least ±join_slab sample spacings
/// `ss`), within 1.3 × the larger radius (a neighbour's points given to one of the two do not widen
/// it); a slab of fewer than 3 points says nothing. Centres are tried within `join_far` × R of each
/// other, leftovers within 2.5 R of a centre; centres beyond `join_near` × R also need the points
/// at the join (±0.25 R: a slab of ±0.1 R held 5-10 points of a pod at 8 spacings, too few for its
/// shape) to ring the line: their offsets from it, p, have a second moment sum(p pᵀ) whose smaller
/// eigenvalue across the line is at least `join_ring` × the larger (a pod's cross-section is round,
/// 1; two fruit side by side meet in a band, or one's cap cut across its length: about 1/aspect²).
/// Labels are merged in place (into the fruit's); returns the fruit centres merged into another.
/// Long fruit (bananas, aspect near 3) are cut into three or four parts along their axis, whose
/// middles are beyond reach of the centres at either end, so their points say little: two centres
/// kLineNear to join_line_far × R apart are also one fruit where the votes between them fill the
/// line: the pairs `lines` (j < k, sorted; line_pairs()).
std::uint32_t join_elongated(const XyzView& points,
                             const std::vector<std::uint32_t>& members,
                             std::vector<std::uint32_t>& labels,
                             const std::vector<Peak>& peaks,
                             const std::vector<std::pair<std::uint32_t, std::uint32_t>>& lines,
                             double R,
                             double ss,
                             const SphereVoteParams& params) {
    const auto count = static_cast<std::uint32_t>(peaks.size());
    std::uint32_t top = count;
    for (auto i : members) {
        top = std::max(top, labels[i]);
    }
    std::vector<std::vector<std::uint32_t>> of(top);  // part l - 1: the points labelled l
    for (auto i : members) {
        if (labels[i] >= 1) {
            of[labels[i] - 1].push_back(i);
        }
    }
    std::vector<V3> centre(top, V3::Zero());
    std::vector<double> radius(top, 0.0);  // 0: a leftover
    for (std::uint32_t l = 0; l < top; ++l) {
        if (l < count) {
            centre[l] = peaks[l].centre;
            radius[l] = peaks[l].radius;
        } else if (!of[l].empty()) {
            for (auto i : of[l]) {
                centre[l] += vec(points[i]);
            }
            centre[l] /= static_cast<double>(of[l].size());
        }
    }
    const double slab = std::max(0.1 * R, params.join_slab * ss);  // one spacing thick at least
    const auto one_body = [&](std::uint32_t j, std::uint32_t k, bool ring) {
        const V3 axis = centre[k] - centre[j];
        const double d = axis.norm();
        const V3 u = axis / d;
        const double split =
            radius[k] > 0 ? radius[j] / (radius[j] + radius[k]) : 0.5;  // j is a fruit
        const double at[3] = {0, d * split, d};
        const double within = 1.3 * std::max(radius[j], radius[k]);
        std::vector<double> across[3];
        Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();  // of the join's offsets from the line
        for (const auto* part : {&of[j], &of[k]}) {
            for (auto i : *part) {
                const V3 q = vec(points[i]) - centre[j];
                const double t = q.dot(u);
                const V3 p = q - t * u;
                const double rho = p.norm();
                for (int w = 0; w < 3; ++w) {
                    if (std::abs(t - at[w]) <= slab && rho <= within) {
                        across[w].push_back(rho);
                    }
                }
                if (ring && std::abs(t - at[1]) <= 0.25 * R && rho <= within) {
                    moment += p * p.transpose();
                }
            }
        }
        if (across[0].size() < 3 || across[1].size() < 3 || across[2].size() < 3) {
            return false;
        }
        const double w0 = median(across[0]), w1 = median(across[1]), w2 = median(across[2]);
        if (w1 < params.join_convex * (w0 + (w2 - w0) * split)) {
            return false;
        }
        if (!ring) {
            return true;
        }
        const V3 e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(moment).eigenvalues();
        return e(1) >= params.join_ring * e(2);  // e(0) ~ 0: along the line
    };
    std::vector<std::uint32_t> root(top);
    std::iota(root.begin(), root.end(), 0u);
    const auto find = [&](std::uint32_t a) { return find_root(root, a); };
    std::uint32_t merged = 0;
    for (std::uint32_t j = 0; j < count; ++j) {
        for (std::uint32_t k = j + 1; k < top; ++k) {
            const double d = (centre[k] - centre[j]).norm();
            const double window = k < count ? std::max(params.join_near, params.join_far) : 2.5;
            const bool ring = k < count && d >= params.join_near * R;
            if (of[j].empty() || of[k].empty() || !(d > 0) || find(j) == find(k) ||
                (k >= count && find(k) != k)) {
                continue;
            }
            if (!(d < window * R && one_body(j, k, ring)) &&
                !std::binary_search(lines.begin(), lines.end(), std::make_pair(j, k))) {
                continue;
            }
            merged += k < count ? 1 : 0;
            root[find(k)] = find(j);
        }
    }
    for (auto i : members) {
        if (labels[i] >= 1) {
            labels[i] = find(labels[i] - 1) + 1;
        }
    }
    return merged;
}

/// The number of distinct labels above 0 among `members`.
double parts(const std::vector<std::uint32_t>& labels, const std::vector<std::uint32_t>& members) {
    std::unordered_set<std::uint32_t> seen;
    for (const std::uint32_t i : members) {
        if (labels[i] != 0) {
            seen.insert(labels[i]);
        }
    }
    return static_cast<double>(seen.size());
}

/// The sampled nearest-neighbour distances of a voxel lattice all lie within this share of their
/// median (the step): the 10th and 90th percentiles (a Poisson sampling's: about 0.5 and 1.5 of
/// it in a volume, 0.4 and 1.8 on a surface).
constexpr double kLatticeTolerance = 0.02;
/// Lattice points this many steps apart or closer are adjacent: face and edge neighbours (1, 1.41).
constexpr double kLatticeLink = 1.5;
/// ... and leftovers are parted by it only where R spans fewer steps than this (below).
constexpr double kLatticeCoarse = 2.5;

/// On a voxel lattice (the clustered points' nearest-neighbour distances all one step) where R
/// spans under kLatticeCoarse steps, the leftovers of each cluster (labels above `fruit`: points
/// no centre took) are parted into the pieces the lattice connects (kLatticeLink steps), each a
/// part of its own. There DBSCAN's eps of 4 steps spans a fruit (1.6-2 R): the caps of a bunch's
/// fruit that no centre took (partial masks) were one part, counted once. From 2.5 steps the
/// leftovers are mostly pieces of fruit that have a centre, or one fruit's patches, and parting
/// them lost slightly (docs/robustness-history.md, session 61). On random samplings, whose
/// spacing varies from point to point (SfM density gradients, scan stripes), no fixed link keeps
/// one fruit's leftover whole (parting them at 1.5 spacings, or at 1.05 x each point's sixth
/// neighbour, lost more than it won), and the clusters stay as DBSCAN made them. Every clustered
/// point is tested (a grid and a sort of them all) only where the voting sample's spacing `ss`
/// (no less than the step) and then the leftovers' own distances allow a lattice (none under
/// their median, and R under kLatticeCoarse of it); those alone do not tell one (their lone
/// points lie farther: 2827, 119 -> 94 of 171). In place.
void part_leftovers_on_lattice(const XyzView& points,
                               const std::vector<std::uint32_t>& members,
                               std::vector<std::uint32_t>& labels,
                               std::uint32_t fruit,
                               double R,
                               double ss) {
    if (!(R < kLatticeCoarse * ss)) {
        return;  // the voting sample's spacing ss is no less than the step
    }
    std::vector<std::uint32_t> left;
    std::uint32_t top = 0;
    for (const std::uint32_t i : members) {
        top = std::max(top, labels[i]);
        if (labels[i] > fruit) {
            left.push_back(i);
        }
    }
    if (left.size() < 2) {
        return;
    }
    const XyzView view = points.subset(left);
    const search::SpacingStats own = search::spacing_stats(view);
    if (!(R < kLatticeCoarse * own.median && own.p10 >= (1 - kLatticeTolerance) * own.median)) {
        return;  // no lattice, or R spans kLatticeCoarse steps or more: no test over every point
    }
    const search::SpacingStats st = search::spacing_stats(points.subset(members));
    if (!(st.median > 0 && R < kLatticeCoarse * st.median &&
          st.p10 >= (1 - kLatticeTolerance) * st.median &&
          st.p90 <= (1 + kLatticeTolerance) * st.median)) {
        return;
    }
    const double link = kLatticeLink * st.median;
    const search::Grid grid(view, link);
    std::vector<std::uint32_t> parent(left.size());
    std::iota(parent.begin(), parent.end(), 0U);
    for (std::uint32_t a = 0; a < left.size(); ++a) {
        grid.for_each_within(view[a], link, [&](std::uint32_t b, double) {
            if (labels[left[b]] == labels[left[a]]) {
                parent[find_root(parent, a)] = find_root(parent, b);
            }
        });
    }
    std::unordered_map<std::uint32_t, std::uint32_t> piece;  // a root's label: top + 1, 2, ...
    for (std::uint32_t a = 0; a < left.size(); ++a) {
        labels[left[a]] = piece
                              .try_emplace(find_root(parent, a),
                                           top + 1 + static_cast<std::uint32_t>(piece.size()))
                              .first->second;
    }
}

/// A leftover holding more points than this many fruit around a centre (their median) is no
/// fruit nor bunch (the matrix's bunches hold up to 12): the tree's wood or the ground.
constexpr double kGiantPart = 50;

/// What finish() kept.
struct Finished {
    std::uint32_t count = 0;  ///< parts counted
    double median_part = 0;   ///< SphereVoteResult::median_part
};

/// The fruit centres' labels as finish() reads them: 1..all are parts around a centre (a joined
/// fruit's points carry the label of its first, strongest centre), and the first `measured`,
/// the strongest centres, as many as the fruit the centres make (all - joins), set the median
/// fruit; the weaker ones are judged as leftovers are. A join says a fruit gave two centres, and
/// the weakest centres are most often more such (a long fruit's third or fourth along its axis,
/// beyond the join's reach): until session 64 this was done by counting the labels above `all -
/// joins` as leftovers outright, whose parts then also held no share of the points claimed;
/// judged as fruit instead, banana-like scenes counted more (3798, 125 -> 186 of 120; 3794,
/// 171 -> 259), dates and chilis one to eight more (docs/robustness-history.md, session 64).
struct CentreLabels {
    std::uint32_t all = 0;
    std::uint32_t measured = 0;
};

/// Drops parts below min_size points or min_relative × the median fruit's points (to 0) and
/// numbers the rest 1.. by decreasing size. Labels 1..centres.all are fruit around a centre,
/// higher ones the leftovers of clusters no centre claimed. When centres claimed most points,
/// giant leftovers (kGiantPart) aside, the median is over the fruit of the `measured` centres,
/// and leftovers and the weaker centres' parts also go below a quarter of it (the pieces DBSCAN
/// cut off a fruit, the crumbs scan lines and noisy colours leave beside the wood); otherwise
/// (few or no centres) every part is measured against the median part.
Finished finish(std::vector<std::uint32_t>& labels,
                std::uint32_t min_size,
                double min_relative,
                CentreLabels centres) {
    const std::uint32_t fruit = centres.all, measured = centres.measured;
    std::uint32_t top = 0;
    for (auto l : labels) {
        top = std::max(top, l);
    }
    std::vector<double> size(std::size_t{top} + 1, 0.0);
    for (auto l : labels) {
        size[l] += 1;
    }
    std::vector<double> fruit_sizes;
    for (std::uint32_t l = 1; l <= std::min(top, measured); ++l) {
        if (size[l] > 0) {
            fruit_sizes.push_back(size[l]);
        }
    }
    const double giant = fruit_sizes.empty() ? 0.0 : kGiantPart * median(fruit_sizes);
    double claimed = 0, all = 0, giants = 0;
    for (std::uint32_t l = 1; l <= top; ++l) {
        claimed += l <= fruit ? size[l] : 0.0;
        all += size[l];
        giants += l > fruit && size[l] > giant ? size[l] : 0.0;
    }
    // The parts kept where the centres' fruit set the reference (`by_fruit`), else the median part.
    const auto kept = [&](bool by_fruit) {
        std::vector<double> reference;
        for (std::uint32_t l = 1; l <= top; ++l) {
            if (size[l] > 0 && (!by_fruit || l <= measured)) {
                reference.push_back(size[l]);
            }
        }
        const double typical = reference.empty() ? 0.0 : median(reference);
        std::vector<bool> keep(std::size_t{top} + 1, false);
        for (std::uint32_t l = 1; l <= top; ++l) {
            const double cut =
                by_fruit && l > measured ? std::max(min_relative, 0.25) : min_relative;
            keep[l] = size[l] > 0 && size[l] >= min_size && size[l] >= cut * typical;
        }
        return keep;
    };
    const bool relative = min_relative > 0 && measured > 0;
    const std::vector<bool> keep = kept(relative && claimed >= 0.5 * (all - giants));
    std::vector<double> judged;
    const std::vector<bool> judged_keep = kept(relative && claimed >= 0.5 * all);
    for (std::uint32_t l = 1; l <= top; ++l) {
        if (judged_keep[l]) {
            judged.push_back(size[l]);
        }
    }
    for (auto& l : labels) {
        l = keep[l] ? l : 0;
    }
    return {renumber_by_size(labels, min_size), judged.empty() ? 0.0 : median(judged)};
}

}  // namespace

void SphereVoteParams::validate() const {
    const auto positive = [](double v, const char* name) {
        if (!(v > 0 && std::isfinite(v))) {
            throw InvalidArgument(std::string("sphere_vote: ") + name + " must be > 0");
        }
    };
    if (!(fruit_radius >= 0 && std::isfinite(fruit_radius))) {
        throw InvalidArgument("sphere_vote: fruit_radius must be >= 0 (0: estimate)");
    }
    positive(normal_scale, "normal_scale");
    positive(min_normal_scale, "min_normal_scale");
    positive(cell, "cell");
    positive(vote_cell, "vote_cell");
    positive(peak_radius, "peak_radius");
    positive(peak_separation, "peak_separation");
    positive(reach, "reach");
    if (!(sheet >= 0 && sheet < 1)) {
        throw InvalidArgument("sphere_vote: sheet must be in [0, 1)");
    }
    positive(fragment_points, "fragment_points");
    if (!(solid_refit >= 1 && std::isfinite(solid_refit))) {
        throw InvalidArgument("sphere_vote: solid_refit must be >= 1");
    }
    if (!(prior_low > 0 && prior_low <= 1)) {
        throw InvalidArgument("sphere_vote: prior_low must be in (0, 1]");
    }
    if (!(recheck_below >= 0 && recheck_below <= 1)) {
        throw InvalidArgument("sphere_vote: recheck_below must be in [0, 1]");
    }
    if (!(recheck_gain >= 0 && recheck_gain < 1)) {
        throw InvalidArgument("sphere_vote: recheck_gain must be in [0, 1)");
    }
    if (!(branch_below >= 0 && branch_below <= 1)) {
        throw InvalidArgument("sphere_vote: branch_below must be in [0, 1]");
    }
    if (!(branch_ratio >= 0 && branch_ratio <= 1)) {
        throw InvalidArgument("sphere_vote: branch_ratio must be in [0, 1]");
    }
    if (!(min_support >= 0 && min_support <= 1)) {
        throw InvalidArgument("sphere_vote: min_support must be in [0, 1]");
    }
    if (!(max_alignment > 0 && max_alignment <= 1)) {
        throw InvalidArgument("sphere_vote: max_alignment must be in (0, 1]");
    }
    if (!(min_two_way >= 0 && min_two_way <= 1.0 / 3)) {  // a sphere's normals: 1/3 each way
        throw InvalidArgument("sphere_vote: min_two_way must be in [0, 1/3]");
    }
    if (max_samples < 100) {
        throw InvalidArgument("sphere_vote: max_samples must be >= 100");
    }
    if (!(join_near >= 0 && std::isfinite(join_near)) ||
        !(join_far >= 0 && std::isfinite(join_far)) || !(join_ring >= 0 && join_ring <= 1) ||
        !(join_line >= 0 && std::isfinite(join_line)) ||
        !(join_line_far >= 0 && std::isfinite(join_line_far)) ||
        !(join_convex > 0 && join_convex <= 2) ||
        !(join_resolution >= 0 && std::isfinite(join_resolution)) ||
        !(join_slab >= 0 && std::isfinite(join_slab)) ||
        !(coarse_joins >= 0 && std::isfinite(coarse_joins))) {
        throw InvalidArgument(
            "sphere_vote: join_near, join_far, join_line, join_line_far, join_resolution, "
            "join_slab and coarse_joins must be >= 0, "
            "join_ring in [0, 1], join_convex in (0, 2]");
    }
    if (!(min_resolution >= 0 && std::isfinite(min_resolution))) {
        throw InvalidArgument("sphere_vote: min_resolution must be >= 0");
    }
    if (!(min_relative_size >= 0 && min_relative_size < 1)) {
        throw InvalidArgument("sphere_vote: min_relative_size must be in [0, 1)");
    }
}

SphereVoteResult sphere_vote(const XyzView& points,
                             std::vector<std::uint32_t> labels,
                             const SphereVoteParams& params) {
    params.validate();
    if (labels.size() != points.size) {
        throw InvalidArgument("sphere_vote: labels must be one per point (" +
                              std::to_string(points.size) + "), got " +
                              std::to_string(labels.size()));
    }
    SphereVoteResult r;
    std::size_t clustered = 0;
    for (std::uint32_t i = 0; i < points.size; ++i) {
        if (labels[i] != 0 && !is_finite(points[i])) {
            labels[i] = 0;
        }
        clustered += labels[i] != 0 ? 1 : 0;
    }
    std::vector<std::uint32_t> members;  // the clustered points (their number first: no slack)
    members.reserve(clustered);
    for (std::uint32_t i = 0; i < points.size; ++i) {
        if (labels[i] != 0) {
            members.push_back(i);
        }
    }
    // Numbers and filters the parts (the clusters, whole, when no fruit centre was found).
    CentreLabels centres;
    const auto done = [&] {
        const Finished f =
            finish(labels, params.min_cluster_size, params.min_relative_size, centres);
        r.cluster_count = f.count;
        r.median_part = f.median_part;
        r.labels = std::move(labels);
        return r;
    };
    if (members.size() < 10) {
        return done();
    }
    std::unordered_map<std::uint32_t, double> sizes;
    for (const std::uint32_t i : members) {
        sizes[labels[i]] += 1;
    }
    std::vector<double> size_list;
    for (const auto& [label, n] : sizes) {
        size_list.push_back(n);
    }
    const bool fragments = median(size_list) < params.fragment_points;
    // The points that vote (every `every`-th member), their spacing and the first rough size.
    Sample all;
    double ss = 0, first = 0;
    const auto sample = [&](std::size_t every) {
        all = thinned(points, members, labels, every);
        all.view = points.subset(all.at);  // the view points into the moved sample's `at`
        ss = search::median_spacing(all.view);
        first = params.fruit_radius > 0 ? params.fruit_radius : rough_size(all, fragments);
    };
    // Solid fruit: an isotropic inside, seen at half the fruit's size, in 5000 places, each
    // from about kSolidNeighbours of the sample's points at most (the shape of a neighbourhood
    // does not need all of them: a first size the size of the tree, where the rule kept its
    // wood, had neighbourhoods of most of the cloud, 1.8 s a run of 73k points).
    const auto looks_solid = [&] {
        const double h = std::max(0.5 * first, 3 * ss);
        const auto m = static_cast<std::size_t>(mean_neighbours(all, h) / kSolidNeighbours);
        Sample few;
        if (m > 1) {
            few = one_in(points, all, labels, m);
            few.view = points.subset(few.at);
        }
        const Sample& used = few.at.size() >= 10 ? few : all;
        return is_solid(fit_normals(used, h, std::max<std::size_t>(1, used.at.size() / 5000)));
    };
    // The size the sample must resolve: the rough size of its clusters that are not sheets
    // (leaves and the ground need no resolution: with them, the median cluster of a canopy
    // without colours is a leaf of 4.4 lattice steps, and every point of it fitted normals).
    const auto resolved_size = [&] {
        if (params.fruit_radius > 0) {
            return first;
        }
        const Sample rest = without_sheets(points, all.at, labels, all, params.sheet);
        return rest.at.empty() ? first : rough_size(rest, fragments);
    };
    std::size_t every = (members.size() + params.max_samples - 1) / params.max_samples;
    sample(every);
    // The sample must still resolve a fruit: thinned to max_samples points, a tree of 5063 apples
    // of 5.3 spacings a radius kept 2.6 a radius, where R read 25 % large and 29 % of the fruit
    // found no centre (4791 counted). Where that size spans under min_resolution spacings of the
    // sample, it is thinned less, in one step, by the square of the shortfall on surfaces and its
    // cube in solids (a stride thins a surface's spacing as its square root, a volume's as its
    // cube root): that tree every 10th point, 5064 counted. Not measured again and again: the
    // nearest-point spacing of a thinned lattice stays at one or two steps whatever the stride
    // (every 7th to 15th point of that tree: 1.41 steps), so a loop on it crept down point by
    // point to every 6th of a canopy without colours (74 s at 4M, against 17 s now).
    // (The size is looked at only when the sample is thinned: every point is as fine as it gets.)
    if (const double size = every > 1 && ss > 0 ? resolved_size() : 0;
        size > 0 && size < params.min_resolution * ss) {
        const double f = size / (params.min_resolution * ss);
        const bool volume = looks_solid();
        const double finer = static_cast<double>(every) * (volume ? f * f * f : f * f);
        if (const auto e = std::max<std::size_t>(1, std::lround(finer)); e != every) {
            every = e;
            sample(every);
        }
    }
    r.spacing = ss;
    if (!(ss > 0) || !(first > 0)) {
        return done();
    }
    // Neighbourhoods of at least min_normal_scale spacings; the points thinned to one per cube of
    // vote_cell × h, evenly over the surfaces, where a cube holds several (below kThinFrom
    // spacings every point: 1-2.5 thinned the thick outer layer of solids at 2 spacings a radius
    // far more than a stride, and a plum scene's second look at R failed, 146 -> 31 of 150).
    // The labels the thinned points take along: the clusters' until a fit is taken (they move
    // to `clusters` below), then the fit's.
    const std::vector<std::uint32_t>* current = &labels;
    const auto normals = [&](const Sample& base, double h, Sample& used) {
        h = std::max(h, params.min_normal_scale * ss);
        const double cell = params.vote_cell * h;
        used = cell >= kThinFrom * ss ? one_per_cell(points, base.at, *current, cell) : base;
        used.view = points.subset(used.at);
        return fit_normals(used, h);
    };
    // Solid fruit are reduced to their outer layer: from here on every cloud is a surface.
    r.solid = looks_solid();
    Sample s;
    const Sample surface = r.solid ? shell_of(points, all, labels, ss) : all;
    if (surface.at.size() < 10) {
        return done();
    }
    // R from where the normal lines meet, starting from a size: normals that measure R see half
    // of it (larger neighbourhoods span a bunch and feed back into ever larger estimates);
    // refitted once at the scale the first estimate gives, on surfaces only upwards (a smaller
    // neighbourhood on a noisy surface has noisier normals, whose lines meet nearer: 0.033 ->
    // 0.024 for fruit of 0.034), and kept where its normals are usable (kUsableRefit). 0 when
    // the lines say nothing.
    const auto measured = [&](double start, const Sample& base, double one_way = 0,
                              std::vector<std::uint32_t>* two_way = nullptr) {
        Normals nm = normals(base, 0.5 * start, s);
        double e = radius_from_normals(s, nm, !r.solid, one_way, two_way);
        if (e > 0 && differs(e, start) && (r.solid || e > start)) {
            const double usable_first = usable(nm);
            nm = normals(base, 0.5 * e, s);
            std::vector<std::uint32_t> again_two_way;
            const double again = radius_from_normals(s, nm, !r.solid, one_way,
                                                     two_way != nullptr ? &again_two_way : nullptr);
            if (again > 0 && usable(nm) >= kUsableRefit * usable_first) {
                e = again;
                if (two_way != nullptr) {
                    *two_way = std::move(again_two_way);
                }
            }
        }
        return e;
    };
    double R = params.fruit_radius;
    if (R > 0) {
        r.measured_radius =
            measured(rough_size(all, fragments), surface);  // a check of the given one
        // The given R is a prior: the normals measure from it, and may lower it by up to
        // 1 - prior_low (a fruit radius known roughly, or a tree's largest fruit; the measurement
        // is not allowed to raise it, as normals on noisy surfaces and solids read short).
        if (const double m = measured(R, surface); m > 0) {
            R = std::clamp(m, params.prior_low * R, R);
        }
    } else {
        R = measured(first, surface);
        if (!(R > 0)) {
            return done();
        }
        r.estimated = true;
    }

    // Each point votes for the centres at p ± R n; the peaks are the fruit. `each(f)` calls
    // f(p, n, weight, voter) for every voter.
    const auto cast = [&](double radius, const V3& origin, std::size_t voters, const auto& each) {
        Votes votes(params.cell * radius, origin, 2 * voters);
        each([&](const V3& p, const V3& n, float w, std::uint32_t voter) {
            votes.add(p + radius * n, w, voter);
            votes.add(p - radius * n, w, voter);
        });
        votes.finish();
        return votes;
    };
    // The voters (the sample's points whose normals weigh more than kVotes) are kept with a fit
    // for the line test, whose votes are cast again from them: fitting the normals again cost
    // 10-15 % of the time; keeping the votes, 12 % of the peak memory; these are copied once the
    // fit's votes are freed.
    struct Voters {
        V3 origin = V3::Zero();            // of the votes' cells
        std::vector<std::uint32_t> point;  // in `points`
        std::vector<V3> normal;
        std::vector<float> weight;
    };
    const auto vote = [&](double radius, Voters* keep) {
        const Normals nm = normals(surface, params.normal_scale * radius, s);
        const V3 origin = vec(s.view[0]) - V3::Constant(4 * radius);
        std::vector<std::uint32_t> voters;  // in the sample
        for (std::uint32_t i = 0; i < s.view.size; ++i) {
            if (nm.w[i] > kVotes) {
                voters.push_back(i);
            }
        }
        std::vector<Peak> found = cast(radius, origin, voters.size(), [&](const auto& f) {
                                      for (const std::uint32_t i : voters) {
                                          f(vec(s.view[i]), nm.n[i], nm.w[i], i);
                                      }
                                  }).peaks(params, s, radius, nm);
        if (keep != nullptr) {
            *keep = Voters{origin, {}, {}, {}};
            keep->point.reserve(voters.size());
            keep->normal.reserve(voters.size());
            keep->weight.reserve(voters.size());
            for (const std::uint32_t i : voters) {
                keep->point.push_back(s.at[i]);
                keep->normal.push_back(nm.n[i]);
                keep->weight.push_back(nm.w[i]);
            }
        }
        return found;
    };
    // The votes of kept voters (numbered in their order: the votes sort as the fit's did).
    const auto cast_again = [&](double radius, const Voters& v) {
        return cast(radius, v.origin, v.point.size(), [&](const auto& f) {
            for (std::uint32_t k = 0; k < v.point.size(); ++k) {
                f(vec(points[v.point[k]]), v.normal[k], v.weight[k], k);
            }
        });
    };
    // The peaks at a radius, and the members given to them, starting again from the clusters
    // every time (a solid's refit and the second look below try other radii).
    struct Fit {
        std::vector<Peak> peaks;
        std::vector<std::uint32_t> labels;
        Voters voters;  // where the line test will read them (join_line)
    };
    // Moved, not copied: until the first fit is taken they are `labels` (a third copy of the
    // labels of 1M points while voting was 3 MB of pc_fruitcount's peak).
    const std::vector<std::uint32_t> clusters = std::move(labels);
    current = &clusters;
    const auto attempt = [&](double radius) {
        Voters v;
        std::vector<Peak> found =  // before the labels' copy (peak memory)
            vote(radius, params.join_line > 0 && params.join_near > 0 ? &v : nullptr);
        Fit f{std::move(found), clusters, std::move(v)};
        if (!f.peaks.empty()) {
            assign(points, members, f.labels, f.peaks, params, radius);
        }
        return f;
    };
    std::vector<Peak> peaks;
    Voters voters;
    const auto take = [&](Fit&& f, double radius) {
        peaks = std::move(f.peaks);
        labels = std::move(f.labels);
        voters = std::move(f.voters);
        current = &labels;
        R = radius;
        r.fruit_radius = R;
    };
    take(attempt(R), R);
    if (peaks.empty()) {
        return done();
    }
    // The share of the points `of` that the `fruit` centres of `lab` took.
    const auto share = [&](const std::vector<std::uint32_t>& lab, std::size_t fruit,
                           const std::vector<std::uint32_t>& of) {
        const auto n = std::count_if(
            of.begin(), of.end(), [&](std::uint32_t i) { return lab[i] >= 1 && lab[i] <= fruit; });
        return of.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(of.size());
    };
    // Solid fruit: R from the outer layer's normals reads short (about 0.65-0.8 of the fruit's in
    // random volumes, and a fruit of 3 spacings then splits in two). The points given to each
    // centre tell the size: in a filled ball the median distance from the centre is R·0.5^(1/3).
    // Used when the distances spread as a ball's do (a shell's quartiles lie close together) and
    // it says R is larger by more than solid_refit: vote again with it.
    if (r.solid && r.estimated) {
        std::vector<double> d;  // a strided sample of at most max_samples points
        const std::size_t stride = (members.size() + params.max_samples - 1) / params.max_samples;
        for (std::size_t k = 0; k < members.size(); k += stride) {
            const std::uint32_t i = members[k];
            if (labels[i] >= 1 && labels[i] <= peaks.size()) {
                d.push_back((vec(points[i]) - peaks[labels[i] - 1].centre).norm());
            }
        }
        if (d.size() >= 100) {
            const double filled = percentile(d, 50) / std::cbrt(0.5);
            const double q25 = percentile(d, 25), q75 = percentile(d, 75);
            if (q25 < 0.8 * q75 && filled > params.solid_refit * R) {
                take(attempt(filled), filled);
                if (peaks.empty()) {
                    return done();
                }
            }
        }
    }
    r.claimed = share(labels, peaks.size(), members);
    // A smaller R is taken when its centres claim more of the points `judged` (recheck_gain).
    const auto try_smaller = [&](double smaller, const std::vector<std::uint32_t>& judged) {
        Fit f = attempt(smaller);
        if (f.peaks.empty() || !(share(f.labels, f.peaks.size(), judged) >
                                 share(labels, peaks.size(), judged) + params.recheck_gain)) {
            return false;
        }
        const double c = share(f.labels, f.peaks.size(), members);
        if (r.larger_radius == 0) {
            r.larger_radius = R;
        }
        take(std::move(f), smaller);
        r.claimed = c;
        return true;
    };
    // Leaves read as fruit: where colour could not tell leaves from fruit (green fruit), the rims
    // of flat leaves (their normals bend at the edges) set R near a leaf's size (grapes of 4 mm
    // among leaves of 16: R 21-28 mm, 14 and 31 counted of 176 and 164). Where the centres leave
    // points unclaimed, R is measured again without the clusters that are sheets.
    if (r.estimated && r.claimed < params.recheck_below) {
        const Sample rest = without_sheets(points, members, clusters, surface, params.sheet);
        if (!rest.at.empty()) {
            const double smaller = measured(first, rest);
            if (smaller > 0 && smaller < R / 1.1) {
                try_smaller(smaller, members);
            }
        }
    }
    // Branches read as fruit: where the tree's wood holds more points than the fruit, the normal
    // lines of its branches meet on their axes and set R near a branch's radius (grapes of 9 mm
    // beside a trunk of 50: R 46, 25 counted of 200). Where the centres leave points unclaimed, R
    // is measured again without the points whose surroundings curve one way only (branch_ratio),
    // and the two R are judged by the share of those points (the measurement's sample) their
    // centres claim: the branch-sized centres take chunks of the wood, which can outnumber all
    // the fruit (grapes and dates beside a trunk 7 times their radius: 5 centres claimed 20 % of
    // all points, the fruit's R 40 times as many centres 17-18 %; of the points not on a branch's
    // side 24 % and 53 %).
    if (r.estimated && params.branch_ratio > 0 && r.claimed < params.branch_below) {
        std::vector<std::uint32_t> two_way;
        const double smaller = measured(first, surface, params.branch_ratio, &two_way);
        if (smaller > 0 && smaller < R / kThicker) {
            try_smaller(smaller, two_way);
        }
    }
    // Bunches read as fruit: where the centres leave points unclaimed, R may be a bunch's (its
    // normal lines meet at the bunch's scale; a solid bunch's points spread as one ball's). R is
    // measured again from normals of a quarter of it (where a smaller fruit's curvature shows),
    // and the smaller R is taken when its centres claim more of the points; up to three times.
    if (r.estimated) {
        for (int k = 0; k < 3 && r.claimed < params.recheck_below; ++k) {
            const double smaller = measured(0.5 * R, surface);
            if (!(smaller > 0 && smaller < R / 1.1) || !try_smaller(smaller, members)) {
                break;
            }
        }
    }
    // Elongated fruit split in two are joined where the cloud resolves a fruit's profile, and
    // coarser where the joins are many (coarse_joins). The fit's votes are cast again from its
    // voters for the line test and freed before the join.
    std::uint32_t joined = 0;
    if (params.join_near > 0) {
        std::vector<std::pair<std::uint32_t, std::uint32_t>> lines;
        if (params.join_line > 0) {
            const Votes again = cast_again(R, voters);
            // Long fruit side by side: centres sharp on a line (kSharpLine), in the final fit
            // only, where they add centres; the voters are the kept ones, with their normals.
            if (R >= kLinePeaks * ss && !voters.point.empty()) {
                Sample kept{std::move(voters.point), {}, {}};
                kept.view = points.subset(kept.at);
                Normals nm;
                nm.n = std::move(voters.normal);
                nm.w = std::move(voters.weight);
                std::vector<Peak> more = again.peaks(params, kept, R, nm, true);
                if (more.size() > peaks.size()) {
                    labels = clusters;
                    assign(points, members, labels, more, params, R);
                    peaks = std::move(more);
                }
            }
            lines = line_pairs(peaks, again, R, ss, params);
            voters = Voters{};
        }
        if (R >= params.join_resolution * ss) {
            joined = join_elongated(points, members, labels, peaks, lines, R, ss, params);
        } else {
            std::vector<std::uint32_t> trial = labels, counted = labels;
            const std::uint32_t joins =
                join_elongated(points, members, trial, peaks, lines, R, ss, params);
            const double fewer = parts(labels, members) - parts(trial, members);
            const std::uint32_t count =
                finish(counted, params.min_cluster_size, params.min_relative_size,
                       {static_cast<std::uint32_t>(peaks.size()),
                        static_cast<std::uint32_t>(peaks.size())})
                    .count;
            if (fewer > 0 && fewer >= params.coarse_joins * count) {
                labels = std::move(trial);
                joined = joins;
            }
        }
    }
    part_leftovers_on_lattice(points, members, labels, static_cast<std::uint32_t>(peaks.size()), R,
                              ss);
    r.peaks = static_cast<std::uint32_t>(peaks.size()) - joined;
    centres = {static_cast<std::uint32_t>(peaks.size()), r.peaks};
    return done();
}

}  // namespace pc::segmentation
