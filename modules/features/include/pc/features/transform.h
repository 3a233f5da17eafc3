#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

namespace pc::features {

/// A 4x4 affine transform acting on column vectors: p' = M [p; 1].
using Matrix4 = Eigen::Matrix4d;

/// 16 numbers (row-major 4x4) or 12 (row-major 3x4, last row 0 0 0 1), separated by blanks,
/// commas or newlines. Throws pc::InvalidArgument naming `what`.
[[nodiscard]] Matrix4 parse_matrix(const std::string& text, const std::string& what);

/// Rotation by `angle_deg` about the axis (x, y, z) (normalised; right-hand rule).
[[nodiscard]] Matrix4 rotation(const std::array<double, 3>& axis, double angle_deg);

/// nerfstudio's dataparser_transforms.json ({"transform": 3x4, "scale": s}): the map from the
/// dataset frame to nerfstudio's, p_ns = s · (T [p; 1]). Its inverse maps an export back.
[[nodiscard]] Matrix4 nerfstudio_forward(const std::string& json_text, const std::string& what);

/// Throws pc::InvalidArgument unless M is finite, its last row is 0 0 0 1 and its 3x3 part is
/// invertible.
void check_affine(const Matrix4& m, const std::string& what);

}  // namespace pc::features
