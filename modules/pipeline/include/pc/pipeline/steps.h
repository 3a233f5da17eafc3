#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pc/filters/colorize.h>
#include <pc/filters/range_filter.h>
#include <pc/io/blob.h>
#include <pc/pipeline/presets.h>
#include <pc/segmentation/cluster_summary.h>

namespace pc::pipeline {

/// One chain step applied to a full cloud: every field it does not touch passes through.
/// `note` says what the step did, for -v. The steps take the cloud by value and work on it in
/// place (pass a temporary or std::move): no second copy of the cloud is made.
/// What a step did, for the report.
struct StepRecord {
    std::string name;            ///< "color_filter", "crop", "voxel", "knn_outlier", "dbscan", ...
    std::size_t points_in = 0;   ///< points handed to the step
    std::size_t points_out = 0;  ///< points it passed on (dbscan: the points it clustered)
    /// The lengths it used, by name (dbscan: eps and the spacing it came from; the cores split:
    /// spacing, fruit_radius, hollow_radius).
    std::vector<std::pair<std::string, double>> values;
    std::string rule;  ///< a rule chosen from the cloud, in words (the colour step), or empty
};

struct Step {
    io::Blob blob;
    std::string note;
    StepRecord record;
    /// What makes the result doubtful (a filter that removed more than 95 % of the points, a
    /// fruit size that could not be estimated), in words a user can act on.
    std::vector<std::string> warnings;
};

[[nodiscard]] Step apply_color_filter(io::Blob in, const filters::ColorFilterParams& p);
/// The colour rule chosen from the cloud (filters::choose_fruit_color), then applied; the record's
/// `rule` says which. A cloud without colour passes through under `auto` (a word needs colour).
[[nodiscard]] Step apply_fruit_color(io::Blob in, const filters::FruitColorParams& p);
/// The chain's colour step alone (p.color or p.fruit_color, the rule applied without the shape
/// test of run_chain()), on each point's neighbourhood colour where p.color_smooth finds the
/// colours noisy (its record's color_noise and color_smooth say so): pc_colorfilter.
[[nodiscard]] Step apply_colour(io::Blob in,
                                const ChainParams& p,
                                const std::function<void(const std::string&)>& progress = {});
[[nodiscard]] Step apply_crop(io::Blob in, const filters::CropParams& p);
/// Sets `rgb` to filters::colorize's colours; the old colour fields (rgb, rgba, red green blue)
/// go, every other field passes through.
[[nodiscard]] Step apply_colorize(io::Blob in, const filters::ColorizeParams& p);
/// Keeps the points whose fields pass the ranges (filters::range_filter, PDAL's rule).
[[nodiscard]] Step apply_range(io::Blob in, const filters::RangeFilterParams& p);
/// One point per occupied voxel (io::aggregate: centroid, mean colour, majority integer fields).
[[nodiscard]] Step apply_voxel(io::Blob in, const filters::VoxelParams& p);

/// Options of the kNN outlier step beyond the algorithm's Params.
struct KnnOutput {
    std::string mark_field;  ///< if set: write 0/1 (1 = outlier) to this U 4 field, drop nothing
    bool invert = false;     ///< keep only the outliers
};
[[nodiscard]] Step apply_knn_outlier(io::Blob in,
                                     const filters::KnnOutlierParams& p,
                                     const KnnOutput& out = {});

/// Writes `label` (U 4). Unless the rule is fixed, eps is estimated first and reported in the note.
[[nodiscard]] Step apply_dbscan(io::Blob in, segmentation::DbscanParams p, const EpsRule& eps = {});
/// Reads and rewrites `label`.
[[nodiscard]] Step apply_recursive_split(io::Blob in, const segmentation::RecursiveSplitParams& p);
/// Reads and rewrites `label`: the parts filters::wood_parts() calls the wood go to 0 (a cloud
/// without colour passes through).
[[nodiscard]] Step apply_wood_parts(io::Blob in, const filters::WoodPartsParams& p);
/// Whether the wood step follows `split`: `wood` is set and the split is the spheres rule (the
/// rule whose parts are single fruit, so that a part of the wood's size is no fruit).
[[nodiscard]] bool drops_wood(const segmentation::RecursiveSplitParams& split,
                              const std::optional<filters::WoodPartsParams>& wood);

/// The whole chain, colour filter to recursive split; returns the labelled cloud.
struct ChainResult {
    io::Blob labelled;
    std::vector<std::string> notes;     ///< one per step
    std::vector<StepRecord> steps;      ///< one per step, in order
    std::vector<std::string> warnings;  ///< the steps' warnings, in order
};
/// `in` is taken by value: pass a temporary (or std::move) and it is not copied (but where the
/// colours offer groups, below). `progress`, when set, receives each step's note as soon as the
/// step is done (pc_fruitcount -v; by the shape test below, once the run is chosen).
/// Natural colours under the spheres split: the colour rule chosen from the cloud
/// (filters::choose_fruit_color) is checked by shape against the other classes the colours
/// offer: the rule's own two groups (bark beside the fruit), two groups of greens (green fruit
/// among leaves), the green points (green fruit beside bark) and the pale points (cream fruit,
/// under the saturation line, beside bark or leaves). Each is counted alone where the
/// rule's fruit centres claim too few of its points (two groups of greens: also where few points
/// lie outside foliage hue), and the run of the class whose centres claim its points is kept
/// (docs/robustness-history.md gives the shares); a group of the rule kept gives way to the greens
/// where their centres claim clearly more (a group of bark pieces claimed as fruit are). Where
/// p.color_smooth finds the colours noisy, every colour decision reads each point's
/// neighbourhood median colour (the output keeps the cloud's colours). The classes compete with the
/// fruit radius as first measured; the run kept, where its centres claim under half its points, is
/// split again with the radius measured without the points on branches
/// (RecursiveSplitParams::branch_recheck). With p.judge_points (off by default), a larger cloud's
/// classes are judged on every k-th point and the class kept is counted on all. Where no group
/// is offered only the green and the pale points are set aside (a copy of each), and the rule
/// runs on `in` itself. Where the wood step
/// tells the wood apart and drops three quarters of the counted points or more, the split had
/// measured the fruit radius on the wood: the points beside the wood (those it kept and the first
/// count's noise) are counted again from DBSCAN on (their steps follow the first count's in
/// `steps`; `labelled` then holds those points only).
[[nodiscard]] ChainResult run_chain(io::Blob in,
                                    const ChainParams& p,
                                    const std::function<void(const std::string&)>& progress = {});

/// run_chain, and also the input with the chain's `label` (U 4) on every point
/// (pc_fruitcount --cloud-all): the cluster of each point that reached the end of the chain, 0 for
/// the points a step removed or DBSCAN left as noise; every field of the input passes through.
/// Costs one copy of the input. Not with a voxel step, whose points are not the input's
/// (pc::InvalidArgument).
struct MarkedChain {
    ChainResult chain;
    io::Blob marked;
};
[[nodiscard]] MarkedChain run_chain_marked(
    io::Blob in,
    const ChainParams& p,
    const std::function<void(const std::string&)>& progress = {});

/// True when the count may depend on eps: the spheres split's fruit centres took under 90 % of
/// the clustered points (the rest is counted by DBSCAN's clusters). pc_fruitcount then runs
/// check_eps() unasked.
[[nodiscard]] bool eps_sensitive(const ChainResult& chain);

/// The count again at other eps: DBSCAN and the split rerun on the points DBSCAN saw (the
/// chain's labelled cloud), at `factors` × the eps its DBSCAN step used.
struct EpsCheck {
    std::vector<double> eps;             ///< eps tried, ascending, the one used among them
    std::vector<std::size_t> counts;     ///< clusters counted at each
    std::optional<std::string> warning;  ///< when the largest count exceeds twice the smallest
};
[[nodiscard]] EpsCheck check_eps(const ChainResult& chain,
                                 const ChainParams& p,
                                 const std::vector<double>& factors = {0.8, 1.25});

/// The clusters of `label` in a labelled cloud (pc_count, pc_fruitcount); an empty cloud has none
/// and needs no label field. Clusters with fewer than `min_points` points are not counted.
[[nodiscard]] segmentation::ClusterSummary summarize(const io::Blob& labelled,
                                                     std::size_t min_points);

/// Warnings about a count itself: none counted from a cloud that had points; a median cluster
/// under 40 points (fruit of about 2 point spacings in radius: the count is rough).
[[nodiscard]] std::vector<std::string> count_warnings(const segmentation::ClusterSummary& s,
                                                      std::size_t points);

}  // namespace pc::pipeline
