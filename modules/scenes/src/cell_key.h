#pragma once
// Internal to the scenes module: one 64-bit key per integer cell (21 bits per axis, offset so that
// cells -2^20..2^20-1 stay distinct), for the fruit placement grid and the voxel lattice.

#include <cstdint>

namespace pc::scenes {

inline std::uint64_t cell_key(std::int64_t x, std::int64_t y, std::int64_t z) {
    const auto u = [](std::int64_t v) {
        return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1fffff;
    };
    return u(x) | (u(y) << 21) | (u(z) << 42);
}

}  // namespace pc::scenes
