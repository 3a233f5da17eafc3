// pc_info: a report on one cloud, like `pdal info`: size, encoding, fields, bounds, statistics.
#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/io/info.h>

namespace {

using nlohmann::ordered_json;

ordered_json number(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); }

ordered_json to_json(const pc::io::CloudInfo& info,
                     const std::string& input,
                     const std::string& fmt) {
    ordered_json j;
    j["input"] = input;
    j["format"] = fmt;
    j["points"] = info.points;
    j["width"] = info.width;
    j["height"] = info.height;
    j["organised"] = info.organised;
    j["is_dense"] = info.is_dense;
    j["non_finite_points"] = info.non_finite_points;
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
            ordered_json mins = ordered_json::array(), maxs = ordered_json::array(),
                         means = ordered_json::array();
            for (const auto& s : f.stats) {
                mins.push_back(number(s.min));
                maxs.push_back(number(s.max));
                means.push_back(number(s.mean));
            }
            const bool one = f.stats.size() == 1;
            jf["min"] = one ? mins[0] : mins;
            jf["max"] = one ? maxs[0] : maxs;
            jf["mean"] = one ? means[0] : means;
        }
        fields.push_back(jf);
    }
    j["fields"] = fields;
    j["viewpoint"] = info.viewpoint;
    return j;
}

std::string to_csv(const pc::io::CloudInfo& info) {
    std::ostringstream out;
    out << "field,type,size,count,element,min,max,mean,finite\n";
    const auto num = [](double v) { return std::isfinite(v) ? pc::format_number(v) : ""; };
    for (const auto& f : info.fields) {
        if (f.stats.empty()) {
            out << f.name << ',' << f.type << ',' << f.size << ',' << f.count << ",,,,,\n";
        }
        for (std::size_t e = 0; e < f.stats.size(); ++e) {
            const auto& s = f.stats[e];
            out << f.name << ',' << f.type << ',' << f.size << ',' << f.count << ',' << e << ','
                << num(s.min) << ',' << num(s.max) << ',' << num(s.mean) << ',' << s.finite << '\n';
        }
    }
    return out.str();
}

std::string to_text(const pc::io::CloudInfo& info, const std::string& fmt) {
    std::ostringstream out;
    out << "format " << fmt << "\npoints " << info.points << "\nwidth " << info.width << "\nheight "
        << info.height << "\nnon_finite_points " << info.non_finite_points << "\ncolour "
        << (info.colour.empty() ? "none" : info.colour) << "\nfields";
    for (const auto& f : info.fields) {
        out << ' ' << f.name;
    }
    out << '\n';
    if (info.has_xyz && info.non_finite_points < info.points) {
        out << "bbox_min " << pc::format_number(info.bbox_min[0]) << ' '
            << pc::format_number(info.bbox_min[1]) << ' ' << pc::format_number(info.bbox_min[2])
            << "\nbbox_max " << pc::format_number(info.bbox_max[0]) << ' '
            << pc::format_number(info.bbox_max[1]) << ' ' << pc::format_number(info.bbox_max[2])
            << '\n';
    }
    return out.str();
}

}  // namespace

int main(int argc, char** argv) {
    bool csv = false, text = false;
    pc::cli::Tool tool("pc_info", "report size, encoding, fields, bounds and statistics of a cloud",
                       pc::cli::Output::kText);
    tool.flag("csv", &csv, "one CSV row per field element instead of JSON");
    tool.flag("text", &text, "'key value' lines instead of JSON");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (csv && text) {
            throw pc::InvalidArgument("--csv and --text exclude each other");
        }
        const pc::io::Blob blob = io.read();
        const pc::io::CloudInfo info = pc::io::describe(blob);
        if (csv) {
            io.write_text(to_csv(info));
        } else if (text) {
            io.write_text(to_text(info, io.input_format()));
        } else {
            io.write_text(to_json(info, io.input_name(), io.input_format()).dump(2) + "\n");
        }
    });
}
