// pc_crop: keep the points inside an axis-aligned box (paper 2.3.2: isolate the canopy volume).
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/steps.h>

#include "write_step.h"

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    pc::filters::CropParams p;
    pc::cli::Tool tool("pc_crop", "keep points with min <= p <= max on every axis (ends included)");
    tool.option("min", &p.min, "lower corner x,y,z (included)");
    tool.option("max", &p.max, "upper corner x,y,z (included)");
    tool.flag("invert", &p.invert, "keep the points outside the box instead");
    tool.presets(pl::preset_names(), [&](const std::string& name) {
        p = pl::preset_step(name, &pl::ChainParams::crop, "crop");
    });
    tool.epilog("\nNon-finite points are outside the box. See docs/tools/pc_crop.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pc::tools::write_step(io, pl::apply_crop(io.read(), p));
    });
}
