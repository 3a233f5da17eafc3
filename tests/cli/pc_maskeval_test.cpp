// pc_maskeval through the built tool: masks written here with OpenCV, scores computed by hand
// (a square shifted by k pixels: IoU (20 − k) / (20 + k)), JPEG's threshold, instance ids, PSNR of
// images one grey level apart everywhere, paired tests between two methods, and bad folders.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "support/run_tool.h"

namespace pc::test {
namespace {

/// A 64 x 48 mask with a 20 x 20 square of `value` at (10 + shift, 10).
cv::Mat square(int shift, int value = 255, int type = CV_8UC1) {
    cv::Mat m = cv::Mat::zeros(48, 64, type);
    cv::rectangle(m, cv::Rect(10 + shift, 10, 20, 20), cv::Scalar(value), cv::FILLED);
    return m;
}

TEST(PcMaskeval, BinaryScoresPerViewAndPairedTests) {
    TempDir d;
    for (const char* sub : {"/gt", "/a", "/b"}) {
        std::filesystem::create_directory(d.path + sub);
    }
    const int shift_a[] = {0, 2, 4, 1}, shift_b[] = {1, 3, 6, 3};
    for (int v = 0; v < 4; ++v) {
        const std::string name = "/view" + std::to_string(v) + ".png";
        cv::imwrite(d.path + "/gt" + name, square(0));
        cv::imwrite(d.path + "/a" + name, square(shift_a[v], 1));  // 0/1 PNG
        cv::imwrite(d.path + "/b" + name, square(shift_b[v]));
    }
    cv::imwrite(d.path + "/gt/extra.png", square(0));  // no prediction: left out, warned
    const RunResult r =
        run_shell("@pc_maskeval " + d.path + "/a " + d.path + "/gt --against " + d.path + "/b");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("warning: 1 of 5 ground-truth views have no prediction"),
              std::string::npos)
        << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["kind"], "binary");
    EXPECT_EQ(j["views"], 4);
    double mean_a = 0, mean_b = 0;
    for (int v = 0; v < 4; ++v) {
        const double a = (20.0 - shift_a[v]) / (20.0 + shift_a[v]);
        const double b = (20.0 - shift_b[v]) / (20.0 + shift_b[v]);
        EXPECT_NEAR(j["method"]["views"][v]["iou"].get<double>(), a, 1e-12);
        EXPECT_NEAR(j["against"]["views"][v]["iou"].get<double>(), b, 1e-12);
        EXPECT_NEAR(j["method"]["views"][v]["precision"].get<double>(), (20.0 - shift_a[v]) / 20,
                    1e-12);
        mean_a += a / 4;
        mean_b += b / 4;
    }
    EXPECT_NEAR(j["method"]["summary"]["iou"]["mean"].get<double>(), mean_a, 1e-12);
    const auto& p = j["paired"]["iou"];
    EXPECT_EQ(p["n"], 4);
    EXPECT_NEAR(p["mean_difference"].get<double>(), mean_a - mean_b, 1e-12);
    EXPECT_GT(p["t"].get<double>(), 0);                 // a is better on every view
    EXPECT_NEAR(p["p_w"].get<double>(), 0.125, 1e-12);  // exact: 2 of 16 sign patterns
    const RunResult csv = run_shell("@pc_maskeval --csv " + d.path + "/a " + d.path + "/gt -q");
    ASSERT_EQ(csv.code, 0) << csv.err;
    EXPECT_EQ(csv.out.substr(0, csv.out.find('\n')), "view,dice,iou,precision,recall");
    EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 5);
}

TEST(PcMaskeval, JpegInstancesAndImages) {
    TempDir d;
    for (const char* sub : {"/jp", "/gt", "/ip", "/it", "/rp", "/rt"}) {
        std::filesystem::create_directory(d.path + sub);
    }
    // JPEG: fruit where > 125, so a 100-grey square is not fruit and a 200 one is
    cv::imwrite(d.path + "/gt/v.png", square(0));
    cv::Mat jpeg = square(0, 200);
    cv::rectangle(jpeg, cv::Rect(40, 10, 10, 10), cv::Scalar(100), cv::FILLED);
    cv::imwrite(d.path + "/jp/v.jpg", jpeg, {cv::IMWRITE_JPEG_QUALITY, 100});
    RunResult r = run_shell("@pc_maskeval " + d.path + "/jp " + d.path + "/gt");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NEAR(nlohmann::json::parse(r.out)["method"]["views"][0]["iou"].get<double>(), 1, 0.02);
    // JPEG ground truth too: compression blurs its edges into many grey levels, which must not
    // make it read as instance ids
    r = run_shell("@pc_maskeval " + d.path + "/jp " + d.path + "/jp");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["kind"], "binary");

    // 16-bit instance ids: two fruit, one found exactly, one missed
    cv::Mat it = square(0, 300, CV_16UC1), ip = square(0, 7, CV_16UC1);
    cv::rectangle(it, cv::Rect(40, 30, 10, 10), cv::Scalar(301), cv::FILLED);
    cv::imwrite(d.path + "/it/v.png", it);
    cv::imwrite(d.path + "/ip/v.png", ip);
    r = run_shell("@pc_maskeval " + d.path + "/ip " + d.path + "/it");
    ASSERT_EQ(r.code, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["kind"], "instance");
    EXPECT_EQ(j["method"]["views"][0]["precision"], 1.0);
    EXPECT_EQ(j["method"]["views"][0]["recall"], 0.5);

    // colour images 10 grey levels apart everywhere: MSE 100, PSNR 10 log10(255² / 100)
    cv::imwrite(d.path + "/rt/v.png", cv::Mat(48, 64, CV_8UC3, cv::Scalar(100, 120, 140)));
    cv::imwrite(d.path + "/rp/v.png", cv::Mat(48, 64, CV_8UC3, cv::Scalar(110, 130, 150)));
    r = run_shell("@pc_maskeval " + d.path + "/rp " + d.path + "/rt");
    ASSERT_EQ(r.code, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["kind"], "image");
    EXPECT_NEAR(j["method"]["views"][0]["psnr"].get<double>(), 10 * std::log10(255.0 * 255 / 100),
                1e-9);
}

TEST(PcMaskeval, BadFoldersFailWithOneLine) {
    TempDir d;
    for (const char* sub : {"/gt", "/p", "/q"}) {
        std::filesystem::create_directory(d.path + sub);
    }
    cv::imwrite(d.path + "/gt/v.png", square(0));
    cv::imwrite(d.path + "/p/v.png", cv::Mat::zeros(10, 10, CV_8UC1));
    cv::imwrite(d.path + "/q/other.png", square(0));
    const struct {
        std::string args;
        int code;
        std::string says;
    } cases[] = {
        {d.path + "/missing " + d.path + "/gt", 1, "/missing: not a folder"},
        {d.path + "/p " + d.path + "/gt", 1, "10 x 10, its ground truth"},
        {d.path + "/q " + d.path + "/gt", 1, "no image matches"},
        {d.path + "/p", 2, "expected two folders"},
        {d.path + "/p " + d.path + "/gt --kind lots", 2, "--kind must be"},
    };
    for (const auto& c : cases) {
        const RunResult r = run_shell("@pc_maskeval " + c.args);
        EXPECT_EQ(r.code, c.code) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_TRUE(r.out.empty());
    }
}

}  // namespace
}  // namespace pc::test
