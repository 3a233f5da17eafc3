// pc_count: report the clusters in `label`, one report per input.

#include <pc/cli/report.h>
#include <pc/core/error.h>
#include <pc/pipeline/count_report.h>

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    std::vector<std::string> inputs;
    std::uint32_t min_points = 1;
    std::optional<double> gt;
    pc::cli::Tool tool("pc_count", "count the clusters in `label` (0 = noise) and report them",
                       pc::cli::Output::kText);
    tool.inputs(&inputs, "labelled clouds, one report each ('-' = stdin, the default)");
    tool.option("min-cluster-size", &min_points,
                "count only clusters with at least this many points");
    tool.option("gt", &gt, "ground-truth count: adds error (count - gt) and recovery (count / gt)");
    const pc::cli::Report report(tool, "count");
    tool.presets(pl::preset_names(),
                 [&](const std::string& name) { min_points = pl::preset(name).count_min_points; });
    tool.epilog("\nAn empty cloud counts 0. See docs/tools/pc_count.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        report.each(io, inputs, [&](const std::string& path) {
            const pc::io::Blob labelled = io.read(path);
            const auto summary = pl::summarize(labelled, min_points);
            return pl::count_report(summary, gt, {}, pl::count_warnings(summary, labelled.size()));
        });
    });
}
