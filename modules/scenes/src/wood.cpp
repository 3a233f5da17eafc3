// Wood: the trunk and branches of make_scene() as points, in every mode.
#include <unordered_set>

#include "cell_key.h"
#include "emit.h"

namespace pc::scenes::detail {

void add_wood(const Scene& s, const RenderParams& p, Rendered& out) {
    if (s.branches.empty()) {
        return;
    }
    Rng rng(p.seed, 5);
    const double v = p.voxel;
    const bool lattice =
        p.mode == Mode::kExplicit || p.mode == Mode::kImplicit || p.mode == Mode::kDegraded;
    const double jitter = p.mode == Mode::kImplicit ? p.surface_noise * v
                          : lattice                 ? 0.0
                                                    : p.noise * v;
    double widest_fruit = 1e-9;
    for (const auto& f : s.fruits) {
        widest_fruit = std::max(widest_fruit, 2 * f.largest());
    }
    FruitGrid fruit(widest_fruit);
    for (std::size_t f = 0; f < s.fruits.size(); ++f) {
        fruit.add(s.fruits[f].centre, static_cast<std::uint32_t>(f));
    }
    Painter paint(p, rng, 8);
    std::unordered_set<std::uint64_t> taken;  // lattice: one point per voxel
    for (const Branch& b : s.branches) {
        if (rng.uniform() >= p.wood_leak) {
            continue;
        }
        const Vec3 axis = sub(b.to, b.from);
        const double length = std::sqrt(dot(axis, axis)), widest = std::max(b.r_from, b.r_to);
        const auto [e1, e2] = basis(scaled(axis, 1 / length));
        const double tone = rng.uniform(0.85, 1.1);
        // the side's area (a thin cone: its slant is its length); the lattice draws 4 a voxel so
        // that nearly every voxel the surface passes through is hit
        const double area = kPi * (b.r_from + b.r_to) * length;
        for (auto n = std::llround(area / (v * v) * (lattice ? 4 : 1)); n > 0; --n) {
            double t = 0, r = 0;
            do {  // uniform over the side: the density along the axis grows with the radius
                t = rng.uniform();
                r = b.r_from + t * (b.r_to - b.r_from);
            } while (rng.uniform() * widest > r);
            const double phi = rng.uniform(0, 2 * kPi);
            Vec3 normal{}, q{};
            for (int a = 0; a < 3; ++a) {
                normal[a] = std::cos(phi) * e1[a] + std::sin(phi) * e2[a];
                q[a] = b.from[a] + t * axis[a] + r * normal[a];
            }
            if (lattice) {
                const auto i = static_cast<std::int64_t>(std::floor(q[0] / v)),
                           j = static_cast<std::int64_t>(std::floor(q[1] / v)),
                           k = static_cast<std::int64_t>(std::floor(q[2] / v));
                if (!taken.insert(cell_key(i, j, k)).second) {
                    continue;
                }
                q = {(static_cast<double>(i) + 0.5) * v, (static_cast<double>(j) + 0.5) * v,
                     (static_cast<double>(k) + 0.5) * v};
            }
            bool inside = false;
            fruit.for_near(q,
                           [&](std::uint32_t f) { inside = inside || s.fruits[f].level(q) <= 1; });
            if (inside) {
                continue;
            }
            for (auto& c : q) {
                c += jitter * rng.normal();
            }
            add_point(out, q, paint.wood(s.wood_rgb, tone, normal), 0);
        }
    }
}

}  // namespace pc::scenes::detail
