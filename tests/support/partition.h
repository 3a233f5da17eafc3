#pragma once
// Scoring a labelling against the true objects, for the splitters' tests.

#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include <gtest/gtest.h>

namespace pc::test {

/// Points whose label is not the majority label of their true object (truth 0, not fruit, is
/// no object), or -1 when two objects share a majority label (a merge) or one's is noise (0).
inline long misassigned(const std::vector<std::uint32_t>& got,
                        const std::vector<std::uint32_t>& truth) {
    std::map<std::uint32_t, std::map<std::uint32_t, long>> votes;
    for (std::size_t k = 0; k < got.size(); ++k) {
        ++votes[truth[k]][got[k]];
    }
    long wrong = 0;
    std::set<std::uint32_t> used;
    for (const auto& [id, v] : votes) {
        if (id == 0) {
            continue;
        }
        long best = 0, all = 0;
        std::uint32_t label = 0;
        for (const auto& [l, n] : v) {
            if (n > best) {
                best = n;
                label = l;
            }
            all += n;
        }
        if (label == 0 || !used.insert(label).second) {
            return -1;
        }
        wrong += all - best;
    }
    return wrong;
}

/// misassigned() under one in `one_in` of the points (`truth.size() / one_in`, rounded down),
/// as a gtest predicate whose failure says how many went wrong or that two fruit merged:
/// `EXPECT_TRUE(few_misassigned(r.labels, s.truth, 100))`.
inline ::testing::AssertionResult few_misassigned(const std::vector<std::uint32_t>& got,
                                                  const std::vector<std::uint32_t>& truth,
                                                  std::size_t one_in) {
    const long wrong = misassigned(got, truth);
    const auto most = static_cast<long>(truth.size() / one_in);
    if (wrong < 0) {
        return ::testing::AssertionFailure()
               << "two fruit share a part, or a fruit's points went mostly to noise";
    }
    if (wrong >= most) {
        return ::testing::AssertionFailure()
               << wrong << " of " << truth.size() << " points misassigned (under " << most
               << " allowed)";
    }
    return ::testing::AssertionSuccess();
}

/// Objects whose points' largest share (majority label) went to a label no other object's did,
/// noise (0) not counted: the fruit found alone in a part, where misassigned() gives up at the
/// first merge.
inline long alone(const std::vector<std::uint32_t>& got, const std::vector<std::uint32_t>& truth) {
    std::map<std::uint32_t, std::map<std::uint32_t, long>> votes;
    for (std::size_t k = 0; k < got.size(); ++k) {
        ++votes[truth[k]][got[k]];
    }
    std::map<std::uint32_t, long> owners;
    for (const auto& [id, v] : votes) {
        if (id != 0) {
            ++owners[std::max_element(v.begin(), v.end(), [](const auto& a, const auto& b) {
                         return a.second < b.second;
                     })->first];
        }
    }
    return std::count_if(owners.begin(), owners.end(),
                         [](const auto& o) { return o.first != 0 && o.second == 1; });
}

}  // namespace pc::test
