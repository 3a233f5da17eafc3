// pc_count: report the clusters in `label`.

#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/steps.h>

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    std::uint32_t min_points = 1;
    std::optional<double> gt;
    bool plain = false;
    pc::cli::Tool tool("pc_count", "count the clusters in `label` (0 = noise) and report them",
                       pc::cli::Output::kText);
    tool.option("min-cluster-size", &min_points,
                "count only clusters with at least this many points");
    tool.option("gt", &gt, "ground-truth count: adds error (count - gt) and recovery (count / gt)");
    tool.flag("plain", &plain, "print only the count");
    tool.presets(pl::preset_names(),
                 [&](const std::string& name) { min_points = pl::preset(name).count_min_points; });
    tool.epilog("\nAn empty cloud counts 0. See docs/tools/pc_count.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        const pc::io::Blob labelled = io.read();
        const auto summary = [&] {
            try {
                return pl::summarize(labelled, min_points);
            } catch (const pc::IoError& e) {
                throw pc::IoError(io.input_name() + ": " + e.what());  // name the input
            }
        }();
        const auto warnings = pl::count_warnings(summary, labelled.size());
        for (const auto& w : warnings) {
            io.warn(w);
        }
        io.write_text(plain ? std::to_string(summary.clusters.size()) + "\n"
                            : pl::count_report(summary, gt, {}, warnings));
    });
}
