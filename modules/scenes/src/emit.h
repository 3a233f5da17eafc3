#pragma once
// Internal to the scenes module: what render() and the sampled modes share (colour packing, the
// ground and outlier clutter, the final shuffle; small vector algebra from vec3.h).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include <pc/core/random.h>
#include <pc/scenes/render.h>

#include "vec3.h"

namespace pc::scenes::detail {

/// Leaves' colour in natural colours (mask colours paint them near black).
inline constexpr std::array<std::uint8_t, 3> kLeafRgb{60, 125, 45};

/// Packs 0x00RRGGBB from channels rounded and clamped to 0..255.
inline std::uint32_t pack(double r, double g, double b) {
    const auto c = [](double v) {
        return static_cast<std::uint32_t>(std::clamp(std::lround(v), 0L, 255L));
    };
    return (c(r) << 16) | (c(g) << 8) | c(b);
}

inline const Vec3& light() {
    static const Vec3 l = unit({0.3, 0.2, 1.0});
    return l;
}

/// Colours of the sampled modes and the wood: natural (base × tone × shading, ±8 noise, and
/// N(0, color_noise) per channel drawn from the random stream `stream`) or mask (fruit near
/// white, the rest near black).
class Painter {
public:
    Painter(const RenderParams& p, Rng& rng, std::uint64_t stream)
        : p_(p), rng_(rng), noise_(p.seed, stream) {}

    std::uint32_t fruit(const std::array<std::uint8_t, 3>& base, double tone, const Vec3& normal) {
        return paint(base, tone, std::max(0.0, dot(normal, light())), true);
    }
    std::uint32_t wood(const std::array<std::uint8_t, 3>& base, double tone, const Vec3& normal) {
        return paint(base, tone, std::max(0.0, dot(normal, light())), false);
    }
    std::uint32_t leaf(const Vec3& normal) {
        return paint(kLeafRgb, 1.0, std::abs(dot(normal, light())), false);
    }

private:
    std::uint32_t paint(const std::array<std::uint8_t, 3>& base,
                        double tone,
                        double facing,
                        bool is_fruit) {
        if (p_.colors == Colors::kMask) {
            const double c = is_fruit ? rng_.uniform(243, 255) : rng_.uniform(0, 12);
            return pack(c, c, c);
        }
        const double s = tone * (1 - p_.shading * (1 - facing)) * rng_.uniform(0.95, 1.05);
        // blue's noise drawn first, then green's and red's: the order GCC evaluated them in as
        // arguments of one call, which every scene's bytes were written with
        const double nb = rng_.uniform(-8, 8), ng = rng_.uniform(-8, 8), nr = rng_.uniform(-8, 8);
        std::array<double, 3> c{base[0] * s + nr, base[1] * s + ng, base[2] * s + nb};
        if (p_.color_noise > 0) {
            for (double& v : c) {
                v += p_.color_noise * noise_.normal();
            }
        }
        return pack(c[0], c[1], c[2]);
    }

    const RenderParams& p_;
    Rng& rng_;
    Rng noise_;
};

/// Appends one point.
inline void add_point(Rendered& out, const Vec3& p, std::uint32_t rgb, std::uint32_t gt) {
    out.xyz.push_back(
        {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
    out.rgb.push_back(rgb);
    out.gt.push_back(gt);
}

/// Dark ground points (`background` × fruit_total, grey 10-70, or `ground_rgb` when given) on a
/// disc 0.3 m below the canopy and bright sparse outliers (`outliers` × fruit_total) in 1.2 × the
/// canopy box.
void add_ground_and_outliers(
    const Scene& s, const RenderParams& p, std::size_t fruit_total, Rng& rng, Rendered& out);

/// Wood (the scene's branches): points on each branch's side, one per spacing squared, from the
/// stream (seed, 5); each branch exported with probability `wood_leak`. Lattice modes snap them to
/// voxel centres (one per voxel; implicit jitters them as its leaves), sampled modes jitter them
/// by noise × spacing as their leaves. Points inside a fruit are dropped. Natural colours: the
/// bark colour, shaded as fruit are; mask colours: near black.
void add_wood(const Scene& s, const RenderParams& p, Rendered& out);

/// `out` in a fixed shuffle, so that nothing downstream can lean on the generation order, with
/// the points of each of the `fruits` counted.
Rendered shuffled_points(const Rendered& out, std::size_t fruits, Rng& rng);

/// The sampled modes (surface, sfm, stripes, volume): sample.cpp.
Rendered render_sampled(const Scene& s, const RenderParams& p);

}  // namespace pc::scenes::detail
