// lift: spheres floating over a ground plane, seen by nine cameras whose masks are ray-cast
// against the analytic spheres and plane (independent of the points and their z-buffer). Every
// point that some view sees must come out fruit exactly when it lies on a sphere.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <pc/cameras/lift.h>
#include <pc/cameras/render.h>
#include <pc/core/error.h>

#include "support/clouds.h"

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

/// Where the pixel's ray first meets a sphere of `centres` before the plane z = 0: 1 + that
/// sphere's index, else 0.
Mask ray_cast(const View& v, const std::vector<Eigen::Vector3d>& centres = kCentres) {
    Mask m{v.camera.width, v.camera.height, {}};
    const Eigen::Vector3d o = v.centre();
    for (int y = 0; y < m.height; ++y) {
        for (int x = 0; x < m.width; ++x) {
            const Eigen::Vector3d d =
                (v.rotation.transpose() * Eigen::Vector3d((x + 0.5 - v.camera.cx) / v.camera.fx,
                                                          (y + 0.5 - v.camera.cy) / v.camera.fy, 1))
                    .normalized();
            const double plane = d.z() < 0 ? -o.z() / d.z() : std::numeric_limits<double>::max();
            double nearest = plane;
            std::uint16_t id = 0;
            for (std::size_t k = 0; k < centres.size(); ++k) {
                const Eigen::Vector3d& c = centres[k];
                const double b = d.dot(o - c),
                             disc = b * b - ((o - c).squaredNorm() - kRadius * kRadius);
                const double t = disc >= 0 ? -b - std::sqrt(disc) : -1;
                if (t > 0 && t < nearest) {
                    nearest = t;
                    id = static_cast<std::uint16_t>(k + 1);
                }
            }
            m.id.push_back(id);
        }
    }
    return m;
}

/// The ground plane z = 0 (id 0) and the spheres' surfaces (id 1 + the sphere's index), points
/// kSpacing apart.
void scene(const std::vector<Eigen::Vector3d>& centres, Cloud& c, std::vector<std::uint32_t>& id) {
    for (double x = -0.8; x <= 0.8; x += kSpacing) {
        for (double y = -0.8; y <= 0.8; y += kSpacing) {
            c.push_back({static_cast<float>(x), static_cast<float>(y), 0});
            id.push_back(0);
        }
    }
    const auto n = static_cast<int>(4 * kPi * kRadius * kRadius / (kSpacing * kSpacing));
    for (std::size_t k = 0; k < centres.size(); ++k) {
        for (int i = 0; i < n; ++i) {
            const Eigen::Vector3d p = centres[k] + kRadius * test::spiral_direction(i, n);
            c.push_back(
                {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
            id.push_back(static_cast<std::uint32_t>(k + 1));
        }
    }
}

/// A camera from the top and eight around at 45 degrees elevation.
std::vector<View> nine_views() {
    std::vector<View> views{look_at({0.01, 0.02, 2.5})};
    for (int k = 0; k < 8; ++k) {
        const double a = 2 * kPi * k / 8;
        views.push_back(look_at({2 * std::cos(a), 2 * std::sin(a), 1.2}));
    }
    return views;
}

TEST(Lift, EveryPointSeenIsFruitExactlyWhenItLiesOnAFruit) {
    Cloud c;
    std::vector<std::uint32_t> id;
    scene(kCentres, c, id);
    std::vector<bool> truth;
    for (const std::uint32_t i : id) {
        truth.push_back(i != 0);
    }
    const std::vector<View> views = nine_views();
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

TEST(Lift, InstanceMasksTellTouchingFruitApart) {
    // Three spheres touching in a bunch (centres 2R apart) and one alone; the masks give each
    // sphere its own id in every view (ray-cast, independent of the z-buffer). Every sphere must
    // come out as one label of its own; the few points at a contact may go to the neighbour.
    const std::vector<Eigen::Vector3d> centres = {{0, 0, 0.15},
                                                  {2 * kRadius, 0, 0.15},
                                                  {kRadius, std::sqrt(3.0) * kRadius, 0.15},
                                                  {-0.4, -0.3, 0.15}};
    Cloud c;
    std::vector<std::uint32_t> id;
    scene(centres, c, id);
    const std::vector<View> views = nine_views();
    std::vector<Mask> masks;
    for (const View& v : views) {
        masks.push_back(ray_cast(v, centres));
    }
    const LiftResult r = lift(XyzView(c), views, [&](std::size_t k) { return masks[k]; }, kSpacing,
                              {.instances = true});
    ASSERT_EQ(r.label.size(), c.size());
    // per sphere, how many of its lifted points carry each label
    std::vector<std::map<std::uint32_t, std::size_t>> labels(centres.size() + 1);
    for (std::size_t i = 0; i < c.size(); ++i) {
        EXPECT_EQ(r.label[i] != 0, r.fruit[i] != 0) << i;
        if (r.label[i] != 0) {
            ++labels[id[i]][r.label[i]];
        }
    }
    EXPECT_TRUE(labels[0].empty());  // no ground point is fruit
    std::set<std::uint32_t> majority;
    for (std::size_t k = 1; k <= centres.size(); ++k) {
        std::size_t total = 0, best = 0;
        std::uint32_t best_label = 0;
        for (const auto& [label, n] : labels[k]) {
            total += n;
            if (n > best) {
                best = n;
                best_label = label;
            }
        }
        EXPECT_GT(total, 300u) << k;
        EXPECT_GE(best, total * 98 / 100) << k;
        majority.insert(best_label);
    }
    EXPECT_EQ(majority.size(), centres.size());
    EXPECT_EQ(*majority.rbegin(), centres.size());  // no other label: 1 .. 4
    EXPECT_TRUE(lift(XyzView(c), views, [&](std::size_t k) { return masks[k]; }, kSpacing, {})
                    .label.empty());
}

TEST(Lift, AMaskOfAnotherSizeOrAFailingMaskIsAnErrorNamingTheView) {
    Cloud c;
    c.push_back({0, 0, 0});
    View v = look_at({0, 0.01, 2});
    v.image = "images/a.png";
    const auto bad = [&](std::size_t) { return Mask{10, 10, std::vector<std::uint16_t>(100, 0)}; };
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
