#pragma once

#include <string>
#include <vector>

#include <pc/features/extent.h>

namespace pc::features {

/// One measured cloud of a report: its name and input, the whole cloud's extent and, when
/// measured per label, each cluster's.
struct ExtentRow {
    std::string name, input;
    Extent whole;
    std::vector<LabelledExtent> clusters;
};

enum class ExtentFormat { kJson, kCsv, kMarkdown };

/// The report of pc_extent (docs/tools/pc_extent.md): JSON {"clouds": [...]} with every field of
/// the extent (null for what cannot be computed) and, with `per_label`, the clusters and their
/// summary (median, quartiles); CSV with a row for each cloud ("all") and each cluster; or a
/// markdown table in the paper's Table 3 layout (per label: cluster count and medians).
[[nodiscard]] std::string extent_report(const std::vector<ExtentRow>& rows,
                                        ExtentFormat format,
                                        bool per_label);

}  // namespace pc::features
