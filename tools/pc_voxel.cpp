// pc_voxel: voxel-grid downsampling, one point per occupied voxel.
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/steps.h>

#include "write_step.h"

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    pc::filters::VoxelParams p;
    pc::cli::Tool tool("pc_voxel",
                       "one point per occupied voxel: centroid, mean colour, majority labels");
    tool.option("leaf", &p.leaf, "voxel side, cloud units (> 0)");
    tool.presets(pl::preset_names(), [&](const std::string& name) {
        p = pl::preset_step(name, &pl::ChainParams::voxel, "voxel");
    });
    tool.epilog(
        "\nGrid origin half a leaf below the minimum, as Open3D's voxel_down_sample.\n"
        "See docs/tools/pc_voxel.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pc::tools::write_step(io, pl::apply_voxel(io.read(), p));
    });
}
