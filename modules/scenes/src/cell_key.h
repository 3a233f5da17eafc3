#pragma once
// Internal to the scenes module: one 64-bit key per integer cell (21 bits per axis, offset so that
// cells -2^20..2^20-1 stay distinct), for the fruit grid and the voxel lattice.

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "vec3.h"

namespace pc::scenes {

inline std::uint64_t cell_key(std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto u = [](std::int64_t v) {
        return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff;
    };
    return u(x) | (u(y) << 21) | (u(z) << 42);
}

/// Fruit (their indices) bucketed by the cells of their centres; for_near() visits those in the
/// 3 x 3 x 3 cells around a point: every fruit that can reach it when the cell is at least as
/// large as the widest interaction (fruit placement, wood points inside a fruit).
class FruitGrid {
public:
    explicit FruitGrid(double cell) : cell_(cell) {}
    void add(const Vec3& centre, std::uint32_t index) { cells_[key(centre)].push_back(index); }
    template <class F>
    void for_near(const Vec3& c, F&& visit) const {
        const auto ix = coord(c[0]), iy = coord(c[1]), iz = coord(c[2]);
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
            for (std::int64_t dy = -1; dy <= 1; ++dy) {
                for (std::int64_t dz = -1; dz <= 1; ++dz) {
                    const auto it = cells_.find(cell_key(ix + dx, iy + dy, iz + dz));
                    if (it != cells_.end()) {
                        for (auto i : it->second) {
                            visit(i);
                        }
                    }
                }
            }
        }
    }

private:
    [[nodiscard]] std::int64_t coord(double v) const {
        return static_cast<std::int64_t>(std::floor(v / cell_));
    }
    [[nodiscard]] std::uint64_t key(const Vec3& c) const {
        return cell_key(coord(c[0]), coord(c[1]), coord(c[2]));
    }

    double cell_;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace pc::scenes
