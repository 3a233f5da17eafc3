// pc_plot: draw a plot's numbers (the CSV that --plot writes beside its PNG) into a PNG.
#include <pc/charts/render.h>
#include <pc/cli/tool.h>
#include <pc/core/error.h>

int main(int argc, char** argv) {
    std::vector<std::string> inputs;
    pc::cli::Tool tool("pc_plot",
                       "draw a plot's CSV (panel,kind,xlabel,name,value: what --plot writes "
                       "beside its PNG) into a PNG: histograms, box plots, bars side by side",
                       pc::cli::Output::kImage);
    tool.no_input();
    tool.inputs(&inputs, "DATA.csv", 1);
    tool.epilog(
        "\nEdit the CSV (titles, names, values) and draw it again. See docs/tools/pc_plot.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (inputs.size() != 1) {
            throw pc::InvalidArgument("expected one DATA.csv, got " +
                                      std::to_string(inputs.size()));
        }
        const std::string text = pc::cli::read_text_file(inputs[0], "plot's numbers");
        const auto panels =
            pc::cli::naming(inputs[0], [&] { return pc::charts::parse_panels(text); });
        const std::vector<std::uint8_t> png = pc::charts::render_png(panels);
        io.write_text(std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    });
}
