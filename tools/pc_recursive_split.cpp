// pc_recursive_split: split over-merged clusters by k-means (k = 2) until none violates the rule.
#include <pc/cli/tool.h>
#include <pc/pipeline/steps.h>

#include "split_options.h"
#include "write_step.h"

namespace pl = pc::pipeline;
namespace seg = pc::segmentation;

int main(int argc, char** argv) {
    seg::RecursiveSplitParams p;
    pc::cli::Tool tool("pc_recursive_split",
                       "split clusters in `label` whose size and AABB volume exceed median-based "
                       "thresholds; relabel 1..N");
    pc::tools::bind_split_options(tool, p, "");
    tool.presets(pl::preset_names(), [&](const std::string& name) { p = *pl::preset(name).split; });
    tool.epilog(
        "\nThresholds are fixed from the input clusters. See docs/tools/pc_recursive_split.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pc::tools::write_step(io, pl::apply_recursive_split(io.read(), p));
    });
}
