#pragma once
// The count report (pc_count, pc_fruitcount): apart from steps.h, which most tools include,
// because the JSON library's header is slow to compile.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <pc/pipeline/steps.h>

namespace pc::pipeline {

/// The count report of a labelled cloud, as JSON (pc_count, pc_fruitcount):
/// count, noise_points, small_clusters, clusters [{id, points, centroid, aabb {min, max}}],
/// with `gt`: gt, count_error (count − gt), recovery (count / gt); `cluster_sizes` {median points,
/// `several` (clusters over 1.75 x the median: several fruit?), `fragments` (under 0.25 x the
/// median)}; then `steps` [{step, points_in, points_out, and the step's values}] when given (a
/// chain), `eps_check` {eps, counts} when given, and `warnings` (always, possibly empty).
[[nodiscard]] nlohmann::ordered_json count_report(const segmentation::ClusterSummary& s,
                                                  std::optional<double> gt,
                                                  const std::vector<StepRecord>& steps = {},
                                                  const std::vector<std::string>& warnings = {},
                                                  const std::optional<EpsCheck>& eps_check = {});

}  // namespace pc::pipeline
