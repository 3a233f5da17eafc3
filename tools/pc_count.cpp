// pc_count: report the clusters in `label`, one report per input.

#include <pc/cli/report.h>
#include <pc/core/error.h>
#include <pc/pipeline/count_report.h>

#include "count_plot.h"
#include "plots.h"
#include "stem.h"

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    std::vector<std::string> inputs;
    std::uint32_t min_points = 1;
    std::optional<double> gt;
    std::string plot;
    pc::cli::Tool tool("pc_count", "count the clusters in `label` (0 = noise) and report them",
                       pc::cli::Output::kText);
    tool.inputs(&inputs, "labelled clouds, one report each ('-' = stdin, the default)");
    tool.option("min-cluster-size", &min_points,
                "count only clusters with at least this many points");
    tool.option("gt", &gt, "ground-truth count: adds error (count - gt) and recovery (count / gt)");
    tool.option("plot", &plot,
                "also draw the cluster sizes and radii as histograms into this PNG (its numbers "
                "beside it as .csv); {stem} as the input's name for several inputs");
    const pc::cli::Report report(tool, "count");
    tool.presets(pl::preset_names(),
                 [&](const std::string& name) { min_points = pl::preset(name).count_min_points; });
    tool.epilog("\nAn empty cloud counts 0. See docs/tools/pc_count.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pc::tools::check_plot_path(plot);
        pc::tools::check_stem("plot", plot, inputs.size());
        report.each(io, inputs, [&](const std::string& path) {
            const pc::io::Blob labelled = io.read(path);
            const auto summary = pl::summarize(labelled, min_points);
            if (!plot.empty()) {
                pc::tools::write_plot(pc::tools::with_stem(plot, path),
                                      pc::tools::count_panels(summary));
            }
            return pl::count_report(summary, gt, {}, pl::count_warnings(summary, labelled.size()));
        });
    });
}
