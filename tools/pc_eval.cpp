// pc_eval: score a labelled cloud against ground truth (count, recovery, matching, P/R/F1, merges,
// splits).
#include <cmath>

#include <pc/cli/report.h>
#include <pc/core/error.h>
#include <pc/evaluation/instances.h>
#include <pc/evaluation/score_report.h>
#include <pc/evaluation/truth.h>
#include <pc/io/points.h>
#include <pc/pipeline/presets.h>

namespace ev = pc::evaluation;

namespace {

/// The ground truth of `path` (pc_synth --truth), errors prefixed by the path.
ev::Truth read_truth(const std::string& path) {
    const std::string text = pc::cli::read_text_file(path, "ground truth");
    return pc::cli::naming(path, [&] { return ev::parse_truth(text); });
}

}  // namespace

int main(int argc, char** argv) {
    ev::InstanceParams params;
    std::string truth_path, label_field = "label", gt_field = "gt_instance", match = "auto", name;
    std::optional<double> gt;
    bool csv = false, markdown = false;
    pc::cli::Tool tool(
        "pc_eval",
        "score a labelled cloud against ground truth: count, recovery, one-to-one matching, "
        "precision, recall, F1, merged clusters, split fruit",
        pc::cli::Output::kText);
    tool.option("truth", &truth_path,
                "ground truth JSON (pc_synth --truth): fruit count, centres, radii");
    tool.option("label", &label_field, "field with the predicted instances (0 = noise)");
    tool.option("gt-field", &gt_field, "field with the true instance per point (0 = not fruit)");
    tool.option("match", &match,
                "auto (overlap when the cloud has --gt-field, else centroid), overlap, centroid");
    tool.option("min-iou", &params.min_iou,
                "overlap: a prediction matches a fruit when IoU > this (>= 0.5)");
    tool.option("share", &params.share,
                "merge/split: more than this share of a fruit / of a prediction");
    tool.option("radius-factor", &params.radius_factor,
                "centroid: match within this x the fruit radius");
    tool.option("min-cluster-size", &params.min_points,
                "predictions with fewer points count as noise");
    tool.option("gt", &gt,
                "ground-truth count (default: --truth's fruit_count, else the ids present)");
    tool.option("name", &name, "row name in the report (default: the input's name)");
    tool.flag("csv", &csv, "one CSV row with a header instead of JSON");
    tool.flag("markdown", &markdown, "a markdown table row with a header instead of JSON");
    tool.presets(pc::pipeline::preset_names(), [&](const std::string& n) {
        params.min_points = static_cast<std::uint32_t>(pc::pipeline::preset(n).count_min_points);
    });
    tool.epilog("\nDefinitions of every score: docs/tools/pc_eval.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (csv && markdown) {
            throw pc::InvalidArgument("--csv and --markdown exclude each other");
        }
        if (match != "auto" && match != "overlap" && match != "centroid") {
            throw pc::InvalidArgument("--match must be auto, overlap or centroid, got '" + match +
                                      "'");
        }
        if (gt && (!(*gt >= 0) || *gt != std::floor(*gt) || *gt > 1e12)) {
            throw pc::InvalidArgument("--gt must be a whole number >= 0");
        }
        params.validate();
        const pc::io::Blob blob = io.read();
        const std::string input = io.input_name();
        const bool has_gt_field = pc::io::find_field(blob, gt_field) != nullptr;
        const std::string mode = match == "auto" ? (has_gt_field ? "overlap" : "centroid") : match;
        if (mode == "centroid" && truth_path.empty()) {
            if (match == "centroid") {
                throw pc::InvalidArgument("--match centroid needs --truth");
            }
            throw pc::IoError(input + ": no '" + gt_field +
                              "' field (give --truth to match by centroid)");
        }
        const ev::Truth truth = truth_path.empty() ? ev::Truth{} : read_truth(truth_path);
        const auto labels = [&](const std::string& field) {
            return pc::cli::naming(input, [&] {
                return blob.size() ? pc::io::labels(blob, field) : std::vector<std::uint32_t>{};
            });
        };
        const std::vector<std::uint32_t> predicted = labels(label_field);
        std::size_t gt_count = gt ? static_cast<std::size_t>(*gt) : truth.fruit_count;
        ev::InstanceScores s;
        if (mode == "overlap") {
            if (!has_gt_field) {
                throw pc::IoError(input + ": no '" + gt_field + "' field for overlap matching");
            }
            s = ev::score_by_overlap(predicted, labels(gt_field), gt_count, params);
        } else {
            s = ev::score_by_centroid(pc::io::xyz(blob), predicted, truth.fruits, gt_count, params);
        }
        io.write_text(ev::score_report(s, name.empty() ? input : name, input, mode,
                                       csv        ? ev::ScoreFormat::kCsv
                                       : markdown ? ev::ScoreFormat::kMarkdown
                                                  : ev::ScoreFormat::kJson,
                                       pc::cli::report_header(io)));
    });
}
