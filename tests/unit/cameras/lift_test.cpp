// lift: spheres floating over a ground plane, seen by nine cameras whose masks are ray-cast
// against the analytic spheres and plane (independent of the points and their z-buffer). Every
// point that some view sees must come out fruit exactly when it lies on a sphere.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <pc/cameras/lift.h>
#include <pc/cameras/render.h>
#include <pc/core/error.h>

namespace pc::cameras {
namespace {

constexpr double kPi = 3.141592653589793;
const std::vector<Eigen::Vector3d> kCentres = {{0, 0, 0.15}, {0.3, -0.2, 0.15}, {-0.35, 0.3, 0.2}};
constexpr double kRadius = 0.1, kSpacing = 0.01;

/// A camera at `eye` looking at the origin, z up in the world: 640 x 480 pixels, f = 600 (a pixel
/// 4 mm at the fruit: finer than the 1 cm point spacing).
View look_at(const Eigen::Vector3d& eye) {
    return cameras::look_at(eye, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 640, 480,
                            2 * std::atan(240.0 / 600));
}

/// 1 where the pixel's ray meets a sphere before the plane z = 0.
Mask ray_cast(const View& v) {
    Mask m{v.camera.width, v.camera.height, {}};
    const Eigen::Vector3d o = v.centre();
    for (int y = 0; y < m.height; ++y) {
        for (int x = 0; x < m.width; ++x) {
            const Eigen::Vector3d d =
                (v.rotation.transpose() * Eigen::Vector3d((x + 0.5 - v.camera.cx) / v.camera.fx,
                                                          (y + 0.5 - v.camera.cy) / v.camera.fy, 1))
                    .normalized();
            const double plane = d.z() < 0 ? -o.z() / d.z() : std::numeric_limits<double>::max();
            bool fruit = false;
            for (const Eigen::Vector3d& c : kCentres) {
                const double b = d.dot(o - c),
                             disc = b * b - ((o - c).squaredNorm() - kRadius * kRadius);
                fruit = fruit ||
                        (disc >= 0 && -b - std::sqrt(disc) > 0 && -b - std::sqrt(disc) < plane);
            }
            m.fruit.push_back(fruit ? 1 : 0);
        }
    }
    return m;
}

TEST(Lift, EveryPointSeenIsFruitExactlyWhenItLiesOnAFruit) {
    Cloud c;
    std::vector<bool> truth;
    for (double x = -0.8; x <= 0.8; x += kSpacing) {
        for (double y = -0.8; y <= 0.8; y += kSpacing) {
            c.push_back({static_cast<float>(x), static_cast<float>(y), 0});
            truth.push_back(false);
        }
    }
    const auto n = static_cast<int>(4 * kPi * kRadius * kRadius / (kSpacing * kSpacing));
    for (const Eigen::Vector3d& centre : kCentres) {
        for (int i = 0; i < n; ++i) {
            const double z = 1 - 2 * (i + 0.5) / n, rho = std::sqrt(1 - z * z), phi = 2.399963 * i;
            const Eigen::Vector3d p =
                centre + kRadius * Eigen::Vector3d(rho * std::cos(phi), rho * std::sin(phi), z);
            c.push_back(
                {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
            truth.push_back(true);
        }
    }
    std::vector<View> views{look_at({0.01, 0.02, 2.5})};
    for (int k = 0; k < 8; ++k) {
        const double a = 2 * kPi * k / 8;
        views.push_back(look_at({2 * std::cos(a), 2 * std::sin(a), 1.2}));
    }
    std::vector<Mask> masks;
    for (const View& v : views) {
        masks.push_back(ray_cast(v));
    }
    std::size_t progress_calls = 0;
    const LiftResult r = lift(
        XyzView(c), views, [&](std::size_t k) { return masks[k]; }, kSpacing, {},
        [&](std::size_t done, std::size_t total) {
            ++progress_calls;
            EXPECT_LE(done, total);
        });
    EXPECT_EQ(progress_calls, views.size());
    std::size_t seen = 0, wrong = 0, fruit_seen = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        EXPECT_LE(r.votes[i], r.views[i]);
        if (r.views[i] > 0) {
            ++seen;
            fruit_seen += truth[i];
            wrong += (r.fruit[i] != 0) != truth[i];
        } else {
            EXPECT_EQ(r.fruit[i], 0);
        }
    }
    EXPECT_GT(fruit_seen, 3000u);  // most of the spheres' upper sides
    EXPECT_GT(seen, 20000u);
    // a point on a rim seen by one view may fall on a background pixel: 5 of 28740 do
    EXPECT_LT(wrong, seen / 1000) << wrong << " of " << seen;

    // The top view alone: the ground right under a fruit is hidden, the open ground seen.
    const LiftResult top =
        lift(XyzView(c), {views[0]}, [&](std::size_t) { return masks[0]; }, kSpacing, {});
    std::size_t under = 0, open = 0;
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (truth[i]) {
            continue;
        }
        double nearest = 1e9;
        for (const Eigen::Vector3d& centre : kCentres) {
            nearest = std::min(nearest, std::hypot(c[i].x - centre.x(), c[i].y - centre.y()));
        }
        if (nearest < 0.06) {
            EXPECT_EQ(top.views[i], 0u) << c[i].x << " " << c[i].y;
            ++under;
        } else if (nearest > 0.2 && std::abs(c[i].x) < 0.5 && std::abs(c[i].y) < 0.5) {
            EXPECT_EQ(top.views[i], 1u) << c[i].x << " " << c[i].y;
            EXPECT_EQ(top.fruit[i], 0);
            ++open;
        }
    }
    EXPECT_GT(under, 100u);
    EXPECT_GT(open, 1000u);
}

TEST(Lift, AMaskOfAnotherSizeOrAFailingMaskIsAnErrorNamingTheView) {
    Cloud c;
    c.push_back({0, 0, 0});
    View v = look_at({0, 0.01, 2});
    v.image = "images/a.png";
    const auto bad = [&](std::size_t) { return Mask{10, 10, std::vector<std::uint8_t>(100, 0)}; };
    try {
        (void)lift(XyzView(c), {v}, bad, 0.01, {});
        FAIL();
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("images/a.png: mask is 10 x 10, the camera 640 x 480"),
                  std::string::npos)
            << e.what();
    }
    const auto throws = [](std::size_t) -> Mask { throw IoError("masks/a.png: cannot read"); };
    EXPECT_THROW((void)lift(XyzView(c), {v, v, v}, throws, 0.01, {}), IoError);
    EXPECT_THROW((void)lift(XyzView(c), {v}, bad, 0.01, {.min_ratio = 1.5}), InvalidArgument);
}

}  // namespace
}  // namespace pc::cameras
