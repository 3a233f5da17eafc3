// pc_groupby: one cloud per value of an integer field (a file per cluster, as PDAL's
// filters.groupby with a `#` in the writer's name), and a CSV index of the files.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/io/blob.h>
#include <pc/io/points.h>

namespace {

/// Coordinates as the cloud holds them: the shortest text of the float.
std::string coordinate(double v) {
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<float>(v));
    return std::string(buf, r.ptr);
}

}  // namespace

int main(int argc, char** argv) {
    std::string field = "label", pattern = "cluster_#.pcd";
    bool keep_zero = false;
    std::uint32_t min_points = 1;
    pc::cli::Tool tool("pc_groupby",
                       "write one cloud per value of an integer field (each cluster of `label` "
                       "to its own file) and a CSV index of the files",
                       pc::cli::Output::kText);
    tool.option("field", &field, "the integer field to group by");
    tool.option("pattern", &pattern,
                "file name of each group; '#' becomes the value (.pcd, .ply or .xyz; folders "
                "are made)");
    tool.flag("keep-zero", &keep_zero, "also write the points of value 0 (noise, not fruit)");
    tool.option("min-points", &min_points, "write only groups with at least this many points");
    tool.epilog(
        "\nThe index (stdout or -o) has a row per file: value, points, file, centroid x y z, "
        "box min and max. Every field passes through. See docs/tools/pc_groupby.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (pattern.find('#') == std::string::npos) {
            throw pc::InvalidArgument("--pattern must contain '#', the place of the value, got '" +
                                      pattern + "'");
        }
        (void)pc::cli::container_for(pattern);  // a .las name refused before any work
        const pc::io::Blob blob = io.read();
        const std::vector<std::uint32_t> values = pc::cli::naming(io.input_name(), [&] {
            return blob.size() ? pc::io::labels(blob, field) : std::vector<std::uint32_t>{};
        });
        std::map<std::uint32_t, std::vector<std::uint32_t>> groups;
        for (std::size_t i = 0; i < values.size(); ++i) {
            if (values[i] != 0 || keep_zero) {
                groups[values[i]].push_back(static_cast<std::uint32_t>(i));
            }
        }
        const pc::io::XyzPoints points(blob);
        std::ostringstream index;
        index << field
              << ",points,file,centroid_x,centroid_y,centroid_z,min_x,min_y,min_z,max_x,max_y,"
                 "max_z\n";
        std::size_t written = 0;
        for (const auto& [value, idx] : groups) {
            if (idx.size() < min_points) {
                continue;
            }
            std::string path = pattern;
            for (std::size_t at; (at = path.find('#')) != std::string::npos;) {
                path.replace(at, 1, std::to_string(value));
            }
            const std::filesystem::path parent = std::filesystem::path(path).parent_path();
            if (!parent.empty()) {
                std::filesystem::create_directories(parent);
            }
            pc::cli::write_cloud_file(path, pc::io::copy_points(blob, idx));
            std::array<double, 3> sum{}, lo, hi;
            lo.fill(std::numeric_limits<double>::infinity());
            hi.fill(-std::numeric_limits<double>::infinity());
            std::size_t finite = 0;
            for (const std::uint32_t i : idx) {
                const pcl::PointXYZ p = points.view()[i];
                if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))) {
                    continue;
                }
                ++finite;
                for (int a = 0; a < 3; ++a) {
                    sum[a] += p.data[a];
                    lo[a] = std::min<double>(lo[a], p.data[a]);
                    hi[a] = std::max<double>(hi[a], p.data[a]);
                }
            }
            index << value << ',' << idx.size() << ',' << path;
            for (int a = 0; a < 3; ++a) {
                index << ',' << (finite ? coordinate(sum[a] / static_cast<double>(finite)) : "");
            }
            for (const auto* corner : {&lo, &hi}) {
                for (int a = 0; a < 3; ++a) {
                    index << ',' << (finite ? coordinate((*corner)[a]) : "");
                }
            }
            index << '\n';
            ++written;
        }
        io.note("wrote " + std::to_string(written) + " files");
        if (written == 0 && blob.size() > 0) {
            io.warn("no group written: every point has " + field + " 0" +
                    (keep_zero ? "" : " (give --keep-zero to write them)") +
                    " or the groups are under --min-points");
        }
        io.write_text(index.str());
    });
}
