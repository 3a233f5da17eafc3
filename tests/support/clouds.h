#pragma once
// Typed clouds with known structure for the algorithm tests.

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Core>

#include <pc/core/cloud.h>

namespace pc::test {

/// n x n x n lattice with spacing `step` starting at `origin`.
inline Cloud grid(const pcl::PointXYZ& origin, int n, float step) {
    Cloud c;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            for (int k = 0; k < n; ++k) {
                c.push_back({origin.x + i * step, origin.y + j * step, origin.z + k * step});
            }
        }
    }
    return c;
}

/// n points uniform in the ball of `radius` around `centre` (rejection sampling, seeded).
inline Cloud ball(const pcl::PointXYZ& centre, float radius, std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-radius, radius);
    Cloud c;
    while (c.size() < n) {
        const float x = u(rng), y = u(rng), z = u(rng);
        if (x * x + y * y + z * z <= radius * radius) {
            c.push_back({centre.x + x, centre.y + y, centre.z + z});
        }
    }
    return c;
}

/// n points uniform on the sphere of radius r around the origin (normalised Gaussians, seeded).
inline Cloud sphere_shell(float r, std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> g(0, 1);
    Cloud c;
    for (std::size_t i = 0; i < n; ++i) {
        const float x = g(rng), y = g(rng), z = g(rng);
        const float len = std::sqrt(x * x + y * y + z * z);
        c.push_back({r * x / len, r * y / len, r * z / len});
    }
    return c;
}

/// The i-th of n directions spread evenly over the unit sphere, from the pole z = 1 to z = -1
/// (a golden-angle spiral: points on a sphere about equally far apart).
inline Eigen::Vector3d spiral_direction(std::size_t i, std::size_t n) {
    const double z = 1 - 2 * (static_cast<double>(i) + 0.5) / static_cast<double>(n);
    const double rho = std::sqrt(1 - z * z), phi = 2.399963 * static_cast<double>(i);
    return {rho * std::cos(phi), rho * std::sin(phi), z};
}

/// n points uniform in the cube [0, side)^3.
inline Cloud uniform(std::size_t n, float side, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, side);
    Cloud c;
    for (std::size_t i = 0; i < n; ++i) {
        c.push_back({u(rng), u(rng), u(rng)});
    }
    return c;
}

inline Cloud concat(const Cloud& a, const Cloud& b) {
    Cloud c = a;
    c += b;
    return c;
}

inline pcl::PointXYZ nan_point() {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    return {nan, nan, nan};
}

inline double dist2(const pcl::PointXYZ& a, const pcl::PointXYZ& b) {
    const double dx = double{a.x} - b.x, dy = double{a.y} - b.y, dz = double{a.z} - b.z;
    return dx * dx + dy * dy + dz * dz;
}

/// The points of `c` as records of `stride` bytes with x y z at byte `offset`; every other byte
/// holds a pattern of the point's index, so that a record moved in part would show.
inline std::vector<std::uint8_t> records_of(const Cloud& c,
                                            std::size_t stride,
                                            std::uint32_t offset = 0) {
    std::vector<std::uint8_t> bytes(c.size() * stride);
    for (std::size_t i = 0; i < c.size(); ++i) {
        std::uint8_t* r = &bytes[i * stride];
        for (std::size_t b = 0; b < stride; ++b) {
            r[b] = static_cast<std::uint8_t>(i * 131 + b * 7 + (i >> 8));
        }
        std::memcpy(r + offset, &c[i].x, 4);
        std::memcpy(r + offset + 4, &c[i].y, 4);
        std::memcpy(r + offset + 8, &c[i].z, 4);
    }
    return bytes;
}

}  // namespace pc::test
