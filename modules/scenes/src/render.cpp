#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include <pc/core/error.h>
#include <pc/core/names.h>
#include <pc/core/random.h>
#include <pc/scenes/render.h>

#include "cell_key.h"
#include "emit.h"

namespace pc::scenes {

using namespace detail;

namespace {

void require(bool ok, const std::string& what) {
    if (!ok) {
        throw InvalidArgument("render: " + what);
    }
}

/// A voxel of the global lattice: centre ((i + 0.5) v, (j + 0.5) v, (k + 0.5) v).
struct Voxel {
    std::int32_t i, j, k;
    bool surface;  ///< a 6-neighbour lies outside the object
};

Vec3 centre_of(const Voxel& x, double v) {
    return {(x.i + 0.5) * v, (x.j + 0.5) * v, (x.k + 0.5) * v};
}

/// Every lattice voxel whose centre lies inside the fruit (a sphere: distance <= radius).
std::vector<Voxel> fruit_voxels(const Fruit& f, double v) {
    std::vector<Voxel> out;
    const auto half = [&](int a) {
        return f.reach({a == 0 ? 1.0 : 0, a == 1 ? 1.0 : 0, a == 2 ? 1.0 : 0});
    };
    const auto lo = [&](int a) {
        return static_cast<std::int32_t>(std::floor((f.centre[a] - half(a)) / v));
    };
    const auto hi = [&](int a) {
        return static_cast<std::int32_t>(std::floor((f.centre[a] + half(a)) / v));
    };
    const double r2 = f.radius * f.radius;
    const auto inside = [&](std::int32_t i, std::int32_t j, std::int32_t k) {
        const Vec3 q{(i + 0.5) * v, (j + 0.5) * v, (k + 0.5) * v};
        if (!f.round()) {
            return f.level(q) <= 1;
        }
        const Vec3 d = sub(q, f.centre);
        return dot(d, d) <= r2;
    };
    for (std::int32_t i = lo(0); i <= hi(0); ++i) {
        for (std::int32_t j = lo(1); j <= hi(1); ++j) {
            for (std::int32_t k = lo(2); k <= hi(2); ++k) {
                if (inside(i, j, k)) {
                    const bool surface = !inside(i - 1, j, k) || !inside(i + 1, j, k) ||
                                         !inside(i, j - 1, k) || !inside(i, j + 1, k) ||
                                         !inside(i, j, k - 1) || !inside(i, j, k + 1);
                    out.push_back({i, j, k, surface});
                }
            }
        }
    }
    return out;
}

/// The lattice voxels a leaf disc passes through (the plane's distance to the voxel centre within
/// the voxel's half-width along the normal, so rays cannot slip through), minus fruit voxels.
std::vector<Voxel> leaf_voxels(const Leaf& l,
                               double v,
                               const std::unordered_set<std::uint64_t>& fruit) {
    std::vector<Voxel> out;
    const double half =
        0.5 * v * (std::abs(l.normal[0]) + std::abs(l.normal[1]) + std::abs(l.normal[2]));
    const auto lo = [&](int a) {
        return static_cast<std::int32_t>(std::floor((l.centre[a] - l.radius) / v));
    };
    const auto hi = [&](int a) {
        return static_cast<std::int32_t>(std::floor((l.centre[a] + l.radius) / v));
    };
    for (std::int32_t i = lo(0); i <= hi(0); ++i) {
        for (std::int32_t j = lo(1); j <= hi(1); ++j) {
            for (std::int32_t k = lo(2); k <= hi(2); ++k) {
                const Vec3 d = sub({(i + 0.5) * v, (j + 0.5) * v, (k + 0.5) * v}, l.centre);
                const double h = dot(d, l.normal);
                if (std::abs(h) <= half && dot(d, d) - h * h <= l.radius * l.radius &&
                    !fruit.contains(cell_key(i, j, k))) {
                    out.push_back({i, j, k, true});
                }
            }
        }
    }
    return out;
}

/// Adds points with colours; owns the colour model.
class Output {
public:
    Output(Rendered& out, Rng& rng, Colors colors) : out_(out), rng_(rng), colors_(colors) {}
    void add(const Vec3& p, std::uint32_t rgb, std::uint32_t gt) { add_point(out_, p, rgb, gt); }
    [[nodiscard]] Rendered& points() { return out_; }
    /// A base colour under sun and shade: per-point brightness 0.92..1.08 (times `tone`), ±8 noise.
    std::uint32_t shade(const std::array<std::uint8_t, 3>& base, double tone = 1.0) {
        if (colors_ == Colors::kMask) {  // a semantic export: fruit white, leaves black
            const double c = base == kLeafRgb ? rng_.uniform(0, 12) : rng_.uniform(243, 255);
            return pack(c, c, c);
        }
        const double s = tone * rng_.uniform(0.92, 1.08);
        return pack(base[0] * s + rng_.uniform(-8, 8), base[1] * s + rng_.uniform(-8, 8),
                    base[2] * s + rng_.uniform(-8, 8));
    }

private:
    Rendered& out_;
    Rng& rng_;
    Colors colors_;
};

/// Pinhole cameras on three rings (elevation 5°, 30°, 60°) around the canopy, looking at its
/// centre; a z-buffer each.
class Cameras {
public:
    Cameras(const Scene& s, const RenderParams& p) : voxel_(p.voxel) {
        const double reach = *std::max_element(s.canopy.begin(), s.canopy.end());
        distance_ = 2.5 * reach;
        focal_ = distance_ / voxel_;  // one pixel per voxel at the canopy centre
        const double half_angle = std::asin(std::min(0.95, 1.15 * reach / distance_)) + 0.05;
        half_width_ = static_cast<int>(std::ceil(focal_ * std::tan(half_angle)));
        if (half_width_ > 2048) {  // tiny voxels: cap the image, splats grow instead
            focal_ *= 2048.0 / half_width_;
            half_width_ = 2048;
        }
        for (std::uint32_t c = 0; c < p.cameras; ++c) {
            const double elevation = (c % 3 == 0 ? 5.0 : c % 3 == 1 ? 30.0 : 60.0) * kPi / 180;
            const double azimuth = 2 * kPi * c / p.cameras;
            const Vec3 eye{distance_ * std::cos(elevation) * std::cos(azimuth),
                           distance_ * std::cos(elevation) * std::sin(azimuth),
                           distance_ * std::sin(elevation)};
            View w;
            w.eye = eye;
            w.forward = unit(scaled(eye, -1));
            w.right = unit(cross(w.forward, {0, 0, 1}));
            w.up = cross(w.right, w.forward);
            views_.push_back(w);
        }
    }

