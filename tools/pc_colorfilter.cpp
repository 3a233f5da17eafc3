// pc_colorfilter: keep points by colour (paper 2.3.2: suppress dark background points).
#include <pc/cli/tool.h>
#include <pc/pipeline/steps.h>

#include "write_step.h"

namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    pc::filters::ColorFilterParams p;
    pc::cli::Tool tool("pc_colorfilter", "keep points by colour (rgb/rgba or red green blue)");
    const auto interval = [&](const char* name, std::optional<pc::filters::Interval>* field) {
        return
            [name, field](const std::string& s) { *field = pc::filters::parse_interval(name, s); };
    };
    tool.option("min-mean", &p.min_mean, "keep iff (R+G+B)/3 > this; channels 0..1 (strict >)");
    tool.option("min-value", &p.min_value, "keep iff HSV value max(R,G,B) > this (strict >)");
    tool.option("hue", "off", interval("hue", &p.hue_deg),
                "keep iff hue in LO:HI degrees, ends included; LO > HI wraps (300:30); grey "
                "never matches");
    tool.option("saturation", "off", interval("saturation", &p.saturation),
                "keep iff HSV saturation in LO:HI (0..1), ends included");
    tool.option("value", "off", interval("value", &p.value),
                "keep iff HSV value in LO:HI (0..1), ends included");
    tool.flag("invert", &p.invert, "keep the points the rules reject instead");
    tool.presets(pl::preset_names(), [&](const std::string& name) { p = *pl::preset(name).color; });
    tool.epilog("\nAll rules given must hold. See docs/tools/pc_colorfilter.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pc::tools::write_step(io, pl::apply_color_filter(io.read(), p));
    });
}
