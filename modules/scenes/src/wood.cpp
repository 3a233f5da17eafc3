// Wood: the trunk and branches of make_scene() as points, in every mode.
#include <unordered_map>
#include <unordered_set>

#include "cell_key.h"
#include "emit.h"

namespace pc::scenes::detail {

namespace {

/// The fruit bucketed by cells of their largest diameter: is a point inside one of them?
class FruitCells {
public:
    explicit FruitCells(const Scene& s) : s_(s) {
        for (const auto& f : s.fruits) {
            cell_ = std::max(cell_, 2 * f.largest());
        }
        for (std::size_t f = 0; f < s.fruits.size(); ++f) {
            const Vec3& c = s.fruits[f].centre;
            cells_[cell_key(coord(c[0]), coord(c[1]), coord(c[2]))].push_back(
                static_cast<std::uint32_t>(f));
        }
    }

    [[nodiscard]] bool inside(const Vec3& q) const {
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    const auto it =
                        cells_.find(cell_key(coord(q[0]) + dx, coord(q[1]) + dy, coord(q[2]) + dz));
                    if (it == cells_.end()) {
                        continue;
                    }
                    for (auto f : it->second) {
                        if (s_.fruits[f].level(q) <= 1) {
                            return true;
                        }
                    }
                }
            }
        }
        return false;
    }

private:
    [[nodiscard]] std::int64_t coord(double v) const {
        return static_cast<std::int64_t>(std::floor(v / cell_));
    }

    const Scene& s_;
    double cell_ = 1e-9;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace

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
    const FruitCells fruit(s);
    const Vec3 light = unit({0.3, 0.2, 1.0});
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
            if (fruit.inside(q)) {
                continue;
            }
            for (auto& c : q) {
                c += jitter * rng.normal();
            }
            if (p.colors == Colors::kMask) {
                const double c = rng.uniform(0, 12);
                add_point(out, q, pack(c, c, c), 0);
                continue;
            }
            const double lit = tone * (1 - p.shading * (1 - std::max(0.0, dot(normal, light)))) *
                               rng.uniform(0.95, 1.05);
            add_point(out, q,
                      pack(s.wood_rgb[0] * lit + rng.uniform(-8, 8),
                           s.wood_rgb[1] * lit + rng.uniform(-8, 8),
                           s.wood_rgb[2] * lit + rng.uniform(-8, 8)),
                      0);
        }
    }
}

}  // namespace pc::scenes::detail