    [[nodiscard]] std::size_t size() const { return views_.size(); }

    /// Adds 1 to `seen[n]` for every target voxel visible from camera `c`.
    void count_visible(std::size_t c,
                       const std::vector<Vec3>& occluders,
                       const std::vector<Vec3>& targets,
                       std::vector<std::uint32_t>& seen) const {
        const View& w = views_[c];
        const int width = 2 * half_width_ + 1;
        std::vector<float> zbuf(static_cast<std::size_t>(width) * width,
                                std::numeric_limits<float>::infinity());
        const double reach = 0.5 * std::sqrt(3.0) * voxel_ * focal_;
        for (const Vec3& p : occluders) {
            Projection q;
            if (!project(w, p, q)) {
                continue;
            }
            const int h = std::max(1, static_cast<int>(std::ceil(reach / q.z)));
            for (int y = std::max(0, q.y - h); y <= std::min(width - 1, q.y + h); ++y) {
                for (int x = std::max(0, q.x - h); x <= std::min(width - 1, q.x + h); ++x) {
                    float& z = zbuf[static_cast<std::size_t>(y) * width + x];
                    z = std::min(z, static_cast<float>(q.z));
                }
            }
        }
        for (std::size_t n = 0; n < targets.size(); ++n) {
            Projection q;
            if (project(w, targets[n], q) && q.x >= 0 && q.y >= 0 && q.x < width && q.y < width &&
                q.z <= zbuf[static_cast<std::size_t>(q.y) * width + q.x] + voxel_) {
                ++seen[n];
            }
        }
    }

private:
    struct View {
        Vec3 eye, forward, right, up;
    };
    struct Projection {
        int x = 0, y = 0;
        double z = 0;
    };
    bool project(const View& w, const Vec3& p, Projection& q) const {
        const Vec3 d = sub(p, w.eye);
        q.z = dot(d, w.forward);
        if (q.z <= voxel_) {
            return false;
        }
        q.x = half_width_ + static_cast<int>(std::lround(focal_ * dot(d, w.right) / q.z));
        q.y = half_width_ - static_cast<int>(std::lround(focal_ * dot(d, w.up) / q.z));
        return true;
    }

