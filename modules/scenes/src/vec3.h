#pragma once
// Internal to the scenes module: small vector algebra on Vec3 and pi, for the layout (scene.cpp)
// and the renderers (emit.h), without the renderers' headers.

#include <cmath>
#include <utility>

#include <pc/scenes/scene.h>

namespace pc::scenes::detail {

inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline Vec3 scaled(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline Vec3 unit(const Vec3& a) { return scaled(a, 1.0 / std::sqrt(dot(a, a))); }

/// Two unit vectors perpendicular to unit `d` and to each other.
inline std::pair<Vec3, Vec3> basis(const Vec3& d) {
    const Vec3 helper = std::abs(d[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 a = unit(cross(d, helper));
    return {a, cross(d, a)};
}

inline constexpr double kPi = 3.141592653589793;

}  // namespace pc::scenes::detail
