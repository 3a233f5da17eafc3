// pc_colorfilter: keep points by colour (paper 2.3.2: suppress dark background points), by a rule
// or by a fruit-colour word (auto: chosen from the cloud).
#include <pc/cli/tool.h>
#include <pc/pipeline/steps.h>

#include "color_options.h"
#include "write_step.h"

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    pc::tools::ColorOptions color;
    // by default pc_fruitcount's colour step: the rule chosen from the cloud, on neighbourhood
    // colours where they are noisy
    color.from_preset(pl::preset("dense"));
    pc::cli::Tool tool("pc_colorfilter", "keep points by colour (rgb/rgba or red green blue)");
    pc::tools::bind_color_options(tool, color, "");
    tool.presets(pl::preset_names(),
                 [&](const std::string& name) { color.from_preset(pl::preset(name)); });
    tool.epilog(
        "\nWith no option the rule is chosen from the cloud (--fruit-color auto); all rules "
        "given must hold. See docs/tools/pc_colorfilter.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pl::ChainParams chain;
        color.apply(chain);
        pc::tools::write_step(
            io, pl::apply_colour(io.read(), chain, [&](const std::string& n) { io.note(n); }));
    });
}
