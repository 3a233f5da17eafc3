#pragma once
// What a plot shows (`--plot FILE.png`): panels of histograms, box plots or bars, and their CSV,
// which goes beside the PNG and which pc_plot draws. No drawing library here: the report tools
// write the CSV and leave the drawing to pc_plot (OpenCV costs 50 MB of resident libraries).

#include <string>
#include <vector>

namespace pc::charts {

/// One panel of a plot.
struct Panel {
    enum class Kind {
        kHistogram,  ///< values[0]: the distribution (bins: sqrt(n), 5 to 40), its median marked
        kBox,        ///< a box per name: values[k] (quartiles, whiskers at 1.5 IQR, outliers)
        kBars,       ///< a bar per name: values[0][k]
    };
    Kind kind = Kind::kHistogram;
    std::string title;   ///< above the panel
    std::string xlabel;  ///< under the axis (histograms)
    std::vector<std::string> names;
    std::vector<std::vector<double>> values;
};

/// The panels as CSV, a row a value: `panel,kind,xlabel,name,value` (kind histogram, box or
/// bars; a non-finite value as an empty cell).
[[nodiscard]] std::string panels_csv(const std::vector<Panel>& panels);

/// The panels of panels_csv's text (rows of one panel together, in order). Throws pc::IoError
/// naming the line for anything else.
[[nodiscard]] std::vector<Panel> parse_panels(const std::string& csv);

/// `png_path` with its extension replaced by `.csv` (where a plot's numbers go).
[[nodiscard]] std::string csv_path(const std::string& png_path);

}  // namespace pc::charts
