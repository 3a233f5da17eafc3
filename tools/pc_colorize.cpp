// pc_colorize: colour the points by label or by any field, as `rgb` that every viewer shows.
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/steps.h>

#include "write_step.h"

int main(int argc, char** argv) {
    pc::filters::ColorizeParams p;
    pc::cli::Tool tool("pc_colorize",
                       "colour the points by label (a distinct colour each, 0 grey) or by any "
                       "field through the viridis map, written as rgb that CloudCompare, MeshLab "
                       "and Open3D show");
    tool.option("by", &p.by, "label, x, y, z or any numeric field (3DGS opacity, views, ...)");
    tool.option(
        "range", "P2:P98",
        [&](const std::string& s) {
            const pc::filters::Interval r = pc::filters::parse_interval("range", s);
            p.range = std::array<double, 2>{r.lo, r.hi};
        },
        "values at the ends of the colour map (default: the field's 2nd and 98th percentiles)");
    tool.epilog(
        "\nThe cloud's colour (rgb, rgba, red green blue) is replaced; every other field passes "
        "through. Write PLY (-o x.ply) for MeshLab and Open3D. See docs/tools/pc_colorize.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        p.validate();
        pc::io::Blob in = io.read();
        const pc::pipeline::Step step = pc::cli::naming(
            io.input_name(), [&] { return pc::pipeline::apply_colorize(std::move(in), p); });
        pc::tools::write_step(io, step);
    });
}
