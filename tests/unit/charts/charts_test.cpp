#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include <pc/charts/panel.h>
#include <pc/charts/render.h>
#include <pc/core/error.h>

namespace pc::charts {
namespace {

cv::Mat decode(const std::vector<std::uint8_t>& png) { return cv::imdecode(png, cv::IMREAD_COLOR); }

/// Pixels of the bar colour (BGR 140 104 59) in column range [x0, x1).
int filled(const cv::Mat& m, int x0, int x1) {
    int n = 0;
    for (int y = 0; y < m.rows; ++y) {
        for (int x = x0; x < x1; ++x) {
            n += m.at<cv::Vec3b>(y, x) == cv::Vec3b(140, 104, 59);
        }
    }
    return n;
}

TEST(Plot, PanelsSideBySideAsAPng) {
    const std::vector<Panel> panels = {
        {Panel::Kind::kHistogram, "sizes", "points", {}, {{1, 2, 2, 3, 3, 3, NAN}}},
        {Panel::Kind::kBox, "iou", "", {"a", "b"}, {{0.5, 0.6, 0.7}, {0.8, 0.9}}},
        {Panel::Kind::kBars, "volume", "", {"x", "y"}, {{1.0, 3.0}}}};
    const cv::Mat m = decode(render_png(panels));
    ASSERT_FALSE(m.empty());
    EXPECT_EQ(m.cols, 3 * 640);
    EXPECT_EQ(m.rows, 420);
    // Bars: the second is three times the first, so it covers about three times the pixels.
    const int x = filled(m, 2 * 640, 2 * 640 + 320), y = filled(m, 2 * 640 + 320, 3 * 640);
    EXPECT_NEAR(static_cast<double>(y) / x, 3.0, 0.1);
    // An empty panel still draws (it says "no data").
    EXPECT_FALSE(decode(render_png({{Panel::Kind::kHistogram, "none", "", {}, {{}}}})).empty());
}

TEST(Plot, TheDataGoesBesideThePlotAsCsv) {
    const std::vector<Panel> panels = {
        {Panel::Kind::kBox, "iou, per view", "", {"a", "b"}, {{0.5}, {0.25, NAN}}},
        {Panel::Kind::kBars, "n", "", {"x", "y"}, {{1, 2}}}};
    const std::string csv = panels_csv(panels);
    EXPECT_EQ(csv,
              "panel,kind,xlabel,name,value\n\"iou, per view\",box,,a,0.5\n"
              "\"iou, per view\",box,,b,0.25\n\"iou, per view\",box,,b,\nn,bars,,x,1\n"
              "n,bars,,y,2\n");
    EXPECT_EQ(csv_path("out/plot.png"), "out/plot.csv");
    // Read back: the same panels (pc_plot draws them again from the CSV).
    const std::vector<Panel> back = parse_panels(csv);
    ASSERT_EQ(back.size(), 2u);
    EXPECT_EQ(back[0].title, "iou, per view");
    EXPECT_EQ(back[0].names, (std::vector<std::string>{"a", "b"}));
    ASSERT_EQ(back[0].values[1].size(), 2u);
    EXPECT_TRUE(std::isnan(back[0].values[1][1]));
    EXPECT_EQ(back[1].values[0], (std::vector<double>{1, 2}));
    EXPECT_EQ(panels_csv(back), csv);
    EXPECT_THROW((void)parse_panels("panel,kind,xlabel,name,value\nt,pie,,a,1\n"), IoError);
    EXPECT_THROW((void)parse_panels("panel,kind,xlabel,name,value\nt,bars,,a,x\n"), IoError);
    EXPECT_THROW((void)parse_panels("a,b\n"), IoError);
}

}  // namespace
}  // namespace pc::charts
