// pc_dbscan: DBSCAN clustering into the `label` field (paper 2.3.3).
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/steps.h>

#include "write_step.h"

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    pc::segmentation::DbscanParams p;
    pl::EpsRule eps;
    pc::cli::Tool tool("pc_dbscan",
                       "add field label: DBSCAN cluster 1..N (largest first), 0 = noise");
    tool.option(
        "eps", pc::format_number(p.eps), [&](const std::string& s) { pl::parse_eps(s, p, eps); },
        "neighbour iff distance <= eps (scikit-learn), cloud units; 'auto' = 4 x the median point "
        "spacing; 'Nxs' = N x it ('spacing': 3.5); 'knee' = knee of the k-distance curve "
        "(printed with -v)");
    tool.option("min-points", &p.min_points, "neighbours a core point needs, itself INCLUDED");
    tool.presets(pl::preset_names(), [&](const std::string& name) {
        p = pl::preset(name).dbscan;
        eps = pl::preset(name).eps;
    });
    tool.epilog(
        "\nBorder points join their nearest core point's cluster. Non-finite points are "
        "noise.\nSee docs/tools/pc_dbscan.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pc::tools::write_step(io, pl::apply_dbscan(io.read(), p, eps));
    });
}
