#include <algorithm>
#include <iterator>
#include <numeric>
#include <string>
#include <unordered_map>

#include <pc/cameras/join_instances.h>
#include <pc/core/error.h>
#include <pc/core/labels.h>

namespace pc::cameras {

void JoinParams::validate() const {
    if (!(fragment >= 0 && fragment <= 1)) {
        throw InvalidArgument("join_instances: fragment must be in [0, 1], got " +
                              format_number(fragment));
    }
}

namespace {

/// Groups of nodes with the views they hold: a union-find whose roots keep their views sorted
/// (memory one entry a node, whatever the number of views).
class Groups {
public:
    explicit Groups(const std::vector<std::uint32_t>& view_of)
        : parent_(view_of.size()), views_(view_of.size()) {
        std::iota(parent_.begin(), parent_.end(), 0u);
        for (std::size_t n = 0; n < view_of.size(); ++n) {
            views_[n] = {view_of[n]};
        }
    }

    std::uint32_t root(std::uint32_t n) { return find_root(parent_, n); }

    /// Joins the groups of a and b unless they hold an instance of the same view; true if
    /// they are one group afterwards.
    bool join(std::uint32_t a, std::uint32_t b) {
        a = root(a);
        b = root(b);
        if (a == b) {
            return true;
        }
        const std::vector<std::uint32_t>& small =
            views_[a].size() < views_[b].size() ? views_[a] : views_[b];
        const std::vector<std::uint32_t>& large = &small == &views_[a] ? views_[b] : views_[a];
        for (const std::uint32_t v : small) {
            if (std::binary_search(large.begin(), large.end(), v)) {
                return false;
            }
        }
        if (b < a) {
            std::swap(a, b);
        }
        std::vector<std::uint32_t> joined;
        joined.reserve(views_[a].size() + views_[b].size());
        std::merge(views_[a].begin(), views_[a].end(), views_[b].begin(), views_[b].end(),
                   std::back_inserter(joined));
        views_[a] = std::move(joined);
        views_[b] = {};
        parent_[b] = a;
        return true;
    }

private:
    std::vector<std::uint32_t> parent_;
    std::vector<std::vector<std::uint32_t>> views_;
};

constexpr std::uint32_t kNone = 0xffffffffu;

/// Two ids as one key that sorts and counts, the smaller first (an undirected pair).
std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}
std::uint32_t first_of(std::uint64_t key) { return static_cast<std::uint32_t>(key >> 32); }
std::uint32_t second_of(std::uint64_t key) { return static_cast<std::uint32_t>(key & 0xffffffffu); }

/// The distinct keys of `keys` in ascending order with how often each occurs.
std::vector<std::pair<std::uint64_t, std::uint32_t>> count_keys(std::vector<std::uint64_t> keys) {
    std::sort(keys.begin(), keys.end());
    std::vector<std::pair<std::uint64_t, std::uint32_t>> counts;
    for (std::size_t j = 0; j < keys.size();) {
        std::size_t e = j;
        while (e < keys.size() && keys[e] == keys[j]) {
            ++e;
        }
        counts.emplace_back(keys[j], static_cast<std::uint32_t>(e - j));
        j = e;
    }
    return counts;
}

/// Instances that another view splits: several fruit seen as one (an under-segmented mask, or
/// fruit one behind the other). Among an instance's links to one other view's instances, the
/// second largest shares at least kSplit of what the two largest share, and at least kMinSplit
/// points: more than the few points at a contact that land on a neighbour's instance.
template <class Link>
std::vector<std::uint8_t> split_by_another_view(const std::vector<Link>& links,
                                                const std::vector<std::uint32_t>& view_of) {
    constexpr double kSplit = 0.25;
    constexpr std::uint32_t kMinSplit = 3;
    struct Seen {
        std::uint32_t node, view, shared;
    };
    std::vector<Seen> seen;
    seen.reserve(2 * links.size());
    for (const Link& l : links) {
        const std::uint32_t a = first_of(l.pair), b = second_of(l.pair);
        seen.push_back({a, view_of[b], l.shared});
        seen.push_back({b, view_of[a], l.shared});
    }
    std::sort(seen.begin(), seen.end(), [](const Seen& x, const Seen& y) {
        return x.node != y.node   ? x.node < y.node
               : x.view != y.view ? x.view < y.view
                                  : x.shared > y.shared;
    });
    std::vector<std::uint8_t> several(view_of.size(), 0);
    for (std::size_t j = 0; j < seen.size();) {
        std::size_t e = j + 1;
        while (e < seen.size() && seen[e].node == seen[j].node && seen[e].view == seen[j].view) {
            ++e;
        }
        const std::uint32_t first = seen[j].shared, second = e > j + 1 ? seen[j + 1].shared : 0;
        if (second >= kMinSplit && second >= kSplit * (first + second)) {
            several[seen[j].node] = 1;
        }
        j = e;
    }
    return several;
}

/// Joins a group to a larger one it touches in space (a pair of `touching` points, one in each)
/// when no view sees the two apart and it holds at most `fragment` times the larger one's points:
/// the part of a fruit that only views seeing nothing else of it saw shares no point with the
/// rest of the fruit's instances. Pairs are taken by their touching points over the smaller
/// group's points, most first. `group` and `size` are by root; sizes move to the new root.
void join_fragments(const std::vector<std::pair<std::uint32_t, std::uint32_t>>& touching,
                    const std::vector<std::uint32_t>& group,
                    std::vector<std::uint32_t>& size,
                    const JoinParams& params,
                    Groups& groups) {
    std::vector<std::uint64_t> pairs;
    for (const auto& [i, j] : touching) {
        if (i < group.size() && j < group.size() && group[i] != kNone && group[j] != kNone &&
            group[i] != group[j]) {
            pairs.push_back(pair_key(group[i], group[j]));
        }
    }
    struct Contact {
        std::uint32_t a, b;
        double strength;
    };
    std::vector<Contact> contacts;
    for (const auto& [pair, n] : count_keys(std::move(pairs))) {
        const std::uint32_t a = first_of(pair), b = second_of(pair);
        contacts.push_back({a, b, static_cast<double>(n) / std::min(size[a], size[b])});
    }
    std::stable_sort(contacts.begin(), contacts.end(),
                     [](const Contact& x, const Contact& y) { return x.strength > y.strength; });
    for (const Contact& c : contacts) {
        const std::uint32_t a = groups.root(c.a), b = groups.root(c.b);
        const std::uint32_t small = size[a] < size[b] ? a : b, large = small == a ? b : a;
        if (a == b || size[small] > params.fragment * size[large]) {
            continue;
        }
        const std::uint32_t total = size[a] + size[b];
        if (groups.join(a, b)) {
            size[a] = size[b] = 0;
            size[groups.root(a)] = total;
        }
    }
}

}  // namespace

