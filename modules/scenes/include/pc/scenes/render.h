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
    // Sampled off the lattice (`voxel` is the point spacing); leaves as random points on discs:
    kSurface,  ///< uniform random points on each fruit's visible surface (splats, meshes)
    kSfm,      ///< structure from motion: surface density falling away from the outside of the
               ///< tree, per-fruit density spread, holes, exact duplicate points
    kStripes,  ///< a scanner's lines: vertical planes `voxel` apart, points voxel/3 apart along
               ///< them, only the side facing the scanner
    kVolume,   ///< uniform random points inside each fruit (solid, off the lattice)
};

/// How points are coloured.
enum class Colors {
    kNatural,  ///< fruit_rgb, leaves green, ground dark, wood wood_rgb; `shading` shades fruit
               ///< and wood of the sampled modes
    kMask,     ///< a semantic export: fruit near white, leaves and ground near black
};

/// Parses "explicit", "implicit" or "degraded"; throws pc::InvalidArgument.
[[nodiscard]] Mode parse_mode(const std::string& text);
[[nodiscard]] std::string mode_name(Mode mode);
/// Parses "natural" or "mask"; throws pc::InvalidArgument.
[[nodiscard]] Colors parse_colors(const std::string& text);
[[nodiscard]] std::string colors_name(Colors colors);

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
    double wood_leak = 1;     ///< fraction of the scene's branches exported (bark-coloured)
    // sampled modes
    double noise = 0;         ///< σ of each point's jitter, as a fraction of its fruit's radius
    double holes = 1;         ///< sfm: mean number of empty caps per fruit
    double duplicates = 0.1;  ///< sfm: fraction of points written twice, exactly
    double density_spread = 0.5;  ///< sfm: σ of each fruit's log density
    double shading = 0;  ///< brightness 1 - shading × (1 - max(0, normal · light)); 0 = flat
    /// σ of a Gaussian added to each channel (0..255 levels) of the sampled modes' fruit and
    /// leaves and of the wood, natural colours: SfM and NeRF colours vary between the views a
    /// point was seen from (drawn from streams of their own: 0 keeps every scene's bytes)
    double color_noise = 0;
    Colors colors = Colors::kNatural;
    // units (every mode): written coordinates = metres × scale + offset
    double scale = 1;
    Vec3 offset{0, 0, 0};
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
