#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <pc/features/extent_report.h>

namespace pc::features {
namespace {

/// The unit cube's eight corners, measured by hand: centroid 0.5, AABB and hull volume 1, hull
/// area 6, every corner sqrt(3)/2 from the centroid.
Extent unit_cube() {
    Extent e;
    e.points = 8;
    e.centroid = {0.5, 0.5, 0.5};
    e.min = {0, 0, 0};
    e.max = {1, 1, 1};
    e.aabb_volume = 1;
    e.hull_volume = 1;
    e.hull_area = 6;
    e.mean_radius = e.max_radius = std::sqrt(3.0) / 2;
    e.equivalent_diameter = std::cbrt(6 / std::numbers::pi);
    e.degenerate = false;
    return e;
}

std::vector<ExtentRow> rows() {
    Extent flat;  // three points: no hull
    flat.points = 3;
    flat.hull_volume = flat.hull_area = std::nan("");
    return {{.name = "cube",
             .input = "cube.pcd",
             .whole = unit_cube(),
             .clusters = {{1, unit_cube()}, {2, flat}}}};
}

TEST(ExtentReport, JsonHoldsEveryFieldAndNullForWhatCannotBeComputed) {
    const auto j = nlohmann::json::parse(extent_report(rows(), ExtentFormat::kJson, true));
    const auto& c = j["clouds"][0];
    EXPECT_EQ(c["name"], "cube");
    EXPECT_EQ(c["input"], "cube.pcd");
    EXPECT_EQ(c["points"], 8);
    EXPECT_EQ(c["aabb"]["extent"], nlohmann::json({1.0, 1.0, 1.0}));
    EXPECT_EQ(c["hull"]["area"], 6.0);
    ASSERT_EQ(c["clusters"].size(), 2u);
    EXPECT_EQ(c["clusters"][0]["label"], 1);
    EXPECT_TRUE(c["clusters"][1]["hull"]["volume"].is_null());
    EXPECT_EQ(c["cluster_summary"]["count"], 2);
}

TEST(ExtentReport, CsvHasARowForTheCloudAndEachCluster) {
    const std::string csv = extent_report(rows(), ExtentFormat::kCsv, true);
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "name,label,points,centroid_x,centroid_y,centroid_z,min_x,min_y,min_z,max_x,max_y,"
              "max_z,aabb_volume,hull_volume,hull_area,mean_radius,max_radius,equivalent_diameter,"
              "degenerate");
    EXPECT_NE(csv.find("\ncube,all,8,0.5,0.5,0.5,0,0,0,1,1,1,1,1,6,"), std::string::npos);
    EXPECT_NE(csv.find("\ncube,1,8,"), std::string::npos);
    EXPECT_NE(csv.find("\ncube,2,3,"), std::string::npos);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
}

TEST(ExtentReport, MarkdownIsThePapersTableThreeLayout) {
    const std::string md = extent_report(rows(), ExtentFormat::kMarkdown, false);
    EXPECT_EQ(md,
              "| Model | Points | Convex hull volume | Mean radius | Max radius | AABB volume |\n"
              "| --- | ---: | ---: | ---: | ---: | ---: |\n"
              "| cube | 8 | 1 | 0.866025 | 0.866025 | 1 |\n");
}

}  // namespace
}  // namespace pc::features
