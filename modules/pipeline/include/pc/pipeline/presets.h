#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <pc/core/error.h>
#include <pc/filters/color_filter.h>
#include <pc/filters/color_smooth.h>
#include <pc/filters/crop.h>
#include <pc/filters/fruit_color.h>
#include <pc/filters/knn_outlier.h>
#include <pc/filters/voxel_downsample.h>
#include <pc/filters/wood_parts.h>
#include <pc/segmentation/dbscan.h>
#include <pc/segmentation/recursive_split.h>

namespace pc::pipeline {

/// How DBSCAN's eps is chosen: the fixed dbscan.eps, the knee of the k-distance curve
/// (segmentation::estimate_eps), or `factor` × the point spacing (search::median_spacing).
struct EpsRule {
    enum class Mode { kFixed, kKnee, kSpacing } mode = Mode::kFixed;
    double factor = 3.5;  ///< kSpacing: eps = factor × median nearest-neighbour distance
};

/// Reads the text of an `--eps` option: a number (fixed), "auto" (4 × the point spacing: the
/// robust choice), "knee" (the k-distance knee), "spacing" (factor × spacing, the factor kept), or
/// "Nxs" (N × spacing). Throws pc::InvalidArgument.
void parse_eps(const std::string& text, segmentation::DbscanParams& dbscan, EpsRule& rule);
/// The `--eps` text that parse_eps() reads back to the same choice ("0.015", "knee", "4xs").
[[nodiscard]] std::string eps_text(const segmentation::DbscanParams& dbscan, const EpsRule& rule);

/// Every parameter of the counting chain (../shared/METHOD.md), step by step.
/// A step whose optional is empty is skipped.
struct ChainParams {
    std::optional<filters::ColorFilterParams> color;       ///< a fixed colour rule; when empty,
    std::optional<filters::FruitColorParams> fruit_color;  ///< a rule chosen from the cloud
    /// when set, the colour rule (fixed or chosen) reads each point's neighbourhood colour where
    /// the colours are noisy (filters::smooth_colors: SfM and NeRF colours vary from point to
    /// point); the output keeps the cloud's own colours
    std::optional<filters::ColorSmoothParams> color_smooth;
    std::optional<filters::CropParams> crop;
    std::optional<filters::VoxelParams> voxel;
    std::optional<filters::KnnOutlierParams> knn;
    segmentation::DbscanParams dbscan;
    EpsRule eps;  ///< how dbscan.eps is chosen (fixed by default)
    std::optional<segmentation::RecursiveSplitParams> split;
    /// after the spheres split, on coloured points: the parts coloured like the wood dropped
    std::optional<filters::WoodPartsParams> wood;
    std::uint32_t count_min_points = 1;  ///< clusters with fewer points are not counted
    /// natural colours under the spheres split, on a cloud of more points than this: the colour
    /// classes that compete (run_chain()) are judged on every k-th point (k the smallest that
    /// leaves at most this many), and the class kept is counted on every point; 0 (the default):
    /// judged on every point. Faster on clouds of millions of points, but a doubtful class's
    /// claim moves with the thinning (docs/robustness-history.md, session 47): off unless asked for
    std::size_t judge_points = 0;
};

/// The preset names, in the order --help lists them.
[[nodiscard]] const std::vector<std::string>& preset_names();

/// The named parameter set; throws pc::InvalidArgument for an unknown name.
///  - dense: beyond the paper, for unknown clouds: the colour rule chosen from the cloud
///    (filters::choose_fruit_color), eps = 4 x the point spacing, the spheres split rule
///    (segmentation::sphere_vote: no medians, lengths from the fruit radius it estimates),
///    clusters below 0.1 x the median size dropped, the parts coloured like the wood dropped
///    (filters::wood_parts); pc_fruitcount's default
///  - paper-dense: the paper's dense setting (sections 2.3-2.5): eps 0.015, paper split rule
///  - paper-sparse: the paper's degraded-mask setting: eps 0.030, split only above 5x median volume
///  - invnerfseg: the author's public script, column by column (crop box, voxel 0.001, eps 0.0065,
///    script split rule, count clusters with >= 40 points)
[[nodiscard]] ChainParams preset(std::string_view name);

/// One optional step of preset `name` (`&ChainParams::crop`, `&ChainParams::voxel`), for a
/// single-step tool's --preset; pc::InvalidArgument "--preset: NAME has no WHAT step" when that
/// preset leaves the step out.
template <class P>
[[nodiscard]] P preset_step(std::string_view name,
                            std::optional<P> ChainParams::*step,
                            const std::string& what) {
    const std::optional<P> p = preset(name).*step;
    if (!p) {
        throw InvalidArgument("--preset: " + std::string(name) + " has no " + what + " step");
    }
    return *p;
}

}  // namespace pc::pipeline
