#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include <pc/evaluation/instances.h>

namespace pc::evaluation {

enum class ScoreFormat { kJson, kCsv, kMarkdown };

/// The report of pc_eval (docs/tools/pc_eval.md) for one scored cloud: JSON with every score,
/// the merged labels, the split fruit and the matches (points and IoU when matched by `mode`
/// "overlap", distance by "centroid"); or a CSV or markdown table row under its header. `name`
/// is the row's name, `input` the cloud's; the JSON carries `header` (tool, version,
/// parameters) after them and ends with `warnings` (nothing predicted, no ground truth).
[[nodiscard]] std::string score_report(const InstanceScores& s,
                                       const std::string& name,
                                       const std::string& input,
                                       const std::string& mode,
                                       ScoreFormat format,
                                       const nlohmann::ordered_json& header = {});

}  // namespace pc::evaluation
