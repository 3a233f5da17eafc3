// pc_maskeval: per-view scores of predicted masks or renders against ground truth (paper Fig. 4:
// IoU and Dice of masks, PSNR of images), and paired tests between two methods.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <pc/cli/report.h>
#include <pc/core/error.h>
#include <pc/core/stats.h>
#include <pc/evaluation/mask_scores.h>
#include <pc/evaluation/paired_tests.h>

#include "images.h"
#include "plots.h"

namespace ev = pc::evaluation;
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

/// Image files of a folder by stem (name without extension); pc::IoError for a missing folder or
/// two files of one stem.
std::map<std::string, std::string> images_in(const std::string& dir) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        throw pc::IoError(dir + ": not a folder of masks or images");
    }
    std::map<std::string, std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) {
        const std::string ext = pc::tools::lower_extension(e.path());
        if (!e.is_regular_file() || (ext != ".png" && ext != ".jpg" && ext != ".jpeg" &&
                                     ext != ".bmp" && ext != ".tif" && ext != ".tiff")) {
            continue;
        }
        const auto [it, fresh] = out.emplace(e.path().stem().string(), e.path().string());
        if (!fresh) {
            throw pc::IoError(dir + ": two images named " + e.path().stem().string() + " (" +
                              it->second + ", " + e.path().string() + ")");
        }
    }
    return out;
}

enum class Kind { kBinary, kInstance, kImage };

/// auto: colour ground truth -> images; a grey JPEG -> binary (compression blurs 0/255 into many
/// levels); 16-bit or more than two grey levels -> instance ids; else binary masks.
Kind kind_of(const cv::Mat& truth, const std::string& path) {
    if (truth.channels() >= 3) {
        return Kind::kImage;
    }
    if (pc::tools::is_jpeg(path)) {
        return Kind::kBinary;
    }
    if (truth.depth() == CV_16U) {
        return Kind::kInstance;
    }
    std::set<int> levels;
    for (int y = 0; y < truth.rows && levels.size() <= 2; ++y) {
        for (int x = 0; x < truth.cols && levels.size() <= 2; ++x) {
            levels.insert(truth.ptr<std::uint8_t>(y)[x * truth.channels()]);
        }
    }
    return levels.size() > 2 ? Kind::kInstance : Kind::kBinary;
}

std::vector<std::uint8_t> samples(const cv::Mat& m, const std::string& path) {
    if (m.depth() != CV_8U) {
        throw pc::IoError(path + ": PSNR and SSIM take 8-bit images");
    }
    const cv::Mat c = m.isContinuous() ? m : m.clone();
    return {c.data, c.data + c.total() * c.elemSize()};
}

/// The scores of one view: name -> value.
std::map<std::string, double> score(Kind kind,
                                    const std::string& pred_path,
                                    const std::string& truth_path) {
    const cv::Mat p = pc::tools::read_image(pred_path), t = pc::tools::read_image(truth_path);
    if (p.rows != t.rows || p.cols != t.cols) {
        throw pc::IoError(pred_path + ": " + std::to_string(p.cols) + " x " +
                          std::to_string(p.rows) + ", its ground truth " + truth_path + " " +
                          std::to_string(t.cols) + " x " + std::to_string(t.rows));
    }
    switch (kind) {
        case Kind::kBinary: {
            const ev::BinaryScores s = ev::binary_scores(pc::tools::binary_mask(p, pred_path),
                                                         pc::tools::binary_mask(t, truth_path));
            return {
                {"iou", s.iou}, {"dice", s.dice}, {"precision", s.precision}, {"recall", s.recall}};
        }
        case Kind::kInstance: {
            const ev::InstanceMaskScores s = ev::instance_mask_scores(
                pc::tools::instance_ids(p, pred_path), pc::tools::instance_ids(t, truth_path));
            return {{"precision", s.precision},
                    {"recall", s.recall},
                    {"f1", s.f1},
                    {"mean_iou", s.mean_iou},
                    {"predicted", static_cast<double>(s.predicted)},
                    {"truth", static_cast<double>(s.truth)}};
        }
        case Kind::kImage: {
            if (p.channels() != t.channels()) {
                throw pc::IoError(pred_path + ": " + std::to_string(p.channels()) +
                                  " channels, its ground truth " + std::to_string(t.channels()));
            }
            const auto a = samples(p, pred_path), b = samples(t, truth_path);
            return {{"psnr", ev::psnr(a, b)},
                    {"ssim", ev::ssim(a, b, p.cols, p.rows, p.channels())}};
        }
    }
    return {};
}