    double voxel_, distance_ = 0, focal_ = 0;
    int half_width_ = 0;
    std::vector<View> views_;
};

/// Degraded masks: keeps the fraction `keep` of a fruit's voxels nearest to 1-3 random spots on its
/// surface (the parts the masks caught), so small fractions come out as separate fragments.
std::vector<Voxel> degrade(
    const Fruit& f, const std::vector<Voxel>& voxels, double keep, double v, Rng& rng) {
    const auto spots = 1 + rng.below(3);
    std::vector<Vec3> at;
    for (std::uint64_t s = 0; s < spots; ++s) {
        at.push_back(f.at(rng.direction(), f.radius));
    }
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t n = 0; n < voxels.size(); ++n) {
        const Vec3 c = centre_of(voxels[n], v);
        double best = std::numeric_limits<double>::infinity();
        for (const Vec3& a : at) {
            const Vec3 d = sub(c, a);
            best = std::min(best, dot(d, d));
        }
        order.emplace_back(best, n);
    }
    std::sort(order.begin(), order.end());
    const auto kept =
        static_cast<std::size_t>(std::llround(keep * static_cast<double>(voxels.size())));
    std::vector<Voxel> out;
    for (std::size_t n = 0; n < kept; ++n) {
        out.push_back(voxels[order[n].second]);
    }
    return out;
}

/// Noise bridges: NeRF fills the occluded crevice between touching fruit with loose density. Points
/// fill the space between the two fruit within 0.6 × the smaller radius of their axis (spheroids:
/// their half widths along the axis stand for the radii).
void add_bridges(const Scene& s, const RenderParams& p, Rng& rng, Output& out) {
    std::vector<std::uint32_t> order(s.fruits.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](auto a, auto b) { return s.fruits[a].centre[0] < s.fruits[b].centre[0]; });
    double r_max = 0;
    for (const auto& f : s.fruits) {
        r_max = std::max(r_max, f.largest());
    }
    for (std::size_t a = 0; a < order.size(); ++a) {
        const Fruit& fa = s.fruits[order[a]];
        for (std::size_t b = a + 1; b < order.size(); ++b) {
            const Fruit& fb = s.fruits[order[b]];
            if (fb.centre[0] - fa.centre[0] > fa.largest() + r_max * (1 + p.bridge_gap)) {
                break;
            }
            const Vec3 axis = sub(fb.centre, fa.centre);
            const double length = std::sqrt(dot(axis, axis));
            const Vec3 d = scaled(axis, 1.0 / length);
            const double ra = fa.reach(d), rb = fb.reach(d);
            const double small = std::min(ra, rb);
            if (length - ra - rb >= p.bridge_gap * small || rng.uniform() >= p.bridge_probability) {
                continue;
            }
            const auto [e1, e2] = basis(d);
            const double reach = 0.6 * small;
            const auto n = static_cast<int>(
                std::ceil(rng.uniform(0.5, 1.0) * kPi * reach * reach / (p.voxel * p.voxel)));
            const std::uint32_t rgb = out.shade(s.fruit_rgb, 0.85);
            for (int k = 0; k < n; ++k) {
                const double rho = reach * std::sqrt(rng.uniform()), phi = rng.uniform(0, 2 * kPi);
                const double from = std::sqrt(ra * ra - rho * rho);
                const double to = length - std::sqrt(rb * rb - rho * rho);
                const double t = rng.uniform(from, std::max(from, to));
                Vec3 q = fa.centre;
                for (int c = 0; c < 3; ++c) {
                    q[c] += t * d[c] + rho * (std::cos(phi) * e1[c] + std::sin(phi) * e2[c]);
                }
                out.add(q, rgb, 0);
            }
        }
    }
}

}  // namespace

