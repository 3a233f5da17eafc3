#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <pc/io/blob.h>
#include <pc/scenes/scene.h>

namespace pc::scenes {

/// How a reconstructor exports the fruit after 2D fruit masks were lifted into 3D.
enum class Mode {
    kExplicit,  ///< solid voxel occupancy (SVRaster-like): every voxel centre inside a fruit
    kImplicit,  ///< NeRF-like: only surface voxels seen by cameras (real occlusion), jittered;
                ///< noise bridges between touching fruit; floaters
    kDegraded,  ///< explicit geometry lifted from poor masks: per-fruit recall, fruit missed or
                ///< fragmented
};

/// Parses "explicit", "implicit" or "degraded"; throws pc::InvalidArgument.
[[nodiscard]] Mode parse_mode(const std::string& text);
[[nodiscard]] std::string mode_name(Mode mode);

/// Parameters of render().
struct RenderParams {
    Mode mode = Mode::kExplicit;
    double voxel = 0.004;  ///< voxel edge, m (explicit geometry, surface sampling)
    // implicit
    std::uint32_t cameras = 72;   ///< on three rings (elevation 5°, 30°, 60°) around the canopy
    std::uint32_t min_views = 2;  ///< a surface voxel is exported when this many cameras see it
    double surface_noise = 0.3;   ///< σ of the jitter of implicit points, in voxels
    double bridge_gap = 0.5;      ///< bridge fruit whose gap is below this × the smaller radius
    double bridge_probability = 0.6;  ///< chance that such a pair gets a noise bridge
    double floaters = 0.05;           ///< floater blobs per fruit
    // degraded
    double recall = 0.44;  ///< mean fraction of each fruit's voxels kept
    // clutter (every mode)
    double leaf_leak = 0.1;   ///< fraction of leaves exported as green points
    double background = 0.1;  ///< dark ground points, as a fraction of fruit points
    double outliers = 0.005;  ///< bright sparse points, as a fraction of fruit points
    std::uint64_t seed = 1;

    void validate() const;  ///< throws pc::InvalidArgument naming the field
};

/// The exported points: coordinates, packed colour 0x00RRGGBB, ground truth (fruit index + 1,
/// 0 = not fruit). In a fixed shuffled order.
struct Rendered {
    std::vector<std::array<float, 3>> xyz;
    std::vector<std::uint32_t> rgb;
    std::vector<std::uint32_t> gt;
    std::vector<std::uint32_t> fruit_points;  ///< points of each fruit (index = fruit index)
};

/// Turns a scene into the cloud a reconstructor would export. Deterministic for a seed.
[[nodiscard]] Rendered render(const Scene& scene, const RenderParams& params);

/// The cloud as fields x y z (F 4), rgb (U 4), gt_instance (U 4).
[[nodiscard]] io::Blob to_blob(const Rendered& r);

}  // namespace pc::scenes