struct Method {
    std::string dir;
    std::map<std::string, std::string> files;
    std::vector<std::map<std::string, double>> views;  ///< per common view, in order
};

Json summary(const std::vector<std::map<std::string, double>>& views) {
    Json out = Json::object();
    for (const auto& [metric, unused] : views.front()) {
        std::vector<double> v;
        std::size_t infinite = 0;
        for (const auto& s : views) {
            const double x = s.at(metric);
            std::isfinite(x) ? v.push_back(x) : static_cast<void>(++infinite);
        }
        Json m = {{"n", v.size()}};
        if (!v.empty()) {
            double mean = 0;
            for (double x : v) {
                mean += x;
            }
            mean /= static_cast<double>(v.size());
            double ss = 0;
            for (double x : v) {
                ss += (x - mean) * (x - mean);
            }
            m["mean"] = mean;
            m["median"] = pc::median(v);
            m["std"] = v.size() > 1 ? std::sqrt(ss / static_cast<double>(v.size() - 1)) : 0.0;
            m["min"] = *std::min_element(v.begin(), v.end());
            m["max"] = *std::max_element(v.begin(), v.end());
        }
        if (infinite > 0) {
            m["infinite"] = infinite;  // PSNR of identical images
        }
        out[metric] = m;
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> dirs;
    std::string against, kind_name = "auto";
    std::string plot;
    bool csv = false;
    pc::cli::Tool tool("pc_maskeval",
                       "score predicted masks or renders against ground truth, view by view "
                       "(files matched by name): IoU, Dice, precision, recall (binary masks), "
                       "instance matching at IoU 0.5, PSNR and SSIM (images); mean, median, "
                       "standard deviation; paired t-test and Wilcoxon test against --against",
                       pc::cli::Output::kText);
    tool.no_input();
    tool.inputs(&dirs, "PRED_DIR GT_DIR: folders of images matched by file name (stem)", 2);
    tool.option("against", &against,
                "a second method's folder (PRED_DIR is the first): both scored, and the paired "
                "tests of PRED_DIR − against over the views all three share");
    tool.option("kind", &kind_name,
                "auto (colour ground truth: images; 16-bit or more than two levels: instance "
                "ids; else binary), binary, instance or image");
    tool.flag("csv", &csv, "one CSV row per view instead of JSON");
    tool.option("plot", &plot,
                "also draw each score over the views as box plots, a box per method, into this "
                "PNG (its numbers beside it as .csv)");
    tool.epilog(
        "\nBinary masks: JPEG fruit where > 125, others where not 0 (as pc_lift).\n"
        "See docs/tools/pc_maskeval.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (dirs.size() != 2) {
            throw pc::InvalidArgument("expected two folders PRED_DIR GT_DIR, got " +
                                      std::to_string(dirs.size()));
        }
        pc::tools::check_plot_path(plot);
        if (kind_name != "auto" && kind_name != "binary" && kind_name != "instance" &&
            kind_name != "image") {
            throw pc::InvalidArgument("--kind must be auto, binary, instance or image, got '" +
                                      kind_name + "'");
        }
        const auto truth = images_in(dirs[1]);
        std::vector<Method> methods{{dirs[0], images_in(dirs[0]), {}}};
        if (!against.empty()) {
            methods.push_back({against, images_in(against), {}});
        }
        std::vector<std::string> common, missing;
        for (const auto& [stem, path] : truth) {
            const bool all = std::all_of(methods.begin(), methods.end(),
                                         [&](const Method& m) { return m.files.count(stem) > 0; });
            (all ? common : missing).push_back(stem);
        }
        if (common.empty()) {
            throw pc::IoError(dirs[0] + ": no image matches one of " + dirs[1] + " by name");
        }
        std::vector<std::string> warnings;
        if (!missing.empty()) {
            warnings.push_back(std::to_string(missing.size()) + " of " +
                               std::to_string(truth.size()) +
                               " ground-truth views have no prediction" +
                               (against.empty() ? "" : " in both folders") +
                               " and are left out (first: " + missing.front() + ")");
            io.warn(warnings.back());
        }
        const Kind kind =
            kind_name == "binary"     ? Kind::kBinary
            : kind_name == "instance" ? Kind::kInstance
            : kind_name == "image"
                ? Kind::kImage
                : kind_of(pc::tools::read_image(truth.at(common[0])), truth.at(common[0]));
        const char* kind_word = kind == Kind::kBinary     ? "binary"
                                : kind == Kind::kInstance ? "instance"
                                                          : "image";
        for (Method& m : methods) {
            for (const std::string& stem : common) {
                m.views.push_back(score(kind, m.files.at(stem), truth.at(stem)));
            }
        }
        io.note(std::to_string(common.size()) + " views, " + kind_word);
        if (!plot.empty()) {  // a panel per score, a box per method
            std::vector<pc::charts::Panel> panels;
            for (const auto& [metric, unused] : methods.front().views.front()) {
                pc::charts::Panel panel{pc::charts::Panel::Kind::kBox, metric, "", {}, {}};
                for (const Method& m : methods) {
                    panel.names.push_back(std::filesystem::path(m.dir).filename().string());
                    panel.values.emplace_back();
                    for (const auto& view : m.views) {
                        panel.values.back().push_back(view.at(metric));
                    }
                }
                panels.push_back(std::move(panel));
            }
            pc::tools::write_plot(plot, panels);
        }
        std::ostringstream out;
        if (csv) {
            out << "view";
            for (const Method& m : methods) {
                for (const auto& [metric, v] : m.views.front()) {
                    out << ',' << (&m == &methods.front() ? "" : "against_") << metric;
                }
            }
            out << '\n';
            for (std::size_t k = 0; k < common.size(); ++k) {
                out << common[k];
                for (const Method& m : methods) {
                    for (const auto& [metric, v] : m.views[k]) {
                        out << ',' << pc::format_number(v);
                    }
                }
                out << '\n';
            }
            io.write_text(out.str());
            return;
        }
        const auto method_json = [&](const Method& m) {
            Json per = Json::array();
            for (std::size_t k = 0; k < common.size(); ++k) {
                Json v = {{"view", common[k]}};
                for (const auto& [metric, x] : m.views[k]) {
                    v[metric] = pc::cli::json_number(x);
                }
                per.push_back(v);
            }
            return Json{{"pred", m.dir}, {"summary", summary(m.views)}, {"views", per}};
        };
        Json j = pc::cli::report_header(io);
        j.update(Json{{"pred", dirs[0]},
                      {"gt", dirs[1]},
                      {"kind", kind_word},
                      {"views", common.size()},
                      {"missing", missing}});
        j["method"] = method_json(methods[0]);
        if (methods.size() == 2) {
            j["against"] = method_json(methods[1]);
            Json paired = Json::object();
            if (common.size() >= 2) {
                for (const auto& [metric, unused] : methods[0].views.front()) {
                    std::vector<double> a, b;
                    for (std::size_t k = 0; k < common.size(); ++k) {
                        const double x = methods[0].views[k].at(metric),
                                     y = methods[1].views[k].at(metric);
                        if (std::isfinite(x) && std::isfinite(y)) {
                            a.push_back(x);
                            b.push_back(y);
                        }
                    }
                    if (a.size() < 2) {
                        continue;
                    }
                    const ev::PairedTests t = ev::paired_tests(a, b);
                    paired[metric] = {{"n", t.n},
                                      {"mean_difference", t.mean_difference},
                                      {"t", pc::cli::json_number(t.t)},
                                      {"p_t", t.t_p},
                                      {"w", t.w},
                                      {"p_w", t.w_p}};
                }
            } else {
                io.warn("one view only: no paired tests");
            }
            j["paired"] = paired;
        }
        j["warnings"] = warnings;
        io.write_text(j.dump(1) + "\n");
    });
}
