// pc_range: keep the points whose fields lie in ranges, in PDAL's filters.range syntax
// (`pc_range --limits "opacity[0.1:]" "label![0:0]"`).
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/steps.h>

#include "write_step.h"

int main(int argc, char** argv) {
    pc::filters::RangeFilterParams p;
    std::string given;
    pc::cli::Tool tool("pc_range",
                       "keep points whose fields lie in ranges: FIELD[LO:HI] (PDAL's "
                       "filters.range syntax); ranges on one field are ORed, on different "
                       "fields ANDed");
    tool.option(
        "limits", "",
        [&](const std::string& s) {
            for (auto& r : pc::filters::parse_ranges(s)) {
                p.ranges.push_back(std::move(r));
            }
        },
        "ranges, comma-separated, the option repeatable: z[0:], opacity(0.5:], label![0:0] "
        "('[' ']' include the bound, '(' ')' exclude it, an empty bound is none, '!' keeps what "
        "lies outside)");
    tool.epilog(
        "\nNon-finite values are outside every range. Any numeric field of one element: 3DGS "
        "opacity and scale_0, intensity, label, gt_instance, views/votes from pc_lift. See "
        "docs/tools/pc_range.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (p.ranges.empty()) {
            throw pc::InvalidArgument("--limits: give at least one range, e.g. opacity[0.1:]");
        }
        pc::io::Blob in = io.read();
        const pc::pipeline::Step step = pc::cli::naming(
            io.input_name(), [&] { return pc::pipeline::apply_range(std::move(in), p); });
        pc::tools::write_step(io, step);
    });
}
