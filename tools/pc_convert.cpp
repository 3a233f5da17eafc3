// pc_convert: any readable cloud (PCD, PLY, XYZ text) to PCD or PLY, every field kept.
#include <pc/cli/tool.h>

int main(int argc, char** argv) {
    pc::cli::Tool tool("pc_convert",
                       "convert PCD / PLY / XYZ text to PCD or PLY, keeping every field");
    tool.epilog(
        "\nThe input format is recognised by content, never by extension. The output is PCD\n"
        "unless --to ply is given or -o names a .ply file. See docs/tools/pc_convert.md.\n");
    return tool.run(argc, argv, [](pc::cli::Streams& io) { io.write(io.read()); });
}
