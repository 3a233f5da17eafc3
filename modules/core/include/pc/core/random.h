#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace pc {

/// A small seeded generator (splitmix64) whose sequence is the same on every platform and
/// standard library, unlike std::uniform_real_distribution / std::normal_distribution. Used
/// wherever random numbers reach an output (scenes, sphere RANSAC).
class Rng {
public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    /// The same seed mixed with a stream number: independent sequences for independent parts.
    Rng(std::uint64_t seed, std::uint64_t stream)
        : state_(seed ^ (stream * 0xD1B54A32D192ED03ull)) {
        (void)next();
    }

    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1).
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    /// Uniform in [a, b).
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
    /// Uniform integer in [0, n); n > 0.
    std::uint64_t below(std::uint64_t n) { return next() % n; }
    /// Standard normal (Box-Muller, one value per call).
    double normal() {
        const double u = 1.0 - uniform();  // (0, 1]
        return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * uniform());
    }
    /// A uniformly distributed unit vector.
    std::array<double, 3> direction() {
        const double z = uniform(-1.0, 1.0), a = uniform(0.0, 6.283185307179586);
        const double s = std::sqrt(1.0 - z * z);
        return {s * std::cos(a), s * std::sin(a), z};
    }

private:
    std::uint64_t state_;
};

}  // namespace pc
