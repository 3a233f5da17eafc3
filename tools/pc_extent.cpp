// pc_extent: points, bounding box, convex hull volume and area, mean radius (paper Table 3), for
// whole clouds side by side and, with --per-label, for each cluster.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <nlohmann/json.hpp>

#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/core/stats.h>
#include <pc/features/extent.h>
#include <pc/io/points.h>

namespace {

using nlohmann::ordered_json;
using pc::features::Extent;

struct Row {
    std::string name, input;
    Extent whole;
    std::vector<pc::features::LabelledExtent> clusters;
};

ordered_json extent_json(const Extent& e) {
    const auto num = [](double v) {
        return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr);
    };
    ordered_json j;
    j["points"] = e.points;
    if (e.points == 0) {
        j["degenerate"] = true;
        return j;
    }
    j["centroid"] = e.centroid;
    j["aabb"] = {{"min", e.min},
                 {"max", e.max},
                 {"extent", {e.max[0] - e.min[0], e.max[1] - e.min[1], e.max[2] - e.min[2]}},
                 {"volume", num(e.aabb_volume)}};
    j["hull"] = {{"volume", num(e.hull_volume)}, {"area", num(e.hull_area)}};
    j["mean_radius"] = num(e.mean_radius);
    j["max_radius"] = num(e.max_radius);
    j["equivalent_diameter"] = num(e.equivalent_diameter);
    j["degenerate"] = e.degenerate;
    return j;
}

ordered_json spread(std::vector<double> v) {
    std::vector<double> a = v, b = v, c = v;
    const double q1 = pc::percentile(a, 25), med = pc::percentile(b, 50),
                 q3 = pc::percentile(c, 75);
    if (v.empty()) {
        return nullptr;
    }
    return {{"median", med}, {"q1", q1}, {"q3", q3}, {"iqr", q3 - q1}};
}

ordered_json summary_json(const std::vector<pc::features::LabelledExtent>& clusters) {
    std::vector<double> vol, rad, dia;
    for (const auto& c : clusters) {
        vol.push_back(c.extent.hull_volume);
        rad.push_back(c.extent.mean_radius);
        dia.push_back(c.extent.equivalent_diameter);
    }
    return {{"count", clusters.size()},
            {"hull_volume", spread(vol)},
            {"mean_radius", spread(rad)},
            {"equivalent_diameter", spread(dia)}};
}

std::string g6(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string csv_line(const std::string& name, const std::string& label, const Extent& e) {
    std::ostringstream o;
    o << name << ',' << label << ',' << e.points;
    for (double v : {e.centroid[0], e.centroid[1], e.centroid[2], e.min[0], e.min[1], e.min[2],
                     e.max[0], e.max[1], e.max[2], e.aabb_volume, e.hull_volume, e.hull_area,
                     e.mean_radius, e.max_radius, e.equivalent_diameter}) {
        o << ',' << (e.points ? pc::format_number(v) : "");
    }
    o << ',' << (e.degenerate ? "true" : "false") << '\n';
    return o.str();
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> inputs;
    std::string names_text;
    bool per_label = false, csv = false, markdown = false;
    pc::cli::Tool tool("pc_extent",
                       "points, bounding box, convex hull volume/area and mean radius of clouds "
                       "(paper Table 3), side by side; --per-label for each cluster",
                       pc::cli::Output::kText);
    tool.inputs(&inputs, "clouds to measure, side by side ('-' = stdin)");
    tool.option("names", &names_text, "comma-separated names for the inputs (default: file names)");
    tool.flag("per-label", &per_label, "also measure each cluster of `label` (0 = noise skipped)");
    tool.flag("csv", &csv, "CSV rows instead of JSON");
    tool.flag("markdown", &markdown, "a markdown table instead of JSON");
    tool.epilog("\nDefinitions (centroid, hull, radius) in docs/tools/pc_extent.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (csv && markdown) {
            throw pc::InvalidArgument("--csv and --markdown exclude each other");
        }
        std::vector<std::string> names;
        std::stringstream ss(names_text);
        for (std::string n; std::getline(ss, n, ',');) {
            names.push_back(n);
        }
        if (!names_text.empty() && names.size() != inputs.size()) {
            throw pc::InvalidArgument("--names gives " + std::to_string(names.size()) +
                                      " names for " + std::to_string(inputs.size()) + " inputs");
        }
        std::vector<Row> rows;
        for (std::size_t k = 0; k < inputs.size(); ++k) {
            const pc::io::Blob blob = io.read(inputs[k]);
            const pc::io::XyzPoints points(blob);
            const pc::XyzView& cloud = points.view();
            Row r;
            r.input = pc::io::display_name(inputs[k]);
            r.name = names.empty()
                         ? (inputs[k] == "-" ? r.input
                                             : std::filesystem::path(inputs[k]).stem().string())
                         : names[k];
            r.whole = pc::features::extent(cloud);
            if (per_label) {
                try {
                    r.clusters = pc::features::extent_per_label(
                        cloud,
                        blob.size() ? pc::io::labels(blob, "label") : std::vector<std::uint32_t>{});
                } catch (const pc::IoError& e) {
                    throw pc::IoError(r.input + ": " + e.what());  // name the input, as readers do
                }
            }
            rows.push_back(std::move(r));
        }
        std::ostringstream out;
        if (csv) {
            out << "name,label,points,centroid_x,centroid_y,centroid_z,min_x,min_y,min_z,max_x,max_"
                   "y,"
                   "max_z,aabb_volume,hull_volume,hull_area,mean_radius,max_radius,"
                   "equivalent_diameter,degenerate\n";
            for (const auto& r : rows) {
                out << csv_line(r.name, "all", r.whole);
                for (const auto& c : r.clusters) {
                    out << csv_line(r.name, std::to_string(c.label), c.extent);
                }
            }
        } else if (markdown) {
            out << "| Model | Points | Convex hull volume | Mean radius | Max radius | AABB volume "
                   "|"
                << (per_label
                        ? " Clusters | Median cluster hull volume | Median cluster mean radius |"
                        : "")
                << "\n| --- | ---: | ---: | ---: | ---: | ---: |"
                << (per_label ? " ---: | ---: | ---: |" : "") << '\n';
            for (const auto& r : rows) {
                const Extent& e = r.whole;
                out << "| " << r.name << " | " << e.points << " | " << g6(e.hull_volume) << " | "
                    << g6(e.mean_radius) << " | " << g6(e.max_radius) << " | " << g6(e.aabb_volume)
                    << " |";
                if (per_label) {
                    std::vector<double> vol, rad;
                    for (const auto& c : r.clusters) {
                        vol.push_back(c.extent.hull_volume);
                        rad.push_back(c.extent.mean_radius);
                    }
                    out << ' ' << r.clusters.size() << " | " << g6(pc::median(vol)) << " | "
                        << g6(pc::median(rad)) << " |";
                }
                out << '\n';
            }
        } else {
            ordered_json clouds = ordered_json::array();
            for (const auto& r : rows) {
                ordered_json j;
                j["name"] = r.name;
                j["input"] = r.input;
                j.update(extent_json(r.whole));
                if (per_label) {
                    ordered_json cl = ordered_json::array();
                    for (const auto& c : r.clusters) {
                        ordered_json jc{{"label", c.label}};
                        jc.update(extent_json(c.extent));
                        cl.push_back(jc);
                    }
                    j["cluster_summary"] = summary_json(r.clusters);
                    j["clusters"] = cl;
                }
                clouds.push_back(j);
            }
            out << ordered_json{{"clouds", clouds}}.dump(1) << '\n';
        }
        io.write_text(out.str());
    });
}
