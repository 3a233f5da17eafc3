// pc_crop: keep the points inside an axis-aligned box (paper 2.3.2: isolate the canopy volume).
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/steps.h>

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    pc::filters::CropParams p;
    pc::cli::Tool tool("pc_crop", "keep points with min <= p <= max on every axis (ends included)");
    tool.option("min", &p.min, "lower corner x,y,z (included)");
    tool.option("max", &p.max, "upper corner x,y,z (included)");
    tool.flag("invert", &p.invert, "keep the points outside the box instead");
    tool.presets(pl::preset_names(), [&](const std::string& name) {
        const auto c = pl::preset(name).crop;
        if (!c) {
            throw pc::InvalidArgument("--preset: " + name + " has no crop step");
        }
        p = *c;
    });
    tool.epilog("\nNon-finite points are outside the box. See docs/tools/pc_crop.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pl::Step s = pl::apply_crop(io.read(), p);
        io.note(s.note);
        for (const auto& w : s.warnings) {
            io.warn(w);
        }
        io.write(s.blob);
    });
}
