#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include <pc/core/error.h>
#include <pc/core/stats.h>
#include <pc/features/extent_report.h>

namespace pc::features {

namespace {

using nlohmann::ordered_json;

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
    const double q1 = percentile(a, 25), med = percentile(b, 50), q3 = percentile(c, 75);
    if (v.empty()) {
        return nullptr;
    }
    return {{"median", med}, {"q1", q1}, {"q3", q3}, {"iqr", q3 - q1}};
}

ordered_json summary_json(const std::vector<LabelledExtent>& clusters) {
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
        o << ',' << (e.points ? format_number(v) : "");
    }
    o << ',' << (e.degenerate ? "true" : "false") << '\n';
    return o.str();
}

}  // namespace

std::vector<std::string> extent_warnings(const ExtentRow& row) {
    if (!row.error.empty()) {
        return {};
    }
    if (row.whole.points == 0) {
        return {"no finite point to measure"};
    }
    if (row.whole.degenerate) {
        return {"no 3D hull (" + std::to_string(row.whole.points) +
                " points, fewer than 4 or all in one plane): hull volume and area are 0"};
    }
    return {};
}

std::string extent_report(const std::vector<ExtentRow>& rows,
                          ExtentFormat format,
                          bool per_label,
                          const nlohmann::ordered_json& header) {
    std::ostringstream out;
    if (format == ExtentFormat::kCsv) {
        out << "name,label,points,centroid_x,centroid_y,centroid_z,min_x,min_y,min_z,max_x,max_"
               "y,"
               "max_z,aabb_volume,hull_volume,hull_area,mean_radius,max_radius,"
               "equivalent_diameter,degenerate\n";
        for (const auto& r : rows) {
            if (!r.error.empty()) {
                out << r.name << ",error" << std::string(17, ',') << '\n';
                continue;
            }
            out << csv_line(r.name, "all", r.whole);
            for (const auto& c : r.clusters) {
                out << csv_line(r.name, std::to_string(c.label), c.extent);
            }
        }
    } else if (format == ExtentFormat::kMarkdown) {
        out << "| Model | Points | Convex hull volume | Mean radius | Max radius | AABB volume "
               "|"
            << (per_label ? " Clusters | Median cluster hull volume | Median cluster mean radius |"
                          : "")
            << "\n| --- | ---: | ---: | ---: | ---: | ---: |"
            << (per_label ? " ---: | ---: | ---: |" : "") << '\n';
        for (const auto& r : rows) {
            if (!r.error.empty()) {
                out << "| " << r.name << " | error: see stderr |";
                for (int c = 0; c < (per_label ? 7 : 4); ++c) {
                    out << "  |";
                }
                out << '\n';
                continue;
            }
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
                out << ' ' << r.clusters.size() << " | " << g6(median(vol)) << " | "
                    << g6(median(rad)) << " |";
            }
            out << '\n';
        }
    } else {
        ordered_json clouds = ordered_json::array();
        for (const auto& r : rows) {
            ordered_json j;
            j["name"] = r.name;
            j["input"] = r.input;
            if (!r.error.empty()) {
                j["error"] = r.error;
                clouds.push_back(j);
                continue;
            }
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
            j["warnings"] = extent_warnings(r);
            clouds.push_back(j);
        }
        ordered_json report = header.is_object() ? header : ordered_json::object();
        if (format == ExtentFormat::kJsonLines) {
            for (const auto& cloud : clouds) {
                ordered_json line = report;
                line.update(cloud);
                out << line.dump() << '\n';
            }
        } else {
            report["clouds"] = clouds;
            out << report.dump(1) << '\n';
        }
    }
    return out.str();
}

}  // namespace pc::features
