#pragma once

#include <pc/features/transform.h>
#include <pc/pipeline/steps.h>

namespace pc::pipeline {

/// What pc_transform applies: a fixed affine matrix, then the data-dependent steps.
struct TransformSpec {
    enum class Normalize { kNone, kMeanRadius, kDiagonal };
    features::Matrix4 matrix = features::Matrix4::Identity();
    bool center = false;                     ///< then move the centroid to the origin
    Normalize normalize = Normalize::kNone;  ///< then scale about the centroid to unit mean radius
                                             ///< or unit bounding-box diagonal
};

/// Transforms x y z (F 4 or F 8, computed in double, stored in the field's own type) and, when
/// present, normal_x/y/z (by the inverse transpose of the linear part, renormalised). Every other
/// field is untouched; non-finite points stay as they are. The note gives the final matrix.
[[nodiscard]] Step apply_transform(const io::Blob& in, const TransformSpec& spec);

}  // namespace pc::pipeline