JoinResult join_instances(std::vector<Sighting> sightings,
                          const std::vector<std::uint8_t>& keep,
                          const std::vector<std::pair<std::uint32_t, std::uint32_t>>& touching,
                          const JoinParams& params) {
    params.validate();
    const std::size_t n_points = keep.size();
    std::erase_if(sightings, [&](const Sighting& s) {
        return s.instance == 0 || s.point >= n_points || keep[s.point] == 0;
    });
    JoinResult out;
    out.labels.assign(n_points, 0);
    if (sightings.empty()) {
        return out;
    }
    // By point (a counting sort: run[p] .. run[p + 1] are point p's), each point's by view.
    std::vector<std::size_t> run(n_points + 1, 0);
    for (const Sighting& x : sightings) {
        ++run[x.point + 1];
    }
    for (std::size_t p = 0; p < n_points; ++p) {
        run[p + 1] += run[p];
    }
    {
        std::vector<Sighting> by_point(sightings.size());
        std::vector<std::size_t> next(run.begin(), run.end() - 1);
        for (const Sighting& x : sightings) {
            by_point[next[x.point]++] = x;
        }
        sightings = std::move(by_point);
    }
    for (std::size_t p = 0; p < n_points; ++p) {
        std::sort(sightings.begin() + static_cast<std::ptrdiff_t>(run[p]),
                  sightings.begin() + static_cast<std::ptrdiff_t>(run[p + 1]),
                  [](const Sighting& a, const Sighting& b) { return a.view < b.view; });
    }
    // Nodes: the distinct (view, instance) pairs, numbered as they first appear in that order.
    std::unordered_map<std::uint64_t, std::uint32_t> number;
    std::vector<std::uint32_t> view_of, node(sightings.size());
    for (std::size_t j = 0; j < sightings.size(); ++j) {
        const Sighting& x = sightings[j];
        const auto [it, added] = number.try_emplace((std::uint64_t{x.view} << 32) | x.instance,
                                                    static_cast<std::uint32_t>(view_of.size()));
        if (added) {
            view_of.push_back(x.view);
        }
        node[j] = it->second;
    }
    number = {};
    // Each point links one of its instances (which one moves from point to point) to each of
    // the others: a star, m - 1 links for m sightings instead of all m (m - 1) / 2 pairs, which
    // still counts every pair of a point's instances with the same chance, 2 / m.
    std::vector<std::uint64_t> pairs;
    pairs.reserve(sightings.size());
    for (std::size_t p = 0; p < n_points; ++p) {
        const std::size_t begin = run[p], m = run[p + 1] - begin;
        if (m == 0) {
            continue;
        }
        const std::uint32_t hub = node[begin + sightings[begin].point % m];
        for (std::size_t j = begin; j < begin + m; ++j) {
            if (node[j] != hub) {
                pairs.push_back(pair_key(hub, node[j]));
            }
        }
    }
    // A link's strength: its shared points over the larger node's points. Two views of one fruit
    // share most of both; a view that sees two touching fruit as one instance shares about half
    // of itself with each, so it cannot join them before each fruit's own views have met.
    std::vector<std::uint32_t> points_in(view_of.size(), 0);
    for (const std::uint32_t n : node) {
        ++points_in[n];
    }
    struct Link {
        std::uint64_t pair;
        std::uint32_t shared;
        double strength;
    };
    std::vector<Link> links;
    for (const auto& [pair, shared] : count_keys(std::move(pairs))) {
        const std::uint32_t larger =
            std::max(points_in[first_of(pair)], points_in[second_of(pair)]);
        links.push_back({pair, shared, static_cast<double>(shared) / larger});
    }
    const std::vector<std::uint8_t> several = split_by_another_view(links, view_of);
    std::erase_if(links, [&](const Link& l) {
        return several[first_of(l.pair)] != 0 || several[second_of(l.pair)] != 0;
    });
    std::stable_sort(links.begin(), links.end(),
                     [](const Link& a, const Link& b) { return a.strength > b.strength; });
    Groups groups(view_of);
    for (const Link& l : links) {
        groups.join(first_of(l.pair), second_of(l.pair));
    }
    // Each point to the group most of its sightings belong to (ties: the lower group), counting
    // instances of several fruit only for points no other instance saw.
    std::vector<std::uint32_t> group(n_points, kNone), size(view_of.size(), 0);
    std::vector<std::uint32_t> roots;
    for (std::size_t p = 0; p < n_points; ++p) {
        roots.clear();
        bool fallback = false;
        for (int pass = 0; pass < 2 && roots.empty(); ++pass) {
            for (std::size_t j = run[p]; j < run[p + 1]; ++j) {
                if (pass == 1 || several[node[j]] == 0) {
                    roots.push_back(groups.root(node[j]));
                }
            }
            fallback = pass == 1;
        }
        if (roots.empty()) {
            continue;
        }
        std::sort(roots.begin(), roots.end());
        std::size_t best_count = 0;
        for (std::size_t j = 0; j < roots.size();) {
            std::size_t e = j;
            while (e < roots.size() && roots[e] == roots[j]) {
                ++e;
            }
            if (e - j > best_count) {
                group[p] = roots[j];
                best_count = e - j;
            }
            j = e;
        }
        ++size[group[p]];
        ++out.labelled;
        out.doubtful += fallback || (roots.size() >= 2 && 2 * best_count <= roots.size());
    }
    join_fragments(touching, group, size, params, groups);
    for (std::size_t i = 0; i < n_points; ++i) {
        out.labels[i] = group[i] == kNone ? 0 : groups.root(group[i]) + 1;
    }
    renumber_by_size(out.labels);
    return out;
}

}  // namespace pc::cameras
