#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <pc/core/cloud.h>

namespace pc::evaluation {

/// Parameters of the instance evaluation (docs/tools/pc_eval.md).
struct InstanceParams {
    double min_iou =
        0.5;  ///< overlap matching: a pair matches when IoU > this (>= 0.5 keeps it one-to-one)
    double share = 0.5;            ///< merge: a prediction holds > share of each of >= 2 fruit;
                                   ///< split: >= 2 predictions each made of > share of one fruit
    double radius_factor = 1.0;    ///< centroid matching: centroid within this × the fruit radius
    std::uint32_t min_points = 1;  ///< predictions with fewer points are treated as noise

    void validate() const;
};

/// A ground-truth fruit for centroid matching.
struct TruthFruit {
    std::uint32_t id = 0;
    std::array<double, 3> centre{};
    double radius = 0;
};

/// A matched pair: predicted label and ground-truth id, with the overlap (points) or the distance.
struct Match {
    std::uint32_t label = 0, fruit = 0;
    double overlap = 0;  ///< points shared (overlap mode) or centroid distance (centroid mode)
    double iou = 0;      ///< overlap mode only
};

struct InstanceScores {
    std::size_t count = 0;     ///< predicted instances (labels != 0 with >= min_points points)
    std::size_t gt_count = 0;  ///< ground-truth fruit
    std::size_t true_positives = 0;  ///< one-to-one matches
    double precision = 0, recall = 0, f1 = 0, recovery = 0;
    std::vector<std::uint32_t> merged;  ///< predictions holding > share of >= 2 fruit
    std::vector<std::uint32_t> split;   ///< fruit with >= 2 predictions made mostly of it
    std::vector<Match> matches;         ///< sorted by label
};

/// Scores predicted labels (0 = noise) against per-point ground-truth ids (0 = not fruit).
/// `gt_count` = 0 takes the number of distinct ids present; a larger value also counts fruit
/// absent from the cloud as missed. Matching: greedy by decreasing IoU, ties by smaller ids.
[[nodiscard]] InstanceScores score_by_overlap(std::span<const std::uint32_t> predicted,
                                              std::span<const std::uint32_t> truth,
                                              std::size_t gt_count,
                                              const InstanceParams& params);

/// Scores predicted labels by their centroids (FruitNeRF's matching): pairs whose centroid lies
/// within radius_factor × the fruit radius, matched greedily by increasing distance. Points are
/// attributed to the nearest fruit whose scaled sphere holds them, for merges and splits.
/// `gt_count` = 0 takes the number of fruit given; it may not be smaller.
[[nodiscard]] InstanceScores score_by_centroid(const Cloud& cloud,
                                               std::span<const std::uint32_t> predicted,
                                               std::span<const TruthFruit> fruits,
                                               std::size_t gt_count,
                                               const InstanceParams& params);

}  // namespace pc::evaluation
