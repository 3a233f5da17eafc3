// pc_recursive_split: split over-merged clusters by k-means (k = 2) until none violates the rule.
#include <optional>

#include <pc/cli/tool.h>
#include <pc/pipeline/steps.h>

#include "split_options.h"
#include "write_step.h"

namespace pl = pc::pipeline;
namespace seg = pc::segmentation;

int main(int argc, char** argv) {
    seg::RecursiveSplitParams p;
    std::optional<pc::filters::WoodPartsParams> wood;
    bool no_wood = false;
    pc::cli::Tool tool("pc_recursive_split",
                       "split clusters in `label` whose size and AABB volume exceed median-based "
                       "thresholds; relabel 1..N");
    pc::tools::bind_split_options(tool, p, "");
    tool.presets(pl::preset_names(), [&](const std::string& name) {
        p = *pl::preset(name).split;
        wood = pl::preset(name).wood;
    });
    tool.flag("no-wood", &no_wood,
              "keep the parts coloured like the wood (the dense preset drops them after the "
              "spheres split, as pc_fruitcount does)");
    tool.epilog(
        "\nThresholds are fixed from the input clusters. See docs/tools/pc_recursive_split.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pl::Step split = pl::apply_recursive_split(io.read(), p);
        if (!no_wood && pl::drops_wood(p, wood)) {
            io.note(split.note);
            pl::Step dropped = pl::apply_wood_parts(std::move(split.blob), *wood);
            dropped.warnings.insert(dropped.warnings.begin(), split.warnings.begin(),
                                    split.warnings.end());
            split = std::move(dropped);
        }
        pc::tools::write_step(io, split);
    });
}
