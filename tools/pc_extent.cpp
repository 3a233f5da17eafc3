// pc_extent: points, bounding box, convex hull volume and area, mean radius (paper Table 3), for
// whole clouds side by side and, with --per-label, for each cluster.
#include <cmath>
#include <filesystem>
#include <sstream>

#include <pc/cli/report.h>
#include <pc/core/error.h>
#include <pc/features/extent.h>
#include <pc/features/extent_report.h>
#include <pc/io/points.h>

#include "plots.h"

int main(int argc, char** argv) {
    std::vector<std::string> inputs;
    std::string names_text, plot;
    bool per_label = false, csv = false, markdown = false, jsonl = false;
    pc::cli::Tool tool("pc_extent",
                       "points, bounding box, convex hull volume/area and mean radius of clouds "
                       "(paper Table 3), side by side; --per-label for each cluster",
                       pc::cli::Output::kText);
    tool.inputs(&inputs, "clouds to measure, side by side ('-' = stdin)");
    tool.option("names", &names_text, "comma-separated names for the inputs (default: file names)");
    tool.flag("per-label", &per_label, "also measure each cluster of `label` (0 = noise skipped)");
    tool.option("plot", &plot,
                "also draw points, hull volume and mean radius of the clouds side by side as bars "
                "into this PNG (its numbers beside it as .csv)");
    tool.flag("csv", &csv, "CSV rows instead of JSON");
    tool.flag("jsonl", &jsonl,
              "JSON Lines: a line per cloud, with the tool, version and parameters");
    tool.flag("markdown", &markdown, "a markdown table instead of JSON");
    tool.epilog("\nDefinitions (centroid, hull, radius) in docs/tools/pc_extent.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (csv + markdown + jsonl > 1) {
            throw pc::InvalidArgument("--csv, --markdown and --jsonl exclude each other");
        }
        pc::tools::check_plot_path(plot);
        std::vector<std::string> names;
        std::stringstream ss(names_text);
        for (std::string n; std::getline(ss, n, ',');) {
            names.push_back(n);
        }
        if (!names_text.empty() && names.size() != inputs.size()) {
            throw pc::InvalidArgument("--names gives " + std::to_string(names.size()) +
                                      " names for " + std::to_string(inputs.size()) + " inputs");
        }
        std::vector<pc::features::ExtentRow> rows;
        std::size_t failed = 0;
        for (std::size_t k = 0; k < inputs.size(); ++k) {
            pc::features::ExtentRow r;
            r.input = pc::io::display_name(inputs[k]);
            r.name = names.empty()
                         ? (inputs[k] == "-" ? r.input
                                             : std::filesystem::path(inputs[k]).stem().string())
                         : names[k];
            try {  // a failing input gets an error row; the others go on (exit 1 at the end)
                const pc::io::Blob blob = io.read(inputs[k]);
                const pc::io::XyzPoints points(blob);
                const pc::XyzView& cloud = points.view();
                r.whole = pc::features::extent(cloud);
                if (per_label) {
                    r.clusters = pc::cli::naming(r.input, [&] {
                        return pc::features::extent_per_label(
                            cloud, blob.size() ? pc::io::labels(blob, "label")
                                               : std::vector<std::uint32_t>{});
                    });
                }
                for (const auto& w : pc::features::extent_warnings(r)) {
                    io.warn(r.input + ": " + w);
                }
            } catch (const pc::InvalidArgument&) {
                throw;
            } catch (const std::exception& e) {
                r.error = e.what();
                io.fail(r.error);
                ++failed;
            }
            rows.push_back(std::move(r));
        }
        if (failed == rows.size()) {
            return;  // nothing measured: only the error lines
        }
        if (!plot.empty()) {
            using Kind = pc::charts::Panel::Kind;
            pc::charts::Panel n{Kind::kBars, "points", "", {}, {{}}},
                volume{Kind::kBars, "convex hull volume", "", {}, {{}}},
                radius{Kind::kBars, "mean radius", "", {}, {{}}};
            for (const auto& r : rows) {
                const bool ok = r.error.empty();
                for (auto* panel : {&n, &volume, &radius}) {
                    panel->names.push_back(r.name);
                }
                n.values[0].push_back(ok ? static_cast<double>(r.whole.points) : NAN);
                volume.values[0].push_back(ok ? r.whole.hull_volume : NAN);
                radius.values[0].push_back(ok ? r.whole.mean_radius : NAN);
            }
            pc::tools::write_plot(plot, {n, volume, radius});
        }
        io.write_text(pc::features::extent_report(rows,
                                                  csv        ? pc::features::ExtentFormat::kCsv
                                                  : markdown ? pc::features::ExtentFormat::kMarkdown
                                                  : jsonl ? pc::features::ExtentFormat::kJsonLines
                                                          : pc::features::ExtentFormat::kJson,
                                                  per_label, pc::cli::report_header(io)));
    });
}