namespace {

constexpr std::pair<std::string_view, Mode> kModes[] = {
    {"explicit", Mode::kExplicit}, {"implicit", Mode::kImplicit}, {"degraded", Mode::kDegraded},
    {"surface", Mode::kSurface},   {"sfm", Mode::kSfm},           {"stripes", Mode::kStripes},
    {"volume", Mode::kVolume}};
constexpr std::pair<std::string_view, Colors> kColors[] = {{"natural", Colors::kNatural},
                                                           {"mask", Colors::kMask}};

}  // namespace

Mode parse_mode(const std::string& text) { return parse_name<Mode>(kModes, text, "--mode"); }

std::string mode_name(Mode mode) { return name_of<Mode>(kModes, mode); }

Colors parse_colors(const std::string& text) {
    return parse_name<Colors>(kColors, text, "--colors");
}

std::string colors_name(Colors colors) { return name_of<Colors>(kColors, colors); }

void RenderParams::validate() const {
    require(voxel >= 1e-5 && voxel <= 1.0, "voxel must be in [1e-5, 1]");
    require(cameras >= 1 && cameras <= 1000, "cameras must be in 1..1000");
    require(min_views >= 1 && min_views <= cameras, "min_views must be in 1..cameras");
    require(surface_noise >= 0 && surface_noise <= 10, "surface_noise must be in [0, 10] voxels");
    require(bridge_gap >= 0 && bridge_gap <= 10, "bridge_gap must be in [0, 10]");
    require(bridge_probability >= 0 && bridge_probability <= 1,
            "bridge_probability must be in [0, 1]");
    require(floaters >= 0 && floaters <= 100, "floaters must be in [0, 100] per fruit");
    require(recall > 0 && recall <= 1, "recall must be in (0, 1]");
    require(leaf_leak >= 0 && leaf_leak <= 1, "leaf_leak must be in [0, 1]");
    require(background >= 0 && background <= 100, "background must be in [0, 100]");
    require(outliers >= 0 && outliers <= 100, "outliers must be in [0, 100]");
    require(wood_leak >= 0 && wood_leak <= 1, "wood_leak must be in [0, 1]");
    require(noise >= 0 && noise <= 1, "noise must be in [0, 1] radii");
    require(holes >= 0 && holes <= 20, "holes must be in [0, 20] per fruit");
    require(duplicates >= 0 && duplicates <= 1, "duplicates must be in [0, 1]");
    require(density_spread >= 0 && density_spread <= 3, "density_spread must be in [0, 3]");
    require(shading >= 0 && shading <= 1, "shading must be in [0, 1]");
    require(color_noise >= 0 && color_noise <= 255, "color_noise must be in [0, 255]");
    require(scale > 0 && std::isfinite(scale) && scale <= 1e6, "scale must be in (0, 1e6]");
    for (double o : offset) {
        require(std::isfinite(o) && std::abs(o) <= 1e6, "offset must be finite, |offset| <= 1e6");
    }
}

