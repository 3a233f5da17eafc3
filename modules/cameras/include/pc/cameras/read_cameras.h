#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <pc/cameras/camera.h>

namespace pc::cameras {

/// The calibrated views of a dataset, in the frame of the file they came from.
struct Dataset {
    std::vector<View> views;
    /// transforms.json's `applied_transform`: how ns-process-data moved COLMAP's world into this
    /// file's (a COLMAP cloud meets these cameras after it); nullopt when absent.
    std::optional<Similarity> applied;
};

/// Reads the cameras of `path`:
///  - a nerfstudio or instant-ngp `transforms.json` (a file): intrinsics at the top level and/or
///    per frame (`fl_x` `fl_y` `cx` `cy` `w` `h` `k1`..`k4` `p1` `p2` `camera_model`; `fl_x`
///    from `camera_angle_x` when absent; cx, cy default to the image's centre), each frame's
///    `file_path`, camera-to-world `transform_matrix` (4x4, OpenGL axes: x right, y up, z back)
///    and `mask_path` (else FruitNeRF's `semantic_path`);
///  - a COLMAP sparse model (a directory holding `cameras.txt` and `images.txt`, or `cameras.bin`
///    and `images.bin`): world-to-camera quaternions and translations, OpenCV axes.
/// Views come in the source's order (COLMAP: by image id). Throws pc::IoError naming the file
/// and what is wrong: unreadable, not JSON, a missing key, a matrix of the wrong shape, an
/// unknown camera model, a view without its camera, non-finite numbers, a truncated binary.
[[nodiscard]] Dataset read_cameras(const std::string& path);

/// A transforms.json's text, as read_cameras() reads the file; `path` names it in errors (the
/// fuzz target's entry point).
[[nodiscard]] Dataset parse_transforms(std::string_view text, const std::string& path);

/// nerfstudio's `dataparser_transforms.json` ({"transform": 3x4, "scale": s}): the similarity
/// from the transforms.json frame into the frame nerfstudio trains and exports in (ns-export's
/// clouds), p' = s·(T·[p; 1]). Throws pc::IoError as read_cameras() does.
[[nodiscard]] Similarity read_dataparser_transforms(const std::string& path);

/// A dataparser_transforms.json's text, as read_dataparser_transforms() reads the file.
[[nodiscard]] Similarity parse_dataparser_transforms(std::string_view text,
                                                     const std::string& path);

}  // namespace pc::cameras
