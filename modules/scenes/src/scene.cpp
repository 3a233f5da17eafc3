#include <algorithm>
#include <cmath>

#include <pc/core/error.h>
#include <pc/core/random.h>
#include <pc/scenes/scene.h>

#include "cell_key.h"
#include "vec3.h"

namespace pc::scenes {

using namespace detail;

namespace {

void require(bool ok, const std::string& what) {
    if (!ok) {
        throw InvalidArgument("scene: " + what);
    }
}

double dist2(const Vec3& a, const Vec3& b) {
    const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return dx * dx + dy * dy + dz * dz;
}

// A spheroid's half axes: equatorial e = radius / cbrt(aspect) (twice), polar e × aspect, so that
// its volume is the sphere's of `radius`. Every function keeps a sphere's arithmetic as it was.
double equatorial(const Fruit& f) { return f.radius / std::cbrt(f.aspect); }

/// How far the ray from `from` (inside the canopy ellipsoid scaled by `fraction`) along the unit
/// `d` runs before it leaves that ellipsoid: the larger root of |(from + t d) / canopy| = fraction.
double to_canopy_edge(const Vec3& from, const Vec3& d, const Vec3& canopy, double fraction) {
    double a = 0, b = 0, c = -fraction * fraction;
    for (int k = 0; k < 3; ++k) {
        const double f = from[k] / canopy[k], g = d[k] / canopy[k];
        a += g * g;
        b += 2 * f * g;
        c += f * f;
    }
    return (-b + std::sqrt(std::max(0.0, b * b - 4 * a * c))) / (2 * a);
}

/// The trunk from the ground to a fork at 0.3 of the canopy's height below its centre, main
/// branches spread around it rising 15-60 degrees to 0.85 of the canopy, two side branches from
/// each (from 0.3-0.8 of its length, towards it give or take 0.9 of a random direction, a quarter
/// to nearly half the canopy long, inside 0.95 of it) ending in twigs.
std::vector<Branch> grow_wood(const SceneParams& p) {
    Rng rng(p.seed, 4);
    const double trunk = p.trunk_radius, twig = std::min(0.004, 0.2 * trunk);
    const Vec3 fork{0, 0, -0.3 * p.canopy[2]};
    std::vector<Branch> wood{{{0, 0, -p.canopy[2] - 0.3}, fork, trunk, 0.8 * trunk}};
    const double reach = (p.canopy[0] + p.canopy[1] + p.canopy[2]) / 3;
    const auto along = [](const Vec3& from, const Vec3& d, double t) {
        return Vec3{from[0] + t * d[0], from[1] + t * d[1], from[2] + t * d[2]};
    };
    for (std::uint32_t b = 0; b < p.branches; ++b) {
        const double azimuth = 2 * kPi * (b + rng.uniform(-0.3, 0.3)) / p.branches;
        const double elevation = rng.uniform(15, 60) * kPi / 180;
        const Vec3 d{std::cos(elevation) * std::cos(azimuth),
                     std::cos(elevation) * std::sin(azimuth), std::sin(elevation)};
        const Branch main{fork, along(fork, d, to_canopy_edge(fork, d, p.canopy, 0.85)),
                          0.5 * trunk * rng.uniform(0.8, 1.2), 0.15 * trunk};
        wood.push_back(main);
        for (int side = 0; side < 2; ++side) {
            const double t = rng.uniform(0.3, 0.8);
            const Vec3 from = along(main.from, sub(main.to, main.from), t);
            const Vec3 r = rng.direction();
            const Vec3 e = unit(along(d, r, 0.9));
            const double length =
                std::min(rng.uniform(0.25, 0.45) * reach, to_canopy_edge(from, e, p.canopy, 0.95));
            wood.push_back({from, along(from, e, length),
                            0.6 * (main.r_from + t * (main.r_to - main.r_from)), twig});
        }
    }
    return wood;
}

}  // namespace

Vec3 Fruit::at(const Vec3& d, double depth) const {
    if (round()) {
        return {centre[0] + depth * d[0], centre[1] + depth * d[1], centre[2] + depth * d[2]};
    }
    const double e = equatorial(*this), s = depth / radius, along = dot(d, axis);
    Vec3 q;
    for (int k = 0; k < 3; ++k) {
        q[k] = centre[k] + s * (e * (d[k] - along * axis[k]) + e * aspect * along * axis[k]);
    }
    return q;
}

Vec3 Fruit::normal(const Vec3& d) const {
    if (round()) {
        return d;
    }
    const double e = equatorial(*this), along = dot(d, axis);
    Vec3 n;
    for (int k = 0; k < 3; ++k) {
        n[k] = (d[k] - along * axis[k]) / e + along * axis[k] / (e * aspect);
    }
    const double length = std::sqrt(dot(n, n));
    return {n[0] / length, n[1] / length, n[2] / length};
}

double Fruit::level(const Vec3& q) const {
    const Vec3 v = sub(q, centre);
    if (round()) {
        return std::sqrt(dot(v, v)) / radius;
    }
    const double e = equatorial(*this), along = dot(v, axis);
    const double across = std::max(0.0, dot(v, v) - along * along);
    return std::sqrt(across / (e * e) + along * along / (e * e * aspect * aspect));
}

double Fruit::reach(const Vec3& u) const {
    if (round()) {
        return radius;
    }
    const double e = equatorial(*this), along = dot(u, axis);
    const double across = std::max(0.0, dot(u, u) - along * along);
    return e * std::sqrt(across + aspect * aspect * along * along);
}

double Fruit::largest() const {
    return round() ? radius : equatorial(*this) * std::max(1.0, aspect);
}

double Fruit::smallest() const {
    return round() ? radius : equatorial(*this) * std::min(1.0, aspect);
}

double Fruit::area() const {
    if (round()) {
        return 4 * kPi * radius * radius;
    }
    constexpr double p = 1.6075;
    const double e = std::pow(equatorial(*this), p), c = e * std::pow(aspect, p);
    return 4 * kPi * std::pow((e * e + 2 * e * c) / 3, 1 / p);
}

void SceneParams::validate() const {
    require(fruit_count >= 1 && fruit_count <= 1000000, "fruit_count must be in 1..1000000");
    require(fruit_radius > 0 && std::isfinite(fruit_radius), "fruit_radius must be > 0");
    require(radius_spread >= 0 && radius_spread < 1, "radius_spread must be in [0, 1)");
    require(bunch_min >= 1 && bunch_min <= bunch_max && bunch_max <= 1000,
            "bunch sizes must satisfy 1 <= bunch_min <= bunch_max <= 1000");
    require(touch_gap >= 0 && std::isfinite(touch_gap), "touch_gap must be >= 0");
    require(overlap >= 0 && overlap <= 0.5, "overlap must be in [0, 0.5]");
    require(separation >= 0 && std::isfinite(separation), "separation must be >= 0");
    for (double a : canopy) {
        require(a > 0 && std::isfinite(a), "canopy half axes must be > 0");
    }
    require(shell >= 0 && shell < 1, "shell must be in [0, 1)");
    require(leaf_density >= 0 && leaf_density <= 1e6, "leaf_density must be in [0, 1e6]");
    require(leaf_radius > 0 && std::isfinite(leaf_radius), "leaf_radius must be > 0");
    require(aspect >= 0.25 && aspect <= 4, "aspect must be in [0.25, 4]");
    require(aspect_spread >= 0 && aspect_spread < 1, "aspect_spread must be in [0, 1)");
    require(branches <= 100, "branches must be in 0..100");
    require(trunk_radius > 0 && trunk_radius <= 1, "trunk_radius must be in (0, 1] m");
    require(blush_min >= 0 && blush_min <= blush_max && blush_max <= 1,
            "blush shares must satisfy 0 <= blush_min <= blush_max <= 1");
}

const std::array<std::uint8_t, 3>& Scene::fruit_colour(std::size_t f, const Vec3& q) const {
    const Fruit& x = fruits[f];
    if (x.blush_from > 1) {
        return fruit_rgb;
    }
    const Vec3 d = sub(q, x.centre);
    return dot(d, x.blush_side) >= x.blush_from * std::sqrt(dot(d, d)) ? blush_rgb : fruit_rgb;
}

const std::vector<std::string>& species_names() {
    static const std::vector<std::string> names = {"peach", "apple", "plum"};
    return names;
}

SceneParams species(std::string_view name) {
    SceneParams p;
    if (name == "peach") {  // 152 fruit, well separated (paper Table 2)
        p.fruit_count = 152;
        p.fruit_radius = 0.035;
        p.separation = 0.03;
        p.canopy = {1.0, 1.0, 0.8};
        p.fruit_rgb = {240, 165, 95};
        return p;
    }
    if (name == "apple") {  // 283 fruit, moderately clustered: bunches of 1 to 3, 0-15 mm apart
        p.fruit_count = 283;
        p.fruit_radius = 0.035;
        p.bunch_max = 3;
        p.touch_gap = 0.015;  // fruit of a bunch hang close, only some touch
        p.separation = 0.02;
        p.canopy = {1.2, 1.2, 1.0};
        p.fruit_rgb = {232, 118, 88};
        return p;
    }
    if (name == "plum") {  // 745 fruit, dense bunches of 3 to 8 touching fruit
        p.fruit_count = 745;
        p.fruit_radius = 0.017;
        p.bunch_min = 3;
        p.bunch_max = 8;
        p.separation = 0.02;
        p.canopy = {1.0, 1.0, 0.9};
        p.fruit_rgb = {195, 105, 155};
        return p;
    }
    throw InvalidArgument("--species: unknown species '" + std::string(name) +
                          "' (peach, apple, plum)");
}

Scene make_scene(const SceneParams& p) {
    p.validate();
    Rng rng(p.seed, 1);
    Scene s;
    s.canopy = p.canopy;
    s.fruit_rgb = p.fruit_rgb;
    const bool round = p.aspect == 1 && p.aspect_spread == 0;
    // the largest half axis a fruit can have: the polar one of the longest prolate, the equatorial
    // one of the flattest oblate
    const double stretch = round ? 1.0
                                 : std::max(std::pow(p.aspect * (1 + p.aspect_spread), 2.0 / 3),
                                            1 / std::cbrt(p.aspect * (1 - p.aspect_spread)));
    const double r_max = p.fruit_radius * (1 + p.radius_spread) * stretch;
    FruitGrid grid(2 * r_max + std::max(p.separation, p.touch_gap));
    const auto inside_canopy = [&](const Vec3& c, double scale) {
        double q = 0;
        for (int a = 0; a < 3; ++a) {
            q += (c[a] / p.canopy[a]) * (c[a] / p.canopy[a]);
        }
        return q <= scale * scale;
    };
    // Fruit that do not meet: their centres at least the sum of their half widths along the line
    // between them apart (a plane across that line then parts them; exact for spheres, a little
    // apart at most for spheroids), less the overlap in a bunch, plus the separation between
    // bunches.
    const auto fits = [&](const Fruit& x) {
        bool ok = true;
        grid.for_near(x.centre, [&](std::uint32_t i) {
            const Fruit& f = s.fruits[i];
            Vec3 u{};
            if (!x.round() || !f.round()) {
                const double length = std::sqrt(dist2(x.centre, f.centre));
                for (int a = 0; a < 3; ++a) {
                    u[a] = (x.centre[a] - f.centre[a]) / length;  // NaN when they coincide: no fit
                }
            }
            const double need =
                x.reach(u) + f.reach(u) +
                (f.bunch == x.bunch ? -p.overlap * std::min(x.radius, f.radius) : p.separation);
            ok = ok && dist2(x.centre, f.centre) >= need * need;
        });
        return ok;
    };
    const auto place = [&](const Fruit& x) {
        s.fruits.push_back(x);
        grid.add(s.fruits.back().centre, static_cast<std::uint32_t>(s.fruits.size() - 1));
    };
    // A new fruit's size and shape (spheres draw no shape, so their scenes stay as they were).
    const auto shaped = [&](std::uint32_t bunch) {
        Fruit x;
        x.radius = p.fruit_radius * (1 + p.radius_spread * rng.uniform(-1, 1));
        x.bunch = bunch;
        if (!round) {
            x.aspect = p.aspect * (1 + p.aspect_spread * rng.uniform(-1, 1));
            x.axis = rng.direction();
        }
        return x;
    };
    const double shell3 = p.shell * p.shell * p.shell;
    while (s.fruits.size() < p.fruit_count) {
        const auto left = p.fruit_count - s.fruits.size();
        const auto size =
            std::min<std::uint64_t>(left, p.bunch_min + rng.below(p.bunch_max - p.bunch_min + 1));
        const std::uint32_t bunch = s.bunch_count;
        const std::size_t first = s.fruits.size();
        for (int attempt = 0;; ++attempt) {
            if (attempt == 20000) {
                throw InvalidArgument("scene: cannot place " + std::to_string(p.fruit_count) +
                                      " fruit of radius " + format_number(p.fruit_radius) +
                                      " in the canopy (placed " + std::to_string(first) +
                                      "); enlarge the canopy or lower the fruit count");
            }
            const Vec3 d = rng.direction();
            const double u = std::cbrt(rng.uniform(shell3, 1.0));  // uniform in the shell's volume
            Fruit x = shaped(bunch);
            x.centre = {u * d[0] * p.canopy[0], u * d[1] * p.canopy[1], u * d[2] * p.canopy[2]};
            if (fits(x)) {
                place(x);
                break;
            }
        }
        for (std::uint64_t k = 1; k < size; ++k) {
            for (int attempt = 0; attempt < 200; ++attempt) {
                const Fruit m = s.fruits[first + rng.below(s.fruits.size() - first)];
                const Vec3 d = rng.direction();
                Fruit x = shaped(bunch);
                const double at =
                    m.reach(d) + x.reach(d) +
                    rng.uniform(-p.overlap * std::min(m.radius, x.radius), p.touch_gap);
                x.centre = {m.centre[0] + at * d[0], m.centre[1] + at * d[1],
                            m.centre[2] + at * d[2]};
                if (inside_canopy(x.centre, 1.1) && fits(x)) {
                    place(x);
                    break;
                }
            }  // a bunch that cannot grow stays smaller; the next bunch takes the remaining fruit
        }
        ++s.bunch_count;
    }
    const double volume = 4.0 / 3.0 * 3.141592653589793 * p.canopy[0] * p.canopy[1] * p.canopy[2];
    const auto leaves = static_cast<std::uint64_t>(std::llround(p.leaf_density * volume));
    for (std::uint64_t k = 0; k < leaves; ++k) {
        const Vec3 d = rng.direction();
        const double u = std::cbrt(rng.uniform());
        s.leaves.push_back(
            {{u * d[0] * p.canopy[0], u * d[1] * p.canopy[1], u * d[2] * p.canopy[2]},
             rng.direction(),
             p.leaf_radius * rng.uniform(0.7, 1.3)});
    }
    if (p.branches > 0) {
        s.branches = grow_wood(p);
        s.wood_rgb = p.wood_rgb;
    }
    if (p.blush_max > 0) {
        // A cap of the unit sphere whose cosine is at least c holds (1 - c) / 2 of its area.
        Rng blush(p.seed, 6);
        s.blush_rgb = p.blush_rgb;
        for (Fruit& x : s.fruits) {
            x.blush_side = blush.direction();
            x.blush_from = 1 - 2 * blush.uniform(p.blush_min, p.blush_max);
        }
    }
    return s;
}

}  // namespace pc::scenes