namespace {

/// The implicit mode's fruit: surface voxels seen by at least min_views of the cameras (leaves
/// occlude), kept with probability views / 4 and jittered, bridges between close fruit, and
/// fruit-coloured floaters.
void render_implicit(const Scene& s,
                     const RenderParams& p,
                     const std::vector<std::vector<Voxel>>& fruit,
                     const std::vector<std::vector<Voxel>>& leaves,
                     const std::vector<double>& tone,
                     Rng& rng,
                     Output& emit) {
    const double v = p.voxel;
    std::vector<Vec3> occluders, targets;
    std::vector<std::uint32_t> owner;
    for (std::size_t f = 0; f < fruit.size(); ++f) {
        for (const auto& x : fruit[f]) {
            if (x.surface) {
                targets.push_back(centre_of(x, v));
                owner.push_back(static_cast<std::uint32_t>(f));
            }
        }
    }
    occluders = targets;
    for (const auto& l : leaves) {
        for (const auto& x : l) {
            occluders.push_back(centre_of(x, v));
        }
    }
    const Cameras cams(s, p);
    std::vector<std::uint32_t> seen(targets.size(), 0);
#pragma omp parallel
    {
        std::vector<std::uint32_t> mine(targets.size(), 0);
#pragma omp for schedule(dynamic, 1)
        for (std::int64_t c = 0; c < static_cast<std::int64_t>(cams.size()); ++c) {
            cams.count_visible(static_cast<std::size_t>(c), occluders, targets, mine);
        }
#pragma omp critical
        for (std::size_t n = 0; n < seen.size(); ++n) {
            seen[n] += mine[n];  // integer sums: the same in any order
        }
    }
    const double sigma = p.surface_noise * v;
    for (std::size_t n = 0; n < targets.size(); ++n) {
        // Seen from fewer views, NeRF's surface is thinner: keep with probability views / 4.
        const double keep = seen[n] >= p.min_views ? std::min(1.0, seen[n] / 4.0) : 0.0;
        const double draw = rng.uniform();
        Vec3 q = targets[n];
        for (auto& c : q) {
            c += sigma * rng.normal();
        }
        if (draw < keep) {
            emit.add(q, emit.shade(s.fruit_colour(owner[n], q), tone[owner[n]]), owner[n] + 1);
        }
    }
    add_bridges(s, p, rng, emit);
    const auto blobs =
        static_cast<std::uint64_t>(std::llround(p.floaters * static_cast<double>(s.fruits.size())));
    for (std::uint64_t b = 0; b < blobs; ++b) {
        const Vec3 d = rng.direction();
        const double u = std::cbrt(rng.uniform());
        const Vec3 c{u * d[0] * s.canopy[0], u * d[1] * s.canopy[1], u * d[2] * s.canopy[2]};
        const auto n = 5 + rng.below(30);
        const std::uint32_t rgb = emit.shade(s.fruit_rgb, 0.9);
        for (std::uint64_t k = 0; k < n; ++k) {
            emit.add({c[0] + 0.006 * rng.normal(), c[1] + 0.006 * rng.normal(),
                      c[2] + 0.006 * rng.normal()},
                     rgb, 0);
        }
    }
}

/// The explicit and degraded modes' fruit: every voxel (explicit), or those the degraded masks
/// keep for each fruit.
void render_solid(const Scene& s,
                  const RenderParams& p,
                  const std::vector<std::vector<Voxel>>& fruit,
                  const std::vector<double>& tone,
                  Rng& rng,
                  Output& emit) {
    const double v = p.voxel;
    for (std::size_t f = 0; f < fruit.size(); ++f) {
        std::vector<Voxel> kept = fruit[f];
        if (p.mode == Mode::kDegraded) {
            // Per-fruit recall uniform in recall ± 0.4; below 0.15 the masks missed the fruit.
            const double r = std::clamp(p.recall + rng.uniform(-0.4, 0.4), 0.0, 1.0);
            kept = r < 0.15 ? std::vector<Voxel>{} : degrade(s.fruits[f], fruit[f], r, v, rng);
        }
        for (const auto& x : kept) {
            const Vec3 q = centre_of(x, v);
            emit.add(q, emit.shade(s.fruit_colour(f, q), tone[f]),
                     static_cast<std::uint32_t>(f + 1));
        }
    }
}

/// Clutter: leaked leaves, dark ground and bright sparse outliers, in proportion to the
/// `fruit_total` fruit points.
void add_clutter(const Scene& s,
                 const RenderParams& p,
                 const std::vector<std::vector<Voxel>>& leaves,
                 std::size_t fruit_total,
                 Rng& rng,
                 Output& emit) {
    const double v = p.voxel;
    const double jitter = p.mode == Mode::kImplicit ? p.surface_noise * v : 0.0;
    for (const auto& l : leaves) {
        if (rng.uniform() >= p.leaf_leak) {
            continue;
        }
        for (const auto& x : l) {
            Vec3 q = centre_of(x, v);
            for (auto& c : q) {
                c += jitter * rng.normal();
            }
            emit.add(q, emit.shade(kLeafRgb), 0);
        }
    }
    add_ground_and_outliers(s, p, fruit_total, rng, emit.points());
}

}  // namespace

