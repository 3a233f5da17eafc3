// pc_voxel: voxel-grid downsampling, one point per occupied voxel.
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/steps.h>

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    pc::filters::VoxelParams p;
    pc::cli::Tool tool("pc_voxel",
                       "one point per occupied voxel: centroid, mean colour, majority labels");
    tool.option("leaf", &p.leaf, "voxel side, cloud units (> 0)");
    tool.presets(pl::preset_names(), [&](const std::string& name) {
        const auto v = pl::preset(name).voxel;
        if (!v) {
            throw pc::InvalidArgument("--preset: " + name + " has no voxel step");
        }
        p = *v;
    });
    tool.epilog(
        "\nGrid origin half a leaf below the minimum, as Open3D's voxel_down_sample.\n"
        "See docs/tools/pc_voxel.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pl::Step s = pl::apply_voxel(io.read(), p);
        io.note(s.note);
        for (const auto& w : s.warnings) {
            io.warn(w);
        }
        io.write(s.blob);
    });
}
