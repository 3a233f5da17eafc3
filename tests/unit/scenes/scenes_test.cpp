// Synthetic scenes: determinism, the layout's invariants, and what each export mode keeps.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/core/random.h>
#include <pc/scenes/render.h>

namespace pc::scenes {
namespace {

double dist(const Vec3& a, const Vec3& b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                     (a[2] - b[2]) * (a[2] - b[2]));
}

SceneParams small(std::uint64_t seed = 7) {
    SceneParams p = species("plum");
    p.fruit_count = 60;
    p.canopy = {0.4, 0.4, 0.3};
    p.seed = seed;
    return p;
}

TEST(Scene, SameSeedSameSceneAndCloudOtherSeedOther) {
    const Scene a = make_scene(small(7)), b = make_scene(small(7)), c = make_scene(small(8));
    ASSERT_EQ(a.fruits.size(), 60u);
    EXPECT_EQ(a.fruits[17].centre, b.fruits[17].centre);
    EXPECT_NE(a.fruits[17].centre, c.fruits[17].centre);
    for (Mode m : {Mode::kExplicit, Mode::kImplicit, Mode::kDegraded}) {
        RenderParams rp{.mode = m, .seed = 7};
        const Rendered x = render(a, rp), y = render(b, rp);
        EXPECT_EQ(x.xyz, y.xyz) << mode_name(m);
        EXPECT_EQ(x.rgb, y.rgb);
        EXPECT_EQ(x.gt, y.gt);
    }
}

TEST(Scene, SpeciesHaveThePapersCountsAndFruitNeverOverlap) {
    for (const auto& name : species_names()) {
        const SceneParams p = species(name);
        const Scene s = make_scene(p);
        ASSERT_EQ(s.fruits.size(), p.fruit_count) << name;
        std::vector<std::vector<std::size_t>> bunches(s.bunch_count);
        for (std::size_t i = 0; i < s.fruits.size(); ++i) {
            bunches.at(s.fruits[i].bunch).push_back(i);
            for (std::size_t j = i + 1; j < s.fruits.size(); ++j) {
                const auto &a = s.fruits[i], &b = s.fruits[j];
                const double gap = dist(a.centre, b.centre) - a.radius - b.radius;
                EXPECT_GE(gap, a.bunch == b.bunch ? -1e-12 : p.separation - 1e-12)
                    << name << ' ' << i << ' ' << j;
            }
        }
        // Every fruit of a bunch touches another of its bunch (gap within touch_gap).
        for (const auto& members : bunches) {
            EXPECT_LE(members.size(), p.bunch_max);
            for (auto i : members) {
                double nearest = 1e9;
                for (auto j : members) {
                    if (j != i) {
                        const auto &a = s.fruits[i], &b = s.fruits[j];
                        nearest = std::min(nearest, dist(a.centre, b.centre) - a.radius - b.radius);
                    }
                }
                if (members.size() > 1) {
                    EXPECT_LE(nearest, p.touch_gap + 1e-12) << name;
                }
            }
        }
    }
}

TEST(Scene, SpheroidsHaveTheirShapeAndNeverOverlap) {
    Fruit f{{0.1, -0.2, 0.3}, 0.02, 0};
    f.aspect = 1.5;
    f.axis = {0.6, 0, 0.8};
    const double e = 0.02 / std::cbrt(1.5);
    EXPECT_NEAR(f.smallest(), e, 1e-12);
    EXPECT_NEAR(f.largest(), 1.5 * e, 1e-12);
    EXPECT_NEAR(f.reach(f.axis), 1.5 * e, 1e-12);
    EXPECT_NEAR(f.reach({0, 1, 0}), e, 1e-12);
    Rng rng(3, 0);
    for (int k = 0; k < 1000; ++k) {  // on the surface; the normal across the surface
        const Vec3 d = rng.direction(), q = f.at(d, f.radius), n = f.normal(d);
        EXPECT_NEAR(f.level(q), 1.0, 1e-12);
        Vec3 tangent{d[1] * n[2] - d[2] * n[1], d[2] * n[0] - d[0] * n[2],
                     d[0] * n[1] - d[1] * n[0]};
        Vec3 moved = q;  // a step along a tangent stays on the surface to second order
        for (int a = 0; a < 3; ++a) {
            moved[a] += 1e-5 * tangent[a];
        }
        EXPECT_NEAR(f.level(moved), 1.0, 1e-6);
        EXPECT_NEAR(f.level(f.at(d, 0.5 * f.radius)), 0.5, 1e-12);
    }
    SceneParams p = small();
    p.aspect = 1.6;
    p.aspect_spread = 0.1;
    p.touch_gap = 0.002;
    const Scene s = make_scene(p);
    ASSERT_EQ(s.fruits.size(), p.fruit_count);
    for (const auto& a : s.fruits) {
        EXPECT_NEAR(a.aspect, 1.6, 0.16 + 1e-12);
        for (const auto& b : s.fruits) {
            if (&a == &b || dist(a.centre, b.centre) > a.largest() + b.largest()) {
                continue;
            }
            for (int k = 0; k < 200; ++k) {  // a's surface lies outside b
                ASSERT_GE(b.level(a.at(rng.direction(), a.radius)), 1 - 1e-9);
            }
        }
    }
}

TEST(Render, ExplicitModeHasEveryFruitAsSolidVoxels) {
    for (const auto& name : species_names()) {
        const Scene s = make_scene(species(name));
        const RenderParams rp{.mode = Mode::kExplicit, .voxel = 0.004};
        const Rendered r = render(s, rp);
        std::set<std::uint32_t> ids(r.gt.begin(), r.gt.end());
        ids.erase(0);
        EXPECT_EQ(ids.size(), s.fruits.size()) << name;
        // Voxel centres inside a sphere: about its volume / voxel³ of them (r/v >= 3.8 here).
        for (std::size_t f = 0; f < s.fruits.size(); f += 37) {
            const double expected = 4.0 / 3.0 * M_PI * std::pow(s.fruits[f].radius / rp.voxel, 3);
            EXPECT_NEAR(r.fruit_points[f], expected, 0.12 * expected) << name << " fruit " << f;
        }
    }
}

TEST(Render, PointsLieOnTheLatticeInsideTheirFruit) {
    const Scene s = make_scene(small());
    const RenderParams rp{.mode = Mode::kExplicit, .voxel = 0.004};
    const Rendered r = render(s, rp);
    for (std::size_t n = 0; n < r.xyz.size(); ++n) {
        if (r.gt[n] == 0) {
            continue;
        }
        const Fruit& f = s.fruits[r.gt[n] - 1];
        const Vec3 p{r.xyz[n][0], r.xyz[n][1], r.xyz[n][2]};
        EXPECT_LE(dist(p, f.centre), f.radius + 1e-6);
        for (double c : p) {
            EXPECT_NEAR(std::fmod(std::abs(c) / rp.voxel, 1.0), 0.5, 1e-3);  // (i + 0.5) v
        }
    }
}

/// A fruit enclosed by 14 touching fruit (6 faces, 8 corners) and a lone fruit of the same size.
Scene enclosed() {
    Scene s;
    const double r = 0.03, d = 2 * r + 0.001;
    s.canopy = {0.5, 0.5, 0.5};
    s.fruits.push_back({{0, 0, 0}, r, 0});
    for (int a = 0; a < 3; ++a) {
        for (double sign : {-1.0, 1.0}) {
            Vec3 c{0, 0, 0};
            c[a] = sign * d;
            s.fruits.push_back({c, r, 0});
        }
    }
    for (int k = 0; k < 8; ++k) {
        const double e = d / std::sqrt(3.0);
        s.fruits.push_back({{(k & 1 ? e : -e), (k & 2 ? e : -e), (k & 4 ? e : -e)}, r, 0});
    }
    s.fruits.push_back({{0.35, 0.0, 0.1}, r, 1});
    s.bunch_count = 2;
    return s;
}

TEST(Render, ImplicitModeLosesTheInteriorOfEnclosedFruit) {
    const Scene s = enclosed();
    const RenderParams rp{.mode = Mode::kImplicit,
                          .voxel = 0.004,
                          .surface_noise = 0,
                          .floaters = 0,
                          .background = 0,
                          .outliers = 0};
    const Rendered imp = render(s, rp);
    const Rendered exp =
        render(s, {.mode = Mode::kExplicit, .voxel = 0.004, .background = 0, .outliers = 0});
    const auto enclosed_points = imp.fruit_points.front(), lone_points = imp.fruit_points.back();
    EXPECT_GT(lone_points, 200u);
    EXPECT_LT(enclosed_points, lone_points / 4) << enclosed_points << " vs " << lone_points;
    EXPECT_LT(lone_points, exp.fruit_points.back() / 2);  // hollow: surfaces only
    // Without jitter every fruit point is a surface voxel: within one voxel of the sphere.
    for (std::size_t n = 0; n < imp.xyz.size(); ++n) {
        if (imp.gt[n] != 0) {
            const Fruit& f = s.fruits[imp.gt[n] - 1];
            const double d = dist({imp.xyz[n][0], imp.xyz[n][1], imp.xyz[n][2]}, f.centre);
            EXPECT_GE(d, f.radius - std::sqrt(3.0) * rp.voxel);
        }
    }
}

TEST(Render, DegradedModeKeepsAboutTheRecallAndMissesSomeFruit) {
    const Scene s = make_scene(species("plum"));
    const Rendered full = render(s, {.mode = Mode::kExplicit});
    const Rendered poor = render(s, {.mode = Mode::kDegraded, .recall = 0.44});
    double kept = 0, all = 0;
    std::size_t missed = 0;
    for (std::size_t f = 0; f < s.fruits.size(); ++f) {
        kept += poor.fruit_points[f];
        all += full.fruit_points[f];
        missed += poor.fruit_points[f] == 0;
    }
    // Per-fruit recall uniform in 0.44 ± 0.4, fruit below 0.15 missed: E = (0.84² − 0.15²) / 1.6.
    EXPECT_NEAR(kept / all, (0.84 * 0.84 - 0.15 * 0.15) / 1.6, 0.03);
    EXPECT_NEAR(static_cast<double>(missed) / s.fruits.size(), 0.11 / 0.8, 0.04);
}

TEST(Render, ClutterHasTheColoursTheChainExpects) {
    const Scene s = make_scene(small());
    const Rendered r = render(s, {.mode = Mode::kExplicit, .leaf_leak = 1.0});
    std::size_t dark = 0, bright_clutter = 0, green = 0;
    for (std::size_t n = 0; n < r.rgb.size(); ++n) {
        const double R = (r.rgb[n] >> 16) & 255, G = (r.rgb[n] >> 8) & 255, B = r.rgb[n] & 255;
        const double mean = (R + G + B) / 765;
        if (r.gt[n] != 0) {
            EXPECT_GT(mean, 0.5);  // sunlit fruit pass the paper's dark-background filter
        } else if (mean < 0.3) {
            (G > R + 30 ? green : dark) += 1;
        } else {
            ++bright_clutter;
        }
    }
    EXPECT_GT(green, 0u);
    EXPECT_GT(dark, 0u);
    EXPECT_GT(bright_clutter, 0u);
}

TEST(Scene, BadParametersAreRefused) {
    SceneParams p = small();
    p.fruit_radius = -1;
    EXPECT_THROW((void)make_scene(p), InvalidArgument);
    p = small();
    p.bunch_min = 4;
    p.bunch_max = 3;
    EXPECT_THROW((void)make_scene(p), InvalidArgument);
    p = small();
    p.fruit_count = 5000;  // cannot fit
    EXPECT_THROW((void)make_scene(p), InvalidArgument);
    EXPECT_THROW((void)species("banana"), InvalidArgument);
    EXPECT_THROW((void)parse_mode("solid"), InvalidArgument);
    EXPECT_THROW((void)render(make_scene(small()), {.voxel = 0.05}),
                 InvalidArgument);  // voxel > radius
    EXPECT_THROW((void)render(make_scene(small()), {.recall = 0}), InvalidArgument);
}

TEST(Render, BlobHasTheDocumentedFields) {
    const Rendered r = render(make_scene(small()), {});
    const io::Blob b = to_blob(r);
    ASSERT_EQ(b.size(), r.xyz.size());
    ASSERT_NE(io::find_field(b, "gt_instance"), nullptr);
    EXPECT_EQ(io::find_field(b, "gt_instance")->datatype, pcl::PCLPointField::UINT32);
    EXPECT_EQ(io::find_field(b, "rgb")->datatype, pcl::PCLPointField::UINT32);
    io::check_layout(b);
}

}  // namespace
}  // namespace pc::scenes
