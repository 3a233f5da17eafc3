#include <cmath>
#include <cstdio>
#include <sstream>

#include <nlohmann/json.hpp>

#include <pc/core/error.h>
#include <pc/evaluation/score_report.h>

namespace pc::evaluation {

namespace {

using nlohmann::ordered_json;

std::string num(double v) { return std::isfinite(v) ? format_number(v) : ""; }

}  // namespace

std::string score_report(const InstanceScores& s,
                         const std::string& name,
                         const std::string& input,
                         const std::string& mode,
                         ScoreFormat format,
                         const nlohmann::ordered_json& header) {
    std::ostringstream out;
    const std::size_t fp = s.count - s.true_positives, missed = s.gt_count - s.true_positives;
    if (format == ScoreFormat::kCsv) {
        out << "name,match,count,gt_count,recovery,true_positives,false_positives,missed,"
               "precision,recall,f1,"
               "merged,split\n"
            << name << ',' << mode << ',' << s.count << ',' << s.gt_count << ',' << num(s.recovery)
            << ',' << s.true_positives << ',' << fp << ',' << missed << ',' << num(s.precision)
            << ',' << num(s.recall) << ',' << num(s.f1) << ',' << s.merged.size() << ','
            << s.split.size() << '\n';
    } else if (format == ScoreFormat::kMarkdown) {
        char buf[256];
        std::snprintf(buf, sizeof buf,
                      "| %s | %zu | %zu | %.3f | %.3f | %.3f | %.3f | %zu | %zu |\n", name.c_str(),
                      s.count, s.gt_count, s.recovery, s.precision, s.recall, s.f1, s.merged.size(),
                      s.split.size());
        out << "| Cloud | Count | GT | Recovery | Precision | Recall | F1 | Merged | Split |\n"
            << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n"
            << buf;
    } else {
        ordered_json j;
        j["name"] = name;
        j["input"] = input;
        if (header.is_object()) {
            j.update(header);
        }
        j["match"] = mode;
        j["count"] = s.count;
        j["gt_count"] = s.gt_count;
        j["recovery"] =
            std::isfinite(s.recovery) ? ordered_json(s.recovery) : ordered_json(nullptr);
        j["true_positives"] = s.true_positives;
        j["false_positives"] = fp;
        j["missed"] = missed;
        j["precision"] = s.precision;
        j["recall"] = s.recall;
        j["f1"] = s.f1;
        j["merged"] = s.merged.size();
        j["split"] = s.split.size();
        j["merged_labels"] = s.merged;
        j["split_fruit"] = s.split;
        ordered_json m = ordered_json::array();
        for (const auto& x : s.matches) {
            m.push_back(mode == "overlap"
                            ? ordered_json{{"label", x.label},
                                           {"fruit", x.fruit},
                                           {"points", x.overlap},
                                           {"iou", x.iou}}
                            : ordered_json{
                                  {"label", x.label}, {"fruit", x.fruit}, {"distance", x.overlap}});
        }
        j["matches"] = m;
        std::vector<std::string> warnings;
        if (s.count == 0) {
            warnings.emplace_back("no cluster predicted: precision and recall are 0");
        }
        if (s.gt_count == 0) {
            warnings.emplace_back("no ground-truth fruit: recall and recovery are undefined");
        }
        j["warnings"] = warnings;
        out << j.dump(1) << '\n';
    }
    return out.str();
}

}  // namespace pc::evaluation
