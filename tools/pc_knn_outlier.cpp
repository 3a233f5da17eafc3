// pc_knn_outlier: drop points whose mean distance to their k nearest neighbours is large.
#include <pc/cli/tool.h>
#include <pc/pipeline/steps.h>

#include "write_step.h"

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    pc::filters::KnnOutlierParams p;
    pl::KnnOutput out;
    pc::cli::Tool tool("pc_knn_outlier",
                       "drop points whose mean distance to their k nearest neighbours is large");
    tool.option("k", &p.k, "neighbours averaged, the point itself NOT counted");
    tool.option("drop-percentile", &p.drop_percentile,
                "drop points with mean distance >= the (100 - P)th percentile (numpy linear); "
                "0 drops nothing");
    tool.option("std-mul", &p.std_mul,
                "instead: drop points with mean distance > mean + M * sample sigma");
    tool.option("mark", &out.mark_field, "write 0/1 (1 = outlier) to this U 4 field, drop nothing");
    tool.flag("invert", &out.invert, "keep only the outliers");
    tool.presets(pl::preset_names(), [&](const std::string& name) {
        p = pl::preset_step(name, &pl::ChainParams::knn, "kNN outlier");
    });
    tool.epilog("\nNon-finite points are outliers. See docs/tools/pc_knn_outlier.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pc::tools::write_step(io, pl::apply_knn_outlier(io.read(), p, out));
    });
}
