// pc_info: a report on each cloud, like `pdal info`: size, encoding, fields, bounds, statistics;
// with --stats also percentiles, colour and spacing.
#include <cmath>

#include <pc/cli/report.h>
#include <pc/core/error.h>
#include <pc/filters/color_stats.h>
#include <pc/io/info.h>
#include <pc/io/points.h>
#include <pc/search/spacing.h>

namespace {

using nlohmann::ordered_json;

using pc::cli::json_number;

/// Rounded to float: the channels come from 8-bit or float colours.
ordered_json spread(const pc::filters::Spread& s) {
    const auto f = [](double v) { return json_number(static_cast<float>(v)); };
    return {{"p10", f(s.p10)}, {"median", f(s.median)}, {"p90", f(s.p90)}};
}

ordered_json color_json(const pc::filters::ColorStats& c) {
    ordered_json hues = ordered_json::object();
    for (std::size_t b = 0; b < c.hue_histogram.size(); ++b) {
        hues[pc::filters::kHueNames[b]] = c.hue_histogram[b];
    }
    return {{"red", spread(c.red)},     {"green", spread(c.green)},
            {"blue", spread(c.blue)},   {"saturation", spread(c.saturation)},
            {"value", spread(c.value)}, {"grey", c.grey},
            {"hue_histogram", hues}};
}

ordered_json to_json(const pc::io::CloudInfo& info, const std::string& fmt) {
    ordered_json j;
    j["format"] = fmt;
    j["points"] = info.points;
    j["width"] = info.width;
    j["height"] = info.height;
    j["organised"] = info.organised;
    j["is_dense"] = info.is_dense;
    j["non_finite_points"] = info.non_finite_points;
    std::string names;  // as io::field_names, from the description
    for (const auto& f : info.fields) {
        names += (names.empty() ? "" : " ") + f.name;
    }
    j["field_names"] = names;
    j["colour"] = {{"present", !info.colour.empty()}, {"fields", info.colour}};
    if (info.has_xyz && info.non_finite_points < info.points) {
        ordered_json lo = ordered_json::array(), hi = ordered_json::array();
        for (int a = 0; a < 3; ++a) {
            lo.push_back(info.bbox_min[a]);
            hi.push_back(info.bbox_max[a]);
        }
        j["bbox"] = {{"min", lo}, {"max", hi}};
    } else {
        j["bbox"] = nullptr;
    }
    ordered_json fields = ordered_json::array();
    for (const auto& f : info.fields) {
        ordered_json jf{{"name", f.name},
                        {"type", std::string(1, f.type)},
                        {"size", f.size},
                        {"count", f.count}};
        if (f.packed_colour) {
            jf["packed_colour"] = true;
        }
        if (!f.stats.empty()) {
            // One value per statistic, or one list of them for fields of several elements.
            const bool one = f.stats.size() == 1;
            const auto add = [&](const char* key, double pc::io::ElementStats::*member) {
                ordered_json v = ordered_json::array();
                for (const auto& s : f.stats) {
                    v.push_back(json_number(s.*member));
                }
                jf[key] = one ? v[0] : v;
            };
            add("min", &pc::io::ElementStats::min);
            add("max", &pc::io::ElementStats::max);
            add("mean", &pc::io::ElementStats::mean);
            add("stddev", &pc::io::ElementStats::stddev);
            if (std::isfinite(f.stats[0].median) || f.stats[0].finite == 0) {
                add("p10", &pc::io::ElementStats::p10);
                add("median", &pc::io::ElementStats::median);
                add("p90", &pc::io::ElementStats::p90);
            }
        }
        fields.push_back(jf);
    }
    j["fields"] = fields;
    j["viewpoint"] = info.viewpoint;
    return j;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> inputs;
    bool stats = false;
    pc::cli::Tool tool("pc_info",
                       "report size, encoding, fields, bounds and statistics of clouds, one report "
                       "each",
                       pc::cli::Output::kText);
    tool.inputs(&inputs, "clouds to describe ('-' = stdin, the default)");
    tool.flag("stats", &stats,
              "also percentiles (P10, median, P90) of every field, colour statistics (channels, "
              "saturation, value, a hue histogram) and point spacing (nearest-neighbour "
              "distances, duplicate points)");
    const pc::cli::Report report(tool);
    tool.epilog("\nSee docs/tools/pc_info.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        report.each(io, inputs, [&](const std::string& path) {
            const pc::io::Blob blob = io.read(path);
            const pc::io::CloudInfo info = pc::io::describe(blob, stats);
            ordered_json j = to_json(info, io.input_format());
            if (stats) {
                if (!j["colour"]["fields"].get<std::string>().empty()) {
                    j["colour"]["stats"] =
                        color_json(pc::filters::color_stats(pc::io::colours(blob)));
                }
                if (info.has_xyz) {
                    const pc::io::XyzPoints points(blob);
                    const auto sp = pc::search::spacing_stats(points.view());
                    j["spacing"] = {{"p10", sp.p10},
                                    {"median", sp.median},
                                    {"p90", sp.p90},
                                    {"sampled", sp.sampled},
                                    {"duplicates", sp.duplicates}};
                }
            }
            return j;
        });
    });
}
