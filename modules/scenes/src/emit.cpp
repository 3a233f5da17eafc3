#include "emit.h"

#include <numeric>

namespace pc::scenes::detail {

void add_ground_and_outliers(
    const Scene& s, const RenderParams& p, std::size_t fruit_total, Rng& rng, Rendered& out) {
    const double ground = 1.5 * std::max(s.canopy[0], s.canopy[1]);
    const auto n_ground =
        static_cast<std::uint64_t>(std::llround(p.background * static_cast<double>(fruit_total)));
    const bool mask = p.colors == Colors::kMask;
    for (std::uint64_t k = 0; k < n_ground; ++k) {
        const double rho = ground * std::sqrt(rng.uniform()), phi = rng.uniform(0, 2 * kPi);
        const double grey = mask ? rng.uniform(0, 12) : rng.uniform(10, 70);
        if (mask) {
            add_point(out,
                      {rho * std::cos(phi), rho * std::sin(phi),
                       -s.canopy[2] - 0.3 + 0.01 * rng.normal()},
                      pack(grey, grey, grey), 0);
            continue;
        }
        // One expression, as before mask colours existed: the order in which the compiler draws
        // its random numbers is part of the shipped scenes' bytes.
        add_point(
            out,
            {rho * std::cos(phi), rho * std::sin(phi), -s.canopy[2] - 0.3 + 0.01 * rng.normal()},
            pack(grey, grey * rng.uniform(0.9, 1.1), grey * rng.uniform(0.9, 1.1)), 0);
    }
    const auto n_out =
        static_cast<std::uint64_t>(std::llround(p.outliers * static_cast<double>(fruit_total)));
    for (std::uint64_t k = 0; k < n_out; ++k) {
        add_point(out,
                  {1.2 * s.canopy[0] * rng.uniform(-1, 1), 1.2 * s.canopy[1] * rng.uniform(-1, 1),
                   1.2 * s.canopy[2] * rng.uniform(-1, 1)},
                  pack(rng.uniform(150, 255), rng.uniform(150, 255), rng.uniform(150, 255)), 0);
    }
}

/// `out` in a fixed shuffle, so that nothing downstream can lean on the generation order, with
/// the points of each of the `fruits` counted.
Rendered shuffled_points(const Rendered& out, std::size_t fruits, Rng& rng) {
    const std::size_t n = out.xyz.size();
    std::vector<std::size_t> perm(n);
    std::iota(perm.begin(), perm.end(), std::size_t{0});
    for (std::size_t k = n; k > 1; --k) {
        std::swap(perm[k - 1], perm[rng.below(k)]);
    }
    Rendered shuffled;
    shuffled.xyz.resize(n);
    shuffled.rgb.resize(n);
    shuffled.gt.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        shuffled.xyz[k] = out.xyz[perm[k]];
        shuffled.rgb[k] = out.rgb[perm[k]];
        shuffled.gt[k] = out.gt[perm[k]];
    }
    shuffled.fruit_points.assign(fruits, 0);
    for (auto g : shuffled.gt) {
        if (g != 0) {
            ++shuffled.fruit_points[g - 1];
        }
    }
    return shuffled;
}

}  // namespace pc::scenes::detail
