#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <pc/features/extent.h>

namespace pc::features {

/// One measured cloud of a report: its name and input, the whole cloud's extent and, when
/// measured per label, each cluster's.
struct ExtentRow {
    std::string name, input;
    Extent whole;
    std::vector<LabelledExtent> clusters;
    std::string error;  ///< the input could not be measured (unreadable, no label): this instead
};

/// What makes a row doubtful: no point to measure, or no 3D hull (hull volume 0).
[[nodiscard]] std::vector<std::string> extent_warnings(const ExtentRow& row);

enum class ExtentFormat { kJson, kJsonLines, kCsv, kMarkdown };

/// The report of pc_extent (docs/tools/pc_extent.md): JSON `header` (tool, version, parameters)
/// and "clouds": [...] with every field of the extent (null for what cannot be computed), its
/// `warnings` and, with `per_label`, the clusters and their summary (median, quartiles); JSON
/// Lines with a line per cloud (the header's keys, then the cloud's); CSV with
/// a row for each cloud ("all") and each cluster; or a markdown table in the paper's Table 3
/// layout (per label: cluster count and medians). A row with an error says only that.
[[nodiscard]] std::string extent_report(const std::vector<ExtentRow>& rows,
                                        ExtentFormat format,
                                        bool per_label,
                                        const nlohmann::ordered_json& header = {});

}  // namespace pc::features