namespace {

/// Fruit of a bunch may interpenetrate: a voxel inside two of them belongs to the one it lies
/// deeper in (a sphere: whose centre is nearer relative to its radius).
void give_shared_voxels_to_one(const Scene& s, double v, std::vector<std::vector<Voxel>>& fruit) {
    std::unordered_map<std::uint64_t, std::pair<double, std::size_t>> owner;
    const auto score = [&](std::size_t f, const Voxel& x) {
        return s.fruits[f].level(centre_of(x, v));
    };
    for (std::size_t f = 0; f < fruit.size(); ++f) {
        for (const auto& x : fruit[f]) {
            const auto [it, added] = owner.try_emplace(cell_key(x.i, x.j, x.k), score(f, x), f);
            if (!added && score(f, x) < it->second.first) {
                it->second = {score(f, x), f};
            }
        }
    }
    for (std::size_t f = 0; f < fruit.size(); ++f) {
        std::erase_if(fruit[f], [&](const Voxel& x) {
            return owner.at(cell_key(x.i, x.j, x.k)).second != f;
        });
    }
}

Rendered render_lattice(const Scene& s, const RenderParams& p) {
    const double v = p.voxel;
    double r_min = std::numeric_limits<double>::infinity();
    for (const auto& f : s.fruits) {
        r_min = std::min(r_min, f.smallest());
    }
    require(s.fruits.empty() || r_min >= v,
            "the voxel must not be larger than the smallest fruit radius (half axis)");
    Rendered out;
    Rng rng(p.seed, 2);
    Output emit(out, rng, p.colors);

    std::vector<std::vector<Voxel>> fruit(s.fruits.size());
    std::unordered_set<std::uint64_t> occupied;
    for (std::size_t f = 0; f < s.fruits.size(); ++f) {
        fruit[f] = fruit_voxels(s.fruits[f], v);
        for (const auto& x : fruit[f]) {
            occupied.insert(cell_key(x.i, x.j, x.k));
        }
    }
    give_shared_voxels_to_one(s, v, fruit);
    std::vector<std::vector<Voxel>> leaves(s.leaves.size());
    for (std::size_t l = 0; l < s.leaves.size(); ++l) {
        leaves[l] = leaf_voxels(s.leaves[l], v, occupied);
    }
    occupied.clear();

    std::vector<double> tone(s.fruits.size());
    for (auto& t : tone) {
        t = rng.uniform(0.95, 1.05);
    }
    if (p.mode == Mode::kImplicit) {
        render_implicit(s, p, fruit, leaves, tone, rng, emit);
    } else {
        render_solid(s, p, fruit, tone, rng, emit);
    }
    add_clutter(s, p, leaves, out.xyz.size(), rng, emit);
    add_wood(s, p, out);
    return shuffled_points(out, s.fruits.size(), rng);
}

}  // namespace

Rendered render(const Scene& s, const RenderParams& p) {
    p.validate();
    Rendered out =
        p.mode == Mode::kExplicit || p.mode == Mode::kImplicit || p.mode == Mode::kDegraded
            ? render_lattice(s, p)
            : render_sampled(s, p);
    if (p.scale != 1 || p.offset != Vec3{0, 0, 0}) {
        for (auto& q : out.xyz) {
            for (int a = 0; a < 3; ++a) {
                q[a] = static_cast<float>(static_cast<double>(q[a]) * p.scale + p.offset[a]);
            }
        }
    }
    return out;
}

io::Blob to_blob(const Rendered& r) {
    io::Blob b;
    std::uint32_t offset = 0;
    for (const char* name : {"x", "y", "z", "rgb", "gt_instance"}) {
        pcl::PCLPointField f;
        f.name = name;
        f.offset = offset;
        f.datatype = offset < 12 ? pcl::PCLPointField::FLOAT32 : pcl::PCLPointField::UINT32;
        f.count = 1;
        b.cloud.fields.push_back(f);
        offset += 4;
    }
    const std::size_t n = r.xyz.size();
    b.cloud.width = static_cast<std::uint32_t>(n);
    b.cloud.height = 1;
    b.cloud.point_step = offset;
    b.cloud.row_step = static_cast<std::uint32_t>(offset * n);
    b.cloud.is_dense = true;
    b.cloud.data.resize(offset * n);
    std::uint8_t* d = b.cloud.data.data();
    for (std::size_t k = 0; k < n; ++k, d += offset) {
        std::memcpy(d, r.xyz[k].data(), 12);
        std::memcpy(d + 12, &r.rgb[k], 4);
        std::memcpy(d + 16, &r.gt[k], 4);
    }
    return b;
}

}  // namespace pc::scenes
