#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <unordered_map>

#include <pc/core/error.h>
#include <pc/evaluation/instances.h>

namespace pc::evaluation {

namespace {

/// Points per predicted label, per fruit id and per (label, id) pair. Labels with fewer than
/// min_points points are dropped (they are noise for the evaluation).
struct Table {
    std::map<std::uint32_t, std::size_t> label_size, fruit_size;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> pair;
};

Table tabulate(std::span<const std::uint32_t> predicted,
               std::span<const std::uint32_t> truth,
               std::uint32_t min_points) {
    if (predicted.size() != truth.size()) {
        throw InvalidArgument("evaluation: " + std::to_string(predicted.size()) + " labels for " +
                              std::to_string(truth.size()) + " ground-truth ids");
    }
    std::unordered_map<std::uint32_t, std::size_t> all;
    for (auto l : predicted) {
        ++all[l];
    }
    Table t;
    for (std::size_t n = 0; n < predicted.size(); ++n) {
        const auto l = predicted[n], g = truth[n];
        const bool kept = l != 0 && all[l] >= min_points;
        if (kept) {
            ++t.label_size[l];
        }
        if (g != 0) {
            ++t.fruit_size[g];
        }
        if (kept && g != 0) {
            ++t.pair[{l, g}];
        }
    }
    return t;
}

/// Merges and splits (see InstanceParams::share), and the counts and rates from the matches.
InstanceScores finish(const Table& t,
                      std::size_t gt_count,
                      std::vector<Match> matches,
                      double share) {
    InstanceScores s;
    s.count = t.label_size.size();
    s.gt_count = gt_count;
    std::map<std::uint32_t, int> fruit_held_by_label, label_made_of_fruit;
    for (const auto& [key, n] : t.pair) {
        const auto [l, g] = key;
        if (static_cast<double>(n) > share * static_cast<double>(t.fruit_size.at(g))) {
            ++fruit_held_by_label[l];
        }
        if (static_cast<double>(n) > share * static_cast<double>(t.label_size.at(l))) {
            ++label_made_of_fruit[g];
        }
    }
    for (const auto& [l, k] : fruit_held_by_label) {
        if (k >= 2) {
            s.merged.push_back(l);
        }
    }
    for (const auto& [g, k] : label_made_of_fruit) {
        if (k >= 2) {
            s.split.push_back(g);
        }
    }
    std::sort(matches.begin(), matches.end(),
              [](const Match& a, const Match& b) { return a.label < b.label; });
    s.true_positives = matches.size();
    s.matches = std::move(matches);
    const double tp = static_cast<double>(s.true_positives);
    const double pred = static_cast<double>(s.count), gt = static_cast<double>(s.gt_count);
    s.precision = s.count ? tp / pred : (s.gt_count ? 0.0 : 1.0);
    s.recall = s.gt_count ? tp / gt : 1.0;
    s.f1 = s.count + s.gt_count ? 2 * tp / (pred + gt) : 1.0;
    s.recovery = s.gt_count ? pred / gt : std::numeric_limits<double>::quiet_NaN();
    return s;
}

/// Accepts candidate pairs in the given order while both sides are unmatched.
std::vector<Match> greedy(const std::vector<Match>& ordered) {
    std::unordered_map<std::uint32_t, bool> label_used, fruit_used;
    std::vector<Match> out;
    for (const Match& m : ordered) {
        if (!label_used[m.label] && !fruit_used[m.fruit]) {
            label_used[m.label] = fruit_used[m.fruit] = true;
            out.push_back(m);
        }
    }
    return out;
}

std::size_t checked_gt_count(std::size_t given, std::size_t present) {
    if (given != 0 && given < present) {
        throw InvalidArgument("evaluation: ground-truth count " + std::to_string(given) +
                              " is below the " + std::to_string(present) +
                              " fruit present in the cloud");
    }
    return given ? given : present;
}

}  // namespace

void InstanceParams::validate() const {
    if (!(min_iou >= 0.5 && min_iou < 1)) {
        throw InvalidArgument("evaluation: min_iou must be in [0.5, 1), got " +
                              format_number(min_iou));
    }
    if (!(share >= 0.5 && share < 1)) {
        throw InvalidArgument("evaluation: share must be in [0.5, 1), got " + format_number(share));
    }
    if (!(radius_factor > 0 && std::isfinite(radius_factor))) {
        throw InvalidArgument("evaluation: radius_factor must be > 0, got " +
                              format_number(radius_factor));
    }
}

InstanceScores score_by_overlap(std::span<const std::uint32_t> predicted,
                                std::span<const std::uint32_t> truth,
                                std::size_t gt_count,
                                const InstanceParams& p) {
    p.validate();
    const Table t = tabulate(predicted, truth, p.min_points);
    std::vector<Match> candidates;
    for (const auto& [key, n] : t.pair) {
        const double inter = static_cast<double>(n);
        const double uni =
            static_cast<double>(t.label_size.at(key.first) + t.fruit_size.at(key.second)) - inter;
        const double iou = inter / uni;
        if (iou > p.min_iou) {
            candidates.push_back({key.first, key.second, inter, iou});
        }
    }
    std::sort(candidates.begin(), candidates.end(), [](const Match& a, const Match& b) {
        return a.iou != b.iou       ? a.iou > b.iou
               : a.label != b.label ? a.label < b.label
                                    : a.fruit < b.fruit;
    });
    return finish(t, checked_gt_count(gt_count, t.fruit_size.size()), greedy(candidates), p.share);
}

InstanceScores score_by_centroid(const Cloud& cloud,
                                 std::span<const std::uint32_t> predicted,
                                 std::span<const TruthFruit> fruits,
                                 std::size_t gt_count,
                                 const InstanceParams& p) {
    p.validate();
    if (predicted.size() != cloud.size()) {
        throw InvalidArgument("evaluation: " + std::to_string(predicted.size()) + " labels for " +
                              std::to_string(cloud.size()) + " points");
    }
    // Fruit sorted by x, so a point or centroid looks only at the slab that can hold it.
    std::vector<std::size_t> by_x(fruits.size());
    double reach = 0;
    for (std::size_t f = 0; f < fruits.size(); ++f) {
        by_x[f] = f;
        if (!(fruits[f].radius > 0) || fruits[f].id == 0) {
            throw InvalidArgument("evaluation: fruit " + std::to_string(f) +
                                  " needs an id > 0 and a radius > 0");
        }
        reach = std::max(reach, p.radius_factor * fruits[f].radius);
    }
    std::sort(by_x.begin(), by_x.end(),
              [&](auto a, auto b) { return fruits[a].centre[0] < fruits[b].centre[0]; });
    const auto near = [&](const std::array<double, 3>& q, auto&& visit) {
        auto it =
            std::lower_bound(by_x.begin(), by_x.end(), q[0] - reach,
                             [&](std::size_t f, double x) { return fruits[f].centre[0] < x; });
        for (; it != by_x.end() && fruits[*it].centre[0] <= q[0] + reach; ++it) {
            const auto& f = fruits[*it];
            const double dx = q[0] - f.centre[0], dy = q[1] - f.centre[1], dz = q[2] - f.centre[2];
            const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
            if (d <= p.radius_factor * f.radius) {
                visit(f, d);
            }
        }
    };
    // Attribute points to fruit, then tabulate as the overlap mode does.
    std::vector<std::uint32_t> truth(cloud.size(), 0);
    for (std::size_t n = 0; n < cloud.size(); ++n) {
        const auto& pt = cloud[n];
        if (!std::isfinite(pt.x) || !std::isfinite(pt.y) || !std::isfinite(pt.z)) {
            continue;
        }
        double best = std::numeric_limits<double>::infinity();
        near({pt.x, pt.y, pt.z}, [&](const TruthFruit& f, double d) {
            if (d < best || (d == best && f.id < truth[n])) {
                best = d;
                truth[n] = f.id;
            }
        });
    }
    const Table t = tabulate(predicted, truth, p.min_points);
    std::map<std::uint32_t, std::array<double, 4>> sums;  // x, y, z, finite points
    for (std::size_t n = 0; n < cloud.size(); ++n) {
        const auto& pt = cloud[n];
        if (t.label_size.contains(predicted[n]) && std::isfinite(pt.x) && std::isfinite(pt.y) &&
            std::isfinite(pt.z)) {
            auto& s = sums[predicted[n]];
            s[0] += pt.x;
            s[1] += pt.y;
            s[2] += pt.z;
            s[3] += 1;
        }
    }
    std::vector<Match> candidates;
    for (const auto& [predicted_label, s] : sums) {
        const std::array<double, 3> c{s[0] / s[3], s[1] / s[3], s[2] / s[3]};
        const std::uint32_t label = predicted_label;  // clang 14 cannot capture a binding
        near(c, [&](const TruthFruit& f, double d) { candidates.push_back({label, f.id, d, 0}); });
    }
    std::sort(candidates.begin(), candidates.end(), [](const Match& a, const Match& b) {
        return a.overlap != b.overlap ? a.overlap < b.overlap
               : a.label != b.label   ? a.label < b.label
                                      : a.fruit < b.fruit;
    });
    return finish(t, checked_gt_count(gt_count, fruits.size()), greedy(candidates), p.share);
}

}  // namespace pc::evaluation
