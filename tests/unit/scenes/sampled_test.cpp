// The sampled modes (surface, sfm, stripes, volume), mask colours, interpenetrating fruit and
// units: each against a closed form.
#include <algorithm>
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/scenes/render.h>

namespace pc::scenes {
namespace {

constexpr double kPi = 3.141592653589793;

double dist(const std::array<float, 3>& q, const Vec3& c) {
    return std::sqrt((q[0] - c[0]) * (q[0] - c[0]) + (q[1] - c[1]) * (q[1] - c[1]) +
                     (q[2] - c[2]) * (q[2] - c[2]));
}

/// One fruit of radius 0.03 at (0.1, 0.2, 0.3), nothing else.
Scene one_fruit() {
    Scene s;
    s.fruits.push_back({{0.1, 0.2, 0.3}, 0.03, 0});
    s.bunch_count = 1;
    return s;
}

RenderParams bare(Mode mode, double spacing = 0.003) {
    return {.mode = mode, .voxel = spacing, .leaf_leak = 0, .background = 0, .outliers = 0};
}

TEST(Sampled, SurfacePointsLieOnTheSphereOnePerSpacingSquared) {
    const Scene s = one_fruit();
    const Rendered r = render(s, bare(Mode::kSurface));
    // n = area / spacing^2 = 4 pi 0.03^2 / 0.003^2
    EXPECT_EQ(r.xyz.size(), static_cast<std::size_t>(std::llround(4 * kPi * 100)));
    for (const auto& q : r.xyz) {
        ASSERT_NEAR(dist(q, s.fruits[0].centre), 0.03, 1e-6);
    }
    EXPECT_EQ(r.fruit_points[0], r.xyz.size());
}

TEST(Sampled, VolumePointsFillTheBallOnePerSpacingCubed) {
    const Scene s = one_fruit();
    const Rendered r = render(s, bare(Mode::kVolume));
    EXPECT_EQ(r.xyz.size(), static_cast<std::size_t>(std::llround(4.0 / 3 * kPi * 1000)));
    std::size_t inner = 0;  // uniform in volume: (1/2)^3 of the points within half the radius
    for (const auto& q : r.xyz) {
        ASSERT_LE(dist(q, s.fruits[0].centre), 0.03 + 1e-6);
        inner += dist(q, s.fruits[0].centre) < 0.015;
    }
    EXPECT_NEAR(static_cast<double>(inner) / r.xyz.size(), 0.125, 0.03);
}

TEST(Sampled, StripesAreHalfCirclesOnParallelPlanes) {
    const Scene s = one_fruit();
    const double v = 0.003;
    const Rendered r = render(s, bare(Mode::kStripes, v));
    // Sum over planes of half the circle at v/3 per point: ~ (3 pi / v^2) * (pi r^2 / 2).
    const double expected = 1.5 * kPi * kPi * 0.03 * 0.03 / (v * v);
    EXPECT_NEAR(static_cast<double>(r.xyz.size()), expected, 0.05 * expected);
    // Every point lies on the sphere, and the heights z of points of one line vary while their
    // horizontal positions fall on lines: the distinct planes number about 2r / v.
    for (const auto& q : r.xyz) {
        ASSERT_NEAR(dist(q, s.fruits[0].centre), 0.03, 1e-6);
    }
}

/// One prolate fruit (aspect 1.6, polar axis (0, 0.6, 0.8)) of volume radius 0.03.
Scene one_spheroid(double aspect = 1.6) {
    Scene s = one_fruit();
    s.fruits[0].aspect = aspect;
    s.fruits[0].axis = {0, 0.6, 0.8};
    return s;
}

/// Position of q along the fruit's axis, as a fraction of the polar half axis.
double along(const std::array<float, 3>& q, const Fruit& f) {
    double t = 0;
    for (int a = 0; a < 3; ++a) {
        t += (q[a] - f.centre[a]) * f.axis[a];
    }
    return t / (f.radius / std::cbrt(f.aspect) * f.aspect);
}

TEST(Sampled, SpheroidSurfacePointsLieOnItUniformlyOverItsArea) {
    const Scene s = one_spheroid();
    const Fruit& f = s.fruits[0];
    const double e = 0.03 / std::cbrt(1.6), c = 1.6 * e;  // equatorial and polar half axes
    const Rendered r = render(s, bare(Mode::kSurface, 0.0005));
    // Area by quadrature of 2 pi rho(z) sqrt(1 + rho'(z)^2) dz, rho(z) = e sqrt(1 - z^2 / c^2):
    // Thomsen's formula within 1.1 %, and the band |z| < c / 2 its share of it.
    double area = 0, band = 0;
    const int n = 200000;
    for (int k = 0; k < n; ++k) {
        const double z = -c + (k + 0.5) * 2 * c / n, rho = e * std::sqrt(1 - z * z / (c * c));
        const double slope = -e * z / (c * c * std::sqrt(1 - z * z / (c * c)));
        const double dA = 2 * kPi * rho * std::sqrt(1 + slope * slope) * 2 * c / n;
        area += dA;
        band += std::abs(z) < c / 2 ? dA : 0;
    }
    EXPECT_NEAR(f.area(), area, 0.011 * area);
    EXPECT_NEAR(static_cast<double>(r.xyz.size()), area / (0.0005 * 0.0005), 0.011 * r.xyz.size());
    std::size_t in_band = 0;
    for (const auto& q : r.xyz) {
        ASSERT_NEAR(f.level({q[0], q[1], q[2]}), 1.0, 1e-5);
        in_band += std::abs(along(q, f)) < 0.5;
    }
    // uniform over the area: the band holds its share (the unit sphere's directions alone, not
    // thinned by the stretch of the area, would put 0.5 of the points there)
    EXPECT_NEAR(static_cast<double>(in_band) / r.xyz.size(), band / area, 0.01);
    EXPECT_GT(band / area, 0.54);
}

TEST(Sampled, SpheroidVolumeAndStripesStayOnTheSpheroid) {
    const Scene s = one_spheroid(0.8);  // oblate
    const Fruit& f = s.fruits[0];
    const Rendered volume = render(s, bare(Mode::kVolume));
    EXPECT_EQ(volume.xyz.size(), static_cast<std::size_t>(std::llround(4.0 / 3 * kPi * 1000)));
    std::size_t inner = 0;  // uniform in volume: (1/2)^3 of the points within half the level
    for (const auto& q : volume.xyz) {
        ASSERT_LE(f.level({q[0], q[1], q[2]}), 1 + 1e-5);
        inner += f.level({q[0], q[1], q[2]}) < 0.5;
    }
    EXPECT_NEAR(static_cast<double>(inner) / volume.xyz.size(), 0.125, 0.03);
    const Rendered stripes = render(s, bare(Mode::kStripes));
    ASSERT_GT(stripes.xyz.size(), 500u);
    for (const auto& q : stripes.xyz) {
        ASSERT_NEAR(f.level({q[0], q[1], q[2]}), 1.0, 1e-5);
    }
}

TEST(Sampled, SfmIsDenserOutsideHasDuplicatesAndHoles) {
    Scene s = one_fruit();
    s.fruits[0].centre = {0.5, 0, 0};  // outward = +x
    RenderParams p = bare(Mode::kSfm, 0.002);
    p.holes = 0;
    p.density_spread = 0;
    p.duplicates = 0.2;
    const Rendered r = render(s, p);
    std::size_t outer = 0, inner = 0;
    std::map<std::array<float, 3>, int> seen;
    for (const auto& q : r.xyz) {
        (q[0] > 0.5 ? outer : inner) += 1;
        ++seen[q];
    }
    // Keep probability 0.1 + 0.9 max(0, cos): outer half keeps 0.1 + 0.45, inner half 0.1.
    EXPECT_NEAR(static_cast<double>(outer) / inner, 5.5, 0.6);
    std::size_t twice = 0;
    for (const auto& [q, n] : seen) {
        twice += n == 2;
    }
    EXPECT_NEAR(static_cast<double>(twice) / seen.size(), 0.2, 0.03);
    p.holes = 3;
    p.duplicates = 0;
    const Rendered holed = render(s, p);
    EXPECT_LT(holed.xyz.size(), seen.size());  // caps removed
}

TEST(Sampled, InterpenetratingFruitShowOnlyTheirOuterSurfaces) {
    SceneParams sp = species("plum");
    sp.fruit_count = 40;
    sp.bunch_min = 4;
    sp.bunch_max = 6;
    sp.touch_gap = 0;
    sp.overlap = 0.1;
    sp.canopy = {0.3, 0.3, 0.3};
    const Scene s = make_scene(sp);
    bool overlapping = false;
    for (std::size_t a = 0; a < s.fruits.size(); ++a) {
        for (std::size_t b = a + 1; b < s.fruits.size(); ++b) {
            const auto& fa = s.fruits[a];
            const auto& fb = s.fruits[b];
            const std::array<float, 3> c{static_cast<float>(fa.centre[0]),
                                         static_cast<float>(fa.centre[1]),
                                         static_cast<float>(fa.centre[2])};
            const double d = dist(c, fb.centre);
            // never deeper than the allowed overlap
            ASSERT_GE(d, fa.radius + fb.radius - 0.1 * std::min(fa.radius, fb.radius) - 1e-6);
            overlapping = overlapping || d < fa.radius + fb.radius - 1e-4;
        }
    }
    ASSERT_TRUE(overlapping);
    const Rendered r = render(s, bare(Mode::kSurface, 0.002));
    for (std::size_t k = 0; k < r.xyz.size(); ++k) {
        for (std::size_t f = 0; f < s.fruits.size(); ++f) {
            if (r.gt[k] != f + 1) {
                ASSERT_GE(dist(r.xyz[k], s.fruits[f].centre), s.fruits[f].radius - 1e-5);
            }
        }
    }
    // On the lattice a shared voxel goes to one fruit only: no position written twice.
    const Rendered solid = render(s, bare(Mode::kExplicit, 0.002));
    std::map<std::array<float, 3>, int> seen;
    for (const auto& q : solid.xyz) {
        ASSERT_EQ(++seen[q], 1);
    }
}

TEST(Sampled, MaskColoursAreWhiteFruitOnBlack) {
    SceneParams sp = species("peach");
    sp.fruit_count = 20;
    sp.canopy = {0.5, 0.5, 0.5};
    const Scene s = make_scene(sp);
    for (Mode m : {Mode::kSurface, Mode::kExplicit, Mode::kImplicit}) {
        RenderParams p{.mode = m, .voxel = 0.005, .leaf_leak = 1, .outliers = 0};
        p.colors = Colors::kMask;
        const Rendered r = render(s, p);
        std::size_t dark = 0;
        for (std::size_t k = 0; k < r.xyz.size(); ++k) {
            const std::uint32_t c = r.rgb[k];
            const unsigned red = (c >> 16) & 255, green = (c >> 8) & 255, blue = c & 255;
            ASSERT_EQ(red, green);
            ASSERT_EQ(green, blue);
            if (r.gt[k] != 0) {
                ASSERT_GE(red, 243u);
            }
            dark += red <= 12;
        }
        EXPECT_GT(dark, 0u) << mode_name(m);  // leaves and ground
    }
}

TEST(Sampled, BlushedFruitWearTheBlushOverTheirShareOfTheSurface) {
    // Each fruit's blushed cap holds its share of the fruit's surface points (uniform over the
    // area: (1 - cos) / 2 of a sphere's), on its own side; without blush the scene is unchanged.
    SceneParams sp = species("peach");
    sp.fruit_count = 20;
    sp.canopy = {0.5, 0.5, 0.5};
    sp.fruit_rgb = {205, 195, 95};
    const Scene plain = make_scene(sp);
    sp.blush_min = 0.2;
    sp.blush_max = 0.8;
    sp.blush_rgb = {180, 40, 50};
    const Scene s = make_scene(sp);
    ASSERT_EQ(s.fruits.size(), plain.fruits.size());
    const Rendered r = render(s, bare(Mode::kSurface, 0.002));
    const Rendered one = render(plain, bare(Mode::kSurface, 0.002));
    EXPECT_EQ(r.xyz, one.xyz);  // the same fruit, the same points
    std::vector<double> red(s.fruits.size(), 0), all(s.fruits.size(), 0);
    for (std::size_t k = 0; k < r.xyz.size(); ++k) {
        if (r.gt[k] != 0) {
            const auto f = r.gt[k] - 1;
            all[f] += 1;
            red[f] += ((r.rgb[k] >> 8) & 255) < 120;  // the blush's green channel 40 (x 1.05 + 8)
        }
    }
    std::vector<double> shares;
    for (std::size_t f = 0; f < s.fruits.size(); ++f) {
        const double share = (1 - s.fruits[f].blush_from) / 2;
        ASSERT_GE(share, 0.2);
        ASSERT_LE(share, 0.8);
        shares.push_back(share);
        if (all[f] > 300) {  // sampled whole: the cap's share of the points within a few %
            EXPECT_NEAR(red[f] / all[f], share, 0.06) << f;
        }
    }
    EXPECT_GT(*std::max_element(shares.begin(), shares.end()) -
                  *std::min_element(shares.begin(), shares.end()),
              0.2);  // drawn per fruit
    EXPECT_EQ(plain.fruits[0].blush_from, 2);
    sp.blush_min = 0.9;  // above blush_max
    EXPECT_THROW((void)make_scene(sp), InvalidArgument);
}

TEST(Sampled, ColourNoiseSpreadsEachChannelBySigmaAndMovesNoPoint) {
    // N(0, color_noise) per channel from streams of their own: the same points, and each
    // channel's difference to the scene without it spreads by sigma (the colours sit mid-range,
    // clear of the clamping at 0 and 255 within 3 sigma: brown bark and a pale orange fruit).
    SceneParams sp = species("peach");
    sp.fruit_count = 20;
    sp.canopy = {0.5, 0.5, 0.5};
    sp.fruit_rgb = {160, 130, 110};
    sp.branches = 3;
    sp.wood_rgb = {120, 100, 90};
    const Scene s = make_scene(sp);
    RenderParams p = bare(Mode::kSfm, 0.004);
    p.shading = 0.2;
    const Rendered plain = render(s, p);
    p.color_noise = 15;
    const Rendered noisy = render(s, p);
    ASSERT_EQ(noisy.xyz, plain.xyz);
    ASSERT_EQ(noisy.gt, plain.gt);
    for (const bool fruit : {true, false}) {
        double n = 0, sum = 0, sum2 = 0;
        for (std::size_t k = 0; k < plain.xyz.size(); ++k) {
            if ((plain.gt[k] != 0) != fruit) {
                continue;
            }
            for (int shift : {16, 8, 0}) {
                const double d = static_cast<double>((noisy.rgb[k] >> shift) & 255) -
                                 static_cast<double>((plain.rgb[k] >> shift) & 255);
                n += 1;
                sum += d;
                sum2 += d * d;
            }
        }
        ASSERT_GT(n, 3000) << fruit;
        EXPECT_NEAR(sum / n, 0, 0.5) << fruit;
        EXPECT_NEAR(std::sqrt(sum2 / n), 15, 0.5) << fruit;  // rounding adds 1/12 in variance
    }
    p.color_noise = -1;
    EXPECT_THROW((void)render(s, p), InvalidArgument);
}

TEST(Sampled, ScaleAndOffsetMoveEveryPointAndNothingElse) {
    const Scene s = one_fruit();
    RenderParams p = bare(Mode::kSfm);
    const Rendered m = render(s, p);
    p.scale = 1000;
    p.offset = {5, -3, 2};
    const Rendered mm = render(s, p);
    ASSERT_EQ(m.xyz.size(), mm.xyz.size());
    EXPECT_EQ(m.gt, mm.gt);
    EXPECT_EQ(m.rgb, mm.rgb);
    for (std::size_t k = 0; k < m.xyz.size(); ++k) {
        for (int a = 0; a < 3; ++a) {
            ASSERT_NEAR(mm.xyz[k][a], m.xyz[k][a] * 1000 + p.offset[a], 1e-3);
        }
    }
}

TEST(Sampled, SameSeedSameBytesAndBadParametersAreRefused) {
    SceneParams sp = species("apple");
    sp.fruit_count = 30;
    sp.canopy = {0.5, 0.5, 0.5};
    const Scene s = make_scene(sp);
    for (Mode m : {Mode::kSurface, Mode::kSfm, Mode::kStripes, Mode::kVolume}) {
        RenderParams p{.mode = m, .voxel = 0.004};
        p.noise = 0.05;
        p.shading = 0.5;
        const Rendered a = render(s, p), b = render(s, p);
        EXPECT_EQ(a.xyz, b.xyz) << mode_name(m);
        EXPECT_EQ(a.rgb, b.rgb);
        EXPECT_EQ(parse_mode(mode_name(m)), m);
    }
    RenderParams p{.mode = Mode::kSurface};
    p.shading = 2;
    EXPECT_THROW((void)render(s, p), InvalidArgument);
    p = {.mode = Mode::kSurface, .voxel = 0.05};  // spacing > radius
    EXPECT_THROW((void)render(s, p), InvalidArgument);
    p = {.mode = Mode::kSurface};
    p.scale = 0;
    EXPECT_THROW((void)render(s, p), InvalidArgument);
    sp.overlap = 0.6;
    EXPECT_THROW((void)make_scene(sp), InvalidArgument);
    EXPECT_THROW((void)parse_colors("grey"), InvalidArgument);
}

}  // namespace
}  // namespace pc::scenes
