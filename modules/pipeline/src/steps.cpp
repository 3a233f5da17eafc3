#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <unordered_set>

#include <pc/core/error.h>
#include <pc/core/stats.h>
#include <pc/filters/color_smooth.h>
#include <pc/filters/wood_parts.h>
#include <pc/io/info.h>
#include <pc/io/points.h>
#include <pc/pipeline/steps.h>
#include <pc/search/spacing.h>

namespace pc::pipeline {

namespace {

std::string kept_note(const char* step, std::size_t kept, std::size_t total) {
    return std::string(step) + ": kept " + std::to_string(kept) + " of " + std::to_string(total) +
           " points";
}

/// The colour rule in words, for a warning.
std::string describe(const filters::ColorFilterParams& p) {
    std::vector<std::string> rules;
    const auto interval = [](const filters::Interval& i) {
        return format_number(i.lo) + ".." + format_number(i.hi);
    };
    if (p.min_mean) {
        rules.push_back("mean RGB > " + format_number(*p.min_mean));
    }
    if (p.min_value) {
        rules.push_back("max RGB > " + format_number(*p.min_value));
    }
    if (p.hue_deg) {
        rules.push_back("hue " + interval(*p.hue_deg) + " deg");
    }
    if (p.saturation) {
        rules.push_back("saturation " + interval(*p.saturation));
    }
    if (p.value) {
        rules.push_back("value " + interval(*p.value));
    }
    std::string text = p.invert ? "not " : "";
    for (std::size_t k = 0; k < rules.size(); ++k) {
        text += (k ? " and " : "") + rules[k];
    }
    return rules.empty() ? "no rule" : text;
}

/// A step that leaves more than this share of the points behind (filtered out, or noise) gets
/// a warning.
constexpr double kNearlyAll = 0.95;

/// A step's record and, when it removed more than kNearlyAll of a non-empty cloud's points, a
/// warning that says so and what to try (`hint`).
Step finish_step(
    io::Blob out, std::string note, const char* name, std::size_t in, const std::string& hint) {
    const std::size_t kept = out.size();
    Step s{std::move(out), std::move(note), {name, in, kept, {}}, {}};
    if (in > 0 && static_cast<double>(in - kept) > kNearlyAll * static_cast<double>(in)) {
        s.warnings.push_back(std::string(name) + " kept " + std::to_string(kept) + " of " +
                             std::to_string(in) + " points" + (hint.empty() ? "" : ": " + hint));
    }
    return s;
}

/// The colour step's record: rule `p` kept `kept` of `in` points.
Step colour_step(io::Blob kept, std::size_t in, const filters::ColorFilterParams& p) {
    std::string note = kept_note("color_filter", kept.size(), in);
    return finish_step(std::move(kept), std::move(note), "color_filter", in,
                       "the colour rule (" + describe(p) +
                           ") removed nearly every point; is the fruit another colour? try "
                           "--fruit-color (auto, mask, red, orange, yellow, green, purple, any) or "
                           "--no-color");
}

/// The field that carries the colours the colour decisions read, where they are not the cloud's
/// own (ChainParams::color_smooth); run_chain() removes it before it returns.
constexpr const char* kDecisionRgb = "pc_decision_rgb";

/// The colours the colour step decides on: those of kDecisionRgb where the chain set it, else
/// the cloud's (io::colours(), which rejects a non-empty cloud without colour).
std::vector<io::Rgb> decision_colours(const io::Blob& in) {
    if (io::find_field(in, kDecisionRgb) == nullptr) {
        return io::colours(in);
    }
    const std::vector<std::uint32_t> packed = io::labels(in, kDecisionRgb);
    std::vector<io::Rgb> out(packed.size());
    for (std::size_t i = 0; i < packed.size(); ++i) {
        const auto channel = [&](int shift) {
            return static_cast<float>((packed[i] >> shift) & 255u) / 255.0f;
        };
        out[i] = {channel(16), channel(8), channel(0)};
    }
    return out;
}

/// What smooth_decisions() did, for the colour step's record.
struct Smoothing {
    double noise = 0;     ///< the colours' noise read (0..1)
    std::uint32_t k = 0;  ///< the neighbours the colour rule's colours are medians over; 0: none

    /// Removes the decision colours from the colour step's (or the chain's) output and records
    /// the noise and k in the colour step's record.
    void finish(io::Blob& out, StepRecord& colour) const {
        if (k > 0) {
            io::remove_field(out, kDecisionRgb);
        }
        colour.values.insert(colour.values.end(),
                             {{"color_noise", 255 * noise}, {"color_smooth", k}});
    }
};

/// Where `p` has a colour step and smoothing (ChainParams::color_smooth) and `in` has colours:
/// reads their noise (filters::smooth_colors) and, where they are noisy, sets kDecisionRgb to
/// each point's neighbourhood median colour; says so to `progress`.
std::optional<Smoothing> smooth_decisions(io::Blob& in,
                                          const ChainParams& p,
                                          const std::function<void(const std::string&)>& progress) {
    if (!p.color_smooth || !(p.color || p.fruit_color) || in.size() == 0 ||
        io::colour_fields(in).empty()) {
        return std::nullopt;
    }
    const filters::SmoothedColors smooth =
        filters::smooth_colors(io::XyzPoints(in).view(), io::colours(in), *p.color_smooth);
    const Smoothing out{smooth.noise, smooth.colors.empty() ? 0 : p.color_smooth->k};
    if (progress) {
        progress("color_smooth: colour noise " + format_rounded(255 * out.noise) +
                 " of 255 (estimated): " +
                 (out.k > 0 ? "the colour rule reads the median colour of each point and its " +
                                  std::to_string(out.k) + " nearest neighbours"
                            : "under " + format_rounded(255 * p.color_smooth->min_noise) +
                                  ", the colour rule reads each point's own colour"));
    }
    if (out.k > 0) {
        std::vector<std::uint32_t> packed(smooth.colors.size());
        for (std::size_t i = 0; i < packed.size(); ++i) {
            const auto q = [](float v) {
                return static_cast<std::uint32_t>(std::clamp(std::lround(v * 255.0f), 0L, 255L));
            };
            const io::Rgb& c = smooth.colors[i];
            packed[i] = (q(c.r) << 16) | (q(c.g) << 8) | q(c.b);
        }
        io::set_field(in, kDecisionRgb, packed);
    }
    return out;
}

/// The points of `in` that rule `p` keeps.
Indices colour_kept(const io::Blob& in, const filters::ColorFilterParams& p) {
    p.validate();
    // an empty cloud passes through
    return in.size() == 0 ? Indices{} : filters::color_filter(decision_colours(in), p).kept;
}

}  // namespace

Step apply_color_filter(io::Blob in, const filters::ColorFilterParams& p) {
    const Indices kept = colour_kept(in, p);
    const std::size_t n = in.size();
    io::keep_points(in, kept);
    return colour_step(std::move(in), n, p);
}

namespace {

/// The colour rule for `in` (filters::choose_fruit_color); under `auto`, a cloud without points or
/// colours gets none.
filters::FruitColorChoice choose_fruit_color(const io::Blob& in,
                                             const filters::FruitColorParams& p) {
    p.validate();
    if (p.color == filters::FruitColor::kAuto &&
        (in.size() == 0 || io::colour_fields(in).empty())) {
        const std::string why = in.size() == 0 ? "an empty cloud" : "no colour fields";
        return {std::nullopt, "auto: " + why + ": no colour rule", {}, {}};
    }
    return filters::choose_fruit_color(decision_colours(in), p);
}

Step apply_choice(io::Blob in, filters::FruitColorChoice c) {
    const std::size_t n = in.size();
    Step step = c.rule ? apply_color_filter(std::move(in), *c.rule)
                       : Step{std::move(in),
                              kept_note("color_filter", n, n),
                              {"color_filter", n, n, {}, ""},
                              {}};
    step.note += " (" + c.reason + ")";
    step.record.rule = c.reason;
    step.warnings.insert(step.warnings.end(), c.warnings.begin(), c.warnings.end());
    return step;
}

}  // namespace

Step apply_fruit_color(io::Blob in, const filters::FruitColorParams& p) {
    filters::FruitColorChoice c = choose_fruit_color(in, p);
    return apply_choice(std::move(in), std::move(c));
}

Step apply_colour(io::Blob in,
                  const ChainParams& p,
                  const std::function<void(const std::string&)>& progress) {
    const std::optional<Smoothing> smooth = smooth_decisions(in, p, progress);
    if (!p.color && !p.fruit_color) {
        throw InvalidArgument("apply_colour: the chain has no colour step");
    }
    Step out = p.color ? apply_color_filter(std::move(in), *p.color)
                       : apply_fruit_color(std::move(in), *p.fruit_color);
    if (smooth) {
        smooth->finish(out.blob, out.record);
    }
    return out;
}

Step apply_crop(io::Blob in, const filters::CropParams& p) {
    const auto kept = filters::crop(io::XyzPoints(in).view(), p).kept;
    std::string note = kept_note("crop", kept.size(), in.size());
    const std::size_t n = in.size();
    io::keep_points(in, kept);
    return finish_step(std::move(in), std::move(note), "crop", n,
                       "is the box in the cloud's units and frame?");
}

Step apply_colorize(io::Blob in, const filters::ColorizeParams& p) {
    const filters::Colorized c = filters::colorize(in, p);
    auto& fields = in.cloud.fields;
    fields.erase(
        std::remove_if(fields.begin(), fields.end(),
                       [](const pcl::PCLPointField& f) {
                           return f.name == "rgba" || f.name == "red" || f.name == "green" ||
                                  f.name == "blue" ||
                                  (f.name == "rgb" && f.datatype != pcl::PCLPointField::UINT32);
                       }),
        fields.end());
    io::set_field(in, "rgb", filters::packed(c.colors));
    std::string note = "colorize: " + std::to_string(in.size()) + " points by " + p.by;
    if (p.by != "label") {
        note += ", viridis from " + format_number(c.lo) + " to " + format_number(c.hi);
    }
    const std::size_t n = in.size();
    return finish_step(std::move(in), std::move(note), "colorize", n, "");
}

Step apply_range(io::Blob in, const filters::RangeFilterParams& p) {
    const auto kept = filters::range_filter(in, p);
    std::string note = kept_note("range", kept.size(), in.size());
    const std::size_t n = in.size();
    io::keep_points(in, kept);
    return finish_step(std::move(in), std::move(note), "range", n,
                       "are the limits in the field's units? (pc_info --stats shows its "
                       "percentiles)");
}

Step apply_voxel(io::Blob in, const filters::VoxelParams& p) {
    const filters::VoxelResult v = filters::voxel_downsample(io::XyzPoints(in).view(), p);
    return finish_step(io::aggregate(in, v.voxel, v.count),
                       "voxel: " + std::to_string(in.size()) + " points into " +
                           std::to_string(v.count) + " voxels of " + format_number(p.leaf),
                       "voxel", in.size(), "is the leaf size in the cloud's units?");
}

Step apply_knn_outlier(io::Blob in, const filters::KnnOutlierParams& p, const KnnOutput& o) {
    const filters::KnnOutlierResult r = filters::knn_outlier(io::XyzSortable(in).records(), p);
    std::size_t outliers = 0;
    for (auto f : r.outlier) {
        outliers += f;
    }
    const std::string note = "knn_outlier: threshold " + format_rounded(r.threshold) + ", " +
                             std::to_string(outliers) + " of " + std::to_string(in.size()) +
                             " points are outliers";
    if (!o.mark_field.empty()) {
        const std::vector<std::uint32_t> mark(r.outlier.begin(), r.outlier.end());
        io::set_field(in, o.mark_field, mark);
        return finish_step(std::move(in), note, "knn_outlier", r.outlier.size(), "");
    }
    const std::size_t n = in.size();
    io::keep_flagged(in, r.outlier, o.invert);  // the outliers when inverted, else the inliers
    return finish_step(std::move(in), note, "knn_outlier", n, "");
}

Step apply_dbscan(io::Blob in, segmentation::DbscanParams p, const EpsRule& eps) {
    std::string note;
    std::vector<std::pair<std::string, double>> values;
    if (eps.mode == EpsRule::Mode::kKnee) {
        const io::XyzPoints points(in);
        std::size_t finite = 0;
        for (std::size_t i = 0; i < points.view().size; ++i) {
            finite += is_finite(points.view()[i]);
        }
        if (finite < p.min_points) {
            // No knee without min_points points, and no cluster either: all noise, not an error
            // (an empty cloud is valid data).
            p.eps = std::numeric_limits<double>::min();
            note = "dbscan: " + std::to_string(finite) +
                   " finite points, fewer than min_points: "
                   "no eps knee; ";
        } else {
            p.eps = segmentation::estimate_eps(points.view(), p.min_points);
            note = "dbscan: eps knee = " + format_rounded(p.eps) + "; ";
        }
    } else if (eps.mode == EpsRule::Mode::kSpacing) {
        const double s = search::median_spacing(io::XyzPoints(in).view());
        values.emplace_back("spacing", s);
        // Fewer than two distinct points: no spacing; only coincident points can be neighbours.
        p.eps = s > 0 ? eps.factor * s : std::numeric_limits<double>::min();
        note = "dbscan: eps = " + format_number(eps.factor) + " x spacing " + format_rounded(s) +
               " = " + format_rounded(p.eps) + "; ";
    }
    // A rule's eps is a measurement (3 digits); a typed one prints as the user gave it.
    const std::string eps_text =
        eps.mode == EpsRule::Mode::kFixed ? format_number(p.eps) : format_rounded(p.eps);
    const segmentation::DbscanResult r = segmentation::dbscan(io::XyzSortable(in).records(), p);
    std::size_t noise = 0;
    for (auto l : r.labels) {
        noise += l == segmentation::kNoise;
    }
    note += "dbscan: " + std::to_string(r.cluster_count) + " clusters, " + std::to_string(noise) +
            " noise points (eps " + eps_text + ", min_points " + std::to_string(p.min_points) + ")";
    io::set_field(in, "label", r.labels);
    values.emplace_back("eps", p.eps);
    Step step{
        std::move(in), note, {"dbscan", r.labels.size(), r.labels.size() - noise, values}, {}};
    if (static_cast<double>(noise) > kNearlyAll * static_cast<double>(r.labels.size())) {
        step.warnings.push_back(
            "dbscan left " + std::to_string(noise) + " of " + std::to_string(r.labels.size()) +
            " points as noise (eps " + eps_text + ", min_points " + std::to_string(p.min_points) +
            "): eps is small for this cloud's point spacing; try --eps spacing");
    }
    return step;
}

/// A ball of radius R filled with points at median nearest-neighbour spacing s holds about
/// kSolidBallPoints (R/s)³ of them at the least: a Poisson process has a median nearest-neighbour
/// distance of 0.549 ρ^(-1/3), so ρ = 0.165 / s³ and the ball 4.19 × 0.165 (R/s)³; a lattice
/// (ρ = 1 / s³) holds 4.19 (R/s)³.
constexpr double kSolidBallPoints = 0.69;
/// Solid fruit whose median cluster holds under this share of that are not balls of radius R.
/// Measured over the 540 scored scenes of the condition matrix (docs/robustness-history.md): solid
/// ones counted right hold 0.32 (random in the volume, the least) to 4.1 (R/s)³ (lattices), the
/// random-volume bunches at 2 spacings a radius counted as one fruit each 0.04-0.16.
constexpr double kTooFewForABall = 0.25 / kSolidBallPoints;
/// Fruit centres that took under this share of the clustered points leave most of the count to
/// DBSCAN's clusters: the fruit radius is likely wrong (estimated from leaves, or given wrongly).
/// Over the 740 scored scenes of the condition matrix: 5 of the 43 off by more than 20 % are
/// below it (3 more found no centre), 1 of the 697 counted within 20 % (0.38, a degraded peach
/// at 2 spacings).
constexpr double kFewClaimed = 0.4;
/// The first fruit radius the normals gave was replaced by one this many times smaller (its
/// centres claimed more of the points): two sizes fit, a fruit's and likely a bunch's. Over the
/// 740 scored scenes of the condition matrix 32 replaced the first radius; the 5 with a ratio
/// of 2 or more (2.3-4.6: grape and truss bunches sampled in the volume at 2 spacings a radius)
/// counted 97-206 of 80-200, 2 of them off by more than 20 %; below 2 (1.15-1.46) 5 of 27.
constexpr double kTwoSizes = 2.0;
/// A given fruit radius more than 1/kGivenTooLarge times the one the points' normals measure is
/// likely a diameter, or in other units. Over the 740 scenes of the condition matrix given their
/// true median radius, the measured one was 0.60-1.08 of it at 3 spacings a radius and more
/// (solids read short: 0.60-0.7), and up to 2.5 times larger for bunches at 2 spacings (so a
/// larger measurement is no warning: the given radius is the cure there).
constexpr double kGivenTooLarge = 0.55;
/// The spheres split's centres took under this share of the points: DBSCAN's clusters make part
/// of the count, and eps matters. Over the 740 scenes of the condition matrix (0.8 and 1.25 x
/// eps): where centres took 90 % or more (568 scenes) the count moved at most 1.34x; below
/// (172 scenes, every one of the 43 off by more than 20 % among them) 15 swung more than 2x.
/// Below it the count is also a warning: over the 1440 scored scenes (session 28) 280 are
/// below, holding 51 of the 52 off by more than 20 % (2 of them with no other warning: cherry
/// bunches sampled in the volume at 2 spacings, 0.86); of the 229 below counted within 20 %,
/// 11 had no other warning (5 of them off by 10-20 %).
constexpr double kEpsSensitive = 0.9;

Step apply_recursive_split(io::Blob in, const segmentation::RecursiveSplitParams& p) {
    segmentation::RecursiveSplitResult r =
        segmentation::recursive_split(io::XyzPoints(in).view(), io::labels(in, "label"), p);
    io::set_field(in, "label", r.labels);
    const bool spheres = p.rule == segmentation::SplitRule::kSpheres;
    const std::string how =
        spheres ? "fruit centres found by normals voting (spacing " + format_rounded(r.spacing) +
                      ", fruit radius " + format_rounded(r.fruit_radius) +
                      (p.fruit_radius > 0 ? " from the given " + format_number(p.fruit_radius)
                                          : " estimated") +
                      ")"
        : p.rule == segmentation::SplitRule::kCores
            ? "clusters cut at their cores" + std::string(" (spacing ") +
                  format_rounded(r.spacing) + ", estimated fruit radius " +
                  format_rounded(r.fruit_radius) +
                  (r.hollow_radius > 0 ? ", on hollow surfaces " + format_rounded(r.hollow_radius)
                                       : "") +
                  ")"
            : "splits (thresholds: points > " + format_rounded(r.size_threshold) +
                  ", AABB volume > " + format_rounded(r.volume_threshold) + ")";
    const std::size_t n = in.size();
    Step step{std::move(in),
              "recursive_split: " + std::to_string(spheres ? r.peaks : r.splits) + " " + how +
                  ", " + std::to_string(r.cluster_count) + " clusters",
              {"recursive_split", n, n, {}},
              {}};
    if (spheres) {
        step.record.values = {
            {"spacing", r.spacing}, {"fruit_radius", r.fruit_radius}, {"claimed", r.claimed}};
        if (p.fruit_radius > 0) {
            step.record.values.emplace_back("measured_radius", r.measured_radius);
        }
        if (r.larger_radius > 0) {
            step.record.values.emplace_back("larger_radius", r.larger_radius);
        }
        step.record.rule = r.solid ? "solid fruit: their outer layer voted" : "fruit surfaces";
        const double expected = kSolidBallPoints * std::pow(r.fruit_radius / r.spacing, 3);
        const double typical = r.median_part;
        const bool balls = r.solid && r.peaks > 0 && r.fruit_radius > 0 && r.spacing > 0;
        if (balls) {
            step.record.values.emplace_back("ball_fill", typical / expected);
        } else if (r.peaks > 0 && r.fruit_radius > 0 && r.spacing > 0) {
            // a sphere's surface at spacing s: about 4π (R/s)² points
            step.record.values.emplace_back(
                "shell_fill",
                typical / (4 * std::numbers::pi * std::pow(r.fruit_radius / r.spacing, 2)));
        }
        if (balls && typical < kTooFewForABall * expected) {
            step.warnings.push_back(
                "the median fruit holds " + format_rounded(typical) +
                " points, far fewer than a solid ball of the fruit radius " +
                format_rounded(r.fruit_radius) + " at spacing " + format_rounded(r.spacing) +
                " would (about " + format_number(std::round(expected)) +
                "): the radius may be a bunch's, each bunch counted as one fruit; give "
                "--fruit-radius if you know the fruit's size");
        }
        if (p.fruit_radius > 0 && r.measured_radius > 0 &&
            r.measured_radius < kGivenTooLarge * p.fruit_radius) {
            step.warnings.push_back(
                "the given fruit radius " + format_number(p.fruit_radius) + " is more than " +
                format_number(std::round(10 / kGivenTooLarge) / 10) + " times the " +
                format_rounded(r.measured_radius) +
                " the points' normals measure: is it a diameter, or in other units? (too "
                "large a radius joins neighbouring fruit into one)");
        }
        if (r.larger_radius > 0 && r.larger_radius >= kTwoSizes * r.fruit_radius) {
            step.warnings.push_back(
                "two fruit sizes fit these points: the normals first gave a fruit radius of " +
                format_rounded(r.larger_radius) + ", whose centres left many points unclaimed, " +
                "and the count uses " + format_rounded(r.fruit_radius) +
                " (bunches of small fruit?); give --fruit-radius if you know the fruit's size");
        }
        if (r.peaks > 0 && r.claimed < kFewClaimed) {
            step.warnings.push_back(
                "fruit centres took only " + format_number(std::round(100 * r.claimed)) +
                " % of the clustered points (fruit radius " + format_rounded(r.fruit_radius) +
                "): the rest was counted by its DBSCAN clusters; is the fruit radius right "
                "(--fruit-radius)?");
        } else if (r.peaks > 0 && r.claimed < kEpsSensitive) {
            step.warnings.push_back(
                "fruit centres took " + format_number(std::round(100 * r.claimed)) +
                " % of the clustered points (fruit radius " + format_rounded(r.fruit_radius) +
                "): the rest (leaves the colour step kept, fruit without a centre, merged "
                "bunches) was counted by its DBSCAN clusters; treat the count as rough");
        }
        if (r.cluster_count > 0 && !(r.fruit_radius > 0)) {
            step.warnings.push_back(
                "recursive_split could not estimate the fruit radius (spacing " +
                format_rounded(r.spacing) +
                "): clusters were left whole; give --fruit-radius if you know the fruit's size");
        } else if (r.cluster_count > 0 && r.peaks == 0) {
            step.warnings.push_back(
                "recursive_split found no fruit centre (fruit radius " +
                format_rounded(r.fruit_radius) +
                "): clusters were left whole; is the fruit radius right (--fruit-radius)?");
        }
    }
    if (p.rule == segmentation::SplitRule::kCores) {
        step.record.values = {{"spacing", r.spacing},
                              {"fruit_radius", r.fruit_radius},
                              {"hollow_radius", r.hollow_radius}};
        if (r.cluster_count > 0 && !(r.fruit_radius > 0) && !(r.hollow_radius > 0)) {
            step.warnings.push_back(
                "recursive_split could not estimate the fruit radius (spacing " +
                format_rounded(r.spacing) +
                "): no cluster was cut; if DBSCAN shattered the fruit, try a larger --eps, or "
                "--preset paper-dense");
        }
    }
    return step;
}

bool drops_wood(const segmentation::RecursiveSplitParams& split,
                const std::optional<filters::WoodPartsParams>& wood) {
    return wood && split.rule == segmentation::SplitRule::kSpheres;
}

namespace {

/// Whether the wood step can tell parts by colour in `cloud` (apply_wood_parts and check_eps's
/// recount): a cloud without colours passes through it.
bool wood_coloured(const io::Blob& cloud) {
    return cloud.size() > 0 && !io::colour_fields(cloud).empty();
}

}  // namespace

Step apply_wood_parts(io::Blob in, const filters::WoodPartsParams& p) {
    const std::size_t n = in.size();
    if (!wood_coloured(in)) {
        return {
            std::move(in), "wood_parts: no colours, nothing dropped", {"wood_parts", n, n, {}}, {}};
    }
    const filters::WoodPartsResult r =
        filters::wood_parts(io::colours(in), io::labels(in, "label"), p);
    const auto kept = static_cast<std::size_t>(
        std::count_if(r.labels.begin(), r.labels.end(), [](std::uint32_t l) { return l != 0; }));
    io::set_field(in, "label", r.labels);
    return {
        std::move(in),
        "wood_parts: " +
            (r.giants > 0 ? std::to_string(r.giants) + " part(s) of the wood's size and " +
                                std::to_string(r.dropped) + " coloured like them dropped"
             : r.dropped > 0
                 ? std::to_string(r.dropped) +
                       " small part(s) coloured apart from most dropped (pieces of wood)"
                 : std::string("no part of the wood's size coloured apart")) +
            ", " + std::to_string(r.count) + " clusters",
        {"wood_parts",
         n,
         kept,
         {{"giants", r.giants}, {"dropped", r.dropped}, {"colour_spread", r.fruit_colour_spread}},
         {}},
        {}};
}

namespace {

/// The value `name` the last such step of the chain recorded (dbscan's eps, the split's claimed
/// share): where the chain counted again (kMostlyWood), the count's own.
std::optional<double> step_value(const ChainResult& chain,
                                 const std::string& step,
                                 const std::string& name) {
    for (auto record = chain.steps.rbegin(); record != chain.steps.rend(); ++record) {
        for (const auto& [key, value] : record->values) {
            if (record->name == step && key == name) {
                return value;
            }
        }
    }
    return std::nullopt;
}

/// A colour class counted alone is the fruit when its fruit centres claimed at least this share
/// of its clustered points, and the other class's under kOtherClaims × that share. Over the 109
/// scenes of the condition matrix whose greens form two groups (session 29, green and lime fruit
/// among leaves): the fruit's class 0.60-1.0, the leaves' 0-0.72; in 105 the leaves' under half
/// the fruit's (0-0.43), in the other 4 0.50-0.72 (every saturated point is counted, as before).
constexpr double kFruitClaims = 0.5;
constexpr double kOtherClaims = 0.5;

/// The rule's groups are tried where its fruit centres claim under this share of its points
/// (kEpsSensitive's: below it DBSCAN's clusters make part of the count): fruit alone 0.6-1.0 (as
/// kFruitClaims' classes); fruit with their tree's bark 0.35-0.56 on the matrix's wood part, but
/// up to 0.82 where the bark's pieces got centres of their own (held-out-17 to 19, session 33:
/// 2222 claimed 0.73 with 28 bark parts counted as fruit). At 0.6 then, 0.9 now: all 2240 scenes
/// 0.955 -> 0.958, off by more than 20 % 138 -> 118, 69 up by more than 0.02 F1 and 3 down (a
/// group of the fruit alone changed their fruit radius at 2-3 spacings). Groups kept that are
/// claimed under it are looked into the same way (fruit_group in by_shape).
constexpr double kDoubtfulRule = 0.9;

/// ... and a group is kept where the other's centres claim under this share of its claim: a group
/// of bark alone claimed 0-2 %, one of fruit cut by the split of its colours (dark red fruit
/// whose hues straddle it) about a third.
constexpr double kBarkClaims = 0.25;

/// The rule in doubt is judged as it will be counted: where the wood step finds its points mostly
/// wood and counts the rest again (with_wood), by that count's claim, when the points counted again
/// are at least this share of the rule's (small fruit beside a trunk in their own hues: brown
/// acerola-like fruit beside near-black bark in SfM at 20 spacings, matrix scene 5209: the rule's
/// run claimed 19 %, its shell too thin for fruit (judged 0 %), and 96 % counted again; the green
/// points, the leaves, were counted instead, 10 of 200; counted as the rule, 200). Below it the
/// rule's points are the bark and what the wood step leaves are its crumbs (green fruit, the
/// greens' claim beaten by the crumbs' 37-69 % from 0.8-2 % of the rule's points: 3316
/// currant-like 178 -> 163 of 200, 4562 cucumber-like 73 -> 120 of 60; the rules kept and judged
/// again read 12-22 %). Session 62, 182 scenes beside wood.
constexpr double kWoodJudged = 0.05;

/// A run whose parts fill under this share of a ball of its radius in a solid cloud claims
/// nothing here: the tree's wood counted alone (a few "fruit" the size of the tree) filled
/// 0.002-0.11; fruit surfaces at 3-5 spacings read as solid 0.26-0.31 (at kTooFewForABall, 0.36,
/// the rule's fruit lost to the green points: 198 -> 2 of 200 grapes).
constexpr double kNoBall = 0.15;
/// ... and in a surface cloud, parts holding under this share of a sphere's surface of its
/// radius (4π (R/s)² points): over the 1164 surface scenes of the matrix counted within 20 %
/// (session 32) the median part held 0.061-1.1 of it (0.098 at the first percentile); the wood
/// counted alone as one "fruit" the size of the tree, 0.013 (1887: 1 counted of 50).
constexpr double kNoShell = 0.03;
/// The pale points counted (all of them, or a group of them) whose spacing is over this many
/// times the cloud's are a scatter of stray colours, no fruit's surface (pale_fruit in
/// by_shape), and the pale points are not counted. Over 958 matrix scenes (every one under
/// colour noise, and those whose pale points were counted; session 65) the pale run kept read
/// 0.79-1.99 times in 122, and 13.8 in 5467 (kiwi-brown fruit beside bark of their colour: 1385
/// counted of 200; tested on the pale groups only until then). A test of the path, not of one
/// candidate: as a test in claims() of every candidate (session 43), the scattered group
/// claimed nothing, its sibling then passed as the group whose other claims little, and 2958
/// went 120 -> 127 of 120; a scattered group's claim says the colours' split is no clean one.
constexpr double kScattered = 4;
/// The green points are kept instead of the rule where their centres claim at least this much
/// more of their points.
constexpr double kClaimsMore = 0.1;
constexpr const char* kBarkKept =
    "the colour rule's points look like bark, not fruit (its fruit centres claim few of them): "
    "the green points were counted instead (green fruit among leaves); check the count, or give "
    "--fruit-color";

constexpr const char* kPaleKept =
    "the colour rule's saturated points look like bark or leaves, not fruit (its fruit centres "
    "claim few of them): the pale points were counted instead (cream or pale fruit); check the "
    "count, or give --fruit-color";

constexpr const char* kTooLarge =
    "the fruit radius is over a tenth of the spread of the points counted: a cloud of a few "
    "fruit, or what was counted is no fruit (the ground, a trunk); check the count, or give "
    "--fruit-color or --fruit-radius";

/// The run a colour candidate kept whose fruit centres claim under this share of its points is
/// split again with R measured without the points on branches (segmentation::SphereVoteParams::
/// branch_below): the candidates compete with R as first measured, as the claims above were
/// judged (with the recheck in every candidate, a rule that kept the wood claimed more and hid
/// a group of the fruit alone: 148 -> 326 of 150, docs/robustness-history.md, session 35).
constexpr double kBranchAgain = 0.5;

/// A colour candidate's points are no fruit where their fruit radius is over this share of the
/// diagonal of the box holding the middle 98 % of them along each axis: a tree's fruit are many
/// times smaller than it, while a lone blob (the ground, a trunk counted alone) is claimed whole
/// by a few centres of its own size. On the matrix: the dark ground as one "fruit" 0.51 and 0.56
/// (the pale points beside bark, 1887 and 2391: 50 and 90 counted as 1), a dense SfM trunk (a
/// group of the "not foliage" rule, 2842: R 0.207, 7 centres claiming 87 %, 6 counted of 120);
/// cream fruit 0.012.
constexpr double kLargestFruit = 0.1;

/// The diagonal of the box holding the middle 98 % of `cloud`'s points along each axis (stray
/// outliers aside; non-finite coordinates ignored); 0 for an empty cloud. Read on an even stride
/// of about kSpreadSample points: a 1 % tail needs no more (every point of a 1M-point cloud
/// took 0.1 s of its 1.4 s count, a candidate's spread being read several times).
constexpr std::size_t kSpreadSample = 100000;
double spread(const io::Blob& cloud) {
    if (cloud.size() == 0) {
        return 0;
    }
    const io::XyzPoints points(cloud);
    const XyzView& v = points.view();
    const std::size_t stride = std::max<std::size_t>(1, v.size / kSpreadSample);
    double d2 = 0;
    std::vector<double> along((v.size + stride - 1) / stride);
    for (int a = 0; a < 3; ++a) {
        for (std::size_t i = 0; i < along.size(); ++i) {
            const pcl::PointXYZ q = v[i * stride];
            along[i] = a == 0 ? q.x : a == 1 ? q.y : q.z;
        }
        const double lo = percentile_of_finite(along, 1), hi = percentile_of_finite(along, 99);
        d2 += std::isfinite(hi - lo) ? (hi - lo) * (hi - lo) : 0.0;
    }
    return std::sqrt(d2);
}

/// The foliage-green points are counted with the rule's where this share of them or more lies
/// on the rule's fruit (share_near_parts: within about a fruit radius of a counted part's
/// points), in a cloud whose rule is clean fruit (its centres claim kDoubtfulRule of its points
/// or more): a cloud of fruit alone (segmented or cropped, no leaves) whose fruit are partly
/// green (Fuji and Gala apples: red over yellow-green), whose green side the rule drops, and
/// fruit blushed on a small cap then keep too few points to be found. Apple trees of 215
/// fruit, SfM at 75 spacings a radius, a red blush over 5-90 % of each yellow-green fruit and
/// no leaves: 0.95-1.0 of the green points near the parts; the matrix's leafy trees 0.02-0.08
/// (docs/robustness-history.md, session 54). The other way round as well: where the green
/// points win (the rule's, red caps on a few fruit, are claimed less) and the rule's points lie
/// on their fruit, the rule's are the fruit's other side, not bark (session 55).
constexpr double kOwnGreens = 0.5;
constexpr const char* kOwnGreensNote =
    " and the foliage-green points on its fruit (the fruit's own green side: ";
constexpr const char* kOwnBlushNote =
    " and the colour rule's points on their fruit (the fruit's own other side: ";

/// A run kept clearly (its centres claim kDoubtfulRule of its points or more) is counted again
/// with every saturated point that lies on its fruit (near_parts) where those are this share
/// more than its own points, and kept where claimed as clearly: fruit of two colours (green
/// ripening to red under a blush of 0-100 %, yellow-green under red) whose one side a group of
/// the colours kept, the fruit mostly of the other colour then found by a small cap or not at
/// all. The matrix's 4476 (cherry-like, a group of the yellow-green side claimed 94 %): 106 ->
/// 134 of 150; 4915 (tamarillo-like, the red side 92 %): 46 -> 54 of 68; of 609 scenes (500
/// natural-colour drawn at random and the blushed and ripening ones), 32 took it, 20 up by more
/// than 0.01 F1 and 3 down by under 0.02 (docs/robustness-history.md, session 60). Leafy trees
/// of fruit of one colour: the leaves near the fruit mostly lower the claim and the run stays;
/// where they do not (pale-green fruit, 31 of 73 took it) the parts take in the leaves touching
/// them: 5 up, 7 down, by at most 0.071 F1.
constexpr double kOtherSideAdds = 0.1;
constexpr const char* kOtherSideNote = " and the saturated points on its fruit (its other side: ";

/// Cubes r/2 wide that hold the points of the counted parts (label >= 1) of `labelled`: a point
/// is near them where its cube or one of the 26 around it holds one (within r/2 at least, 1.7 r
/// at most).
class NearParts {
public:
    NearParts(const io::Blob& labelled, double r) : cell_(0.5 * r) {
        const io::XyzPoints points(labelled);
        const std::vector<std::uint32_t> label = io::labels(labelled, "label");
        for (std::size_t i = 0; i < label.size(); ++i) {
            if (label[i] >= 1) {
                parts_.insert(key(points.view()[i], 0, 0, 0));
            }
        }
    }
    [[nodiscard]] bool near(const pcl::PointXYZ& q) const {
        for (int d = 0; d < 27; ++d) {
            if (parts_.count(key(q, d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1)) > 0) {
                return true;
            }
        }
        return false;
    }

private:
    [[nodiscard]] std::uint64_t key(const pcl::PointXYZ& q, int dx, int dy, int dz) const {
        const auto at = [&](float v, int d) {  // 21 bits an axis
            return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / cell_)) + d +
                                              (std::int64_t{1} << 20)) &
                   0x1FFFFFu;
        };
        return at(q.x, dx) << 42 | at(q.y, dy) << 21 | at(q.z, dz);
    }
    double cell_;
    std::unordered_set<std::uint64_t> parts_;
};

/// The share of the points of `cloud` (those of `which`, or all where it is null) that lie
/// within about `r` of a point of a counted part of `labelled` (NearParts). Judged on every k-th
/// point, kNearSample points at most (a share, not a tail: a leafy cloud of 1M points spent 4 %
/// of its time on every green point). 0 for no point or r <= 0.
constexpr std::size_t kNearSample = 10000;
double share_near_parts(const io::Blob& cloud,
                        const Indices* which,
                        const io::Blob& labelled,
                        double r) {
    const std::size_t n = which != nullptr ? which->size() : cloud.size();
    if (n == 0 || labelled.size() == 0 || !(r > 0)) {
        return 0;
    }
    const NearParts parts(labelled, r);
    const io::XyzPoints points(cloud);
    const XyzView& v = points.view();
    const std::size_t stride = std::max<std::size_t>(1, n / kNearSample);
    std::size_t near = 0, judged = 0;
    for (std::size_t k = 0; k < n; k += stride, ++judged) {
        near += parts.near(v[which != nullptr ? (*which)[k] : k]) ? 1 : 0;
    }
    return static_cast<double>(near) / static_cast<double>(judged);
}

/// The points of `which` in `cloud` that lie within about `r` of a point of a counted part of
/// `labelled` (NearParts), every one judged; none for r <= 0.
Indices near_parts(const io::Blob& cloud,
                   const Indices& which,
                   const io::Blob& labelled,
                   double r) {
    Indices out;
    if (which.empty() || labelled.size() == 0 || !(r > 0)) {
        return out;
    }
    const NearParts parts(labelled, r);
    const io::XyzPoints points(cloud);
    for (const std::uint32_t i : which) {
        if (parts.near(points.view()[i])) {
            out.push_back(i);
        }
    }
    return out;
}

/// A colour candidate kept: its run, the rule in words, the rule, and the share of its points
/// its fruit centres claim.
struct Kept {
    ChainResult run;
    std::string rule;
    const filters::ColorFilterParams* colour;
    double claim = 0;
};

using Progress = std::function<void(const std::string&)>;

/// run_chain() from the colour step on when the colours are natural (a rule, and other colour
/// classes to try: the rule's own groups, two groups of greens, the green points) and the split
/// is the spheres rule: the candidates counted alone, the one whose fruit centres claim its
/// points kept.
ChainResult by_shape(io::Blob in,
                     const ChainParams& p,
                     filters::FruitColorChoice c,
                     const Progress& progress);

/// run_chain() but its wood step (ChainParams::wood).
ChainResult chain_of(io::Blob in, const ChainParams& p, const Progress& progress = {});

/// run_chain()'s wood step on `out` (chain_of's result): the wood's parts dropped, and where it
/// dropped most counted points (kMostlyWood) the points beside the wood counted again.
ChainResult with_wood(ChainResult out, const ChainParams& p, const Progress& progress = {});

/// Appends step `s`'s record, note and warnings to `out`; returns its points.
io::Blob take(ChainResult& out, Step s, const Progress& progress) {
    out.steps.push_back(s.record);
    out.warnings.insert(out.warnings.end(), s.warnings.begin(), s.warnings.end());
    if (progress) {
        progress(s.note);
    }
    out.notes.push_back(std::move(s.note));
    return std::move(s.blob);
}

/// The chain from the crop step on, after the steps `out` holds, on `cur`.
ChainResult rest_of_chain(ChainResult out,
                          io::Blob cur,
                          const ChainParams& p,
                          const Progress& progress) {
    if (p.crop) {
        cur = take(out, apply_crop(std::move(cur), *p.crop), progress);
    }
    if (p.voxel) {
        cur = take(out, apply_voxel(std::move(cur), *p.voxel), progress);
    }
    if (p.knn) {
        cur = take(out, apply_knn_outlier(std::move(cur), *p.knn), progress);
    }
    cur = take(out, apply_dbscan(std::move(cur), p.dbscan, p.eps), progress);
    if (p.split) {
        cur = take(out, apply_recursive_split(std::move(cur), *p.split), progress);
    }
    out.labelled = std::move(cur);
    return out;
}

/// The chain after its colour step.
ChainResult chain_after(Step colour, const ChainParams& p, const Progress& progress) {
    ChainResult out;
    io::Blob cur = take(out, std::move(colour), progress);
    return rest_of_chain(std::move(out), std::move(cur), p, progress);
}

ChainResult chain_of(io::Blob in, const ChainParams& p, const Progress& progress) {
    // Colour decisions on each point's neighbourhood colour where the colours are noisy,
    // carried through the steps beside the cloud's own colours, which pass through untouched.
    if (std::optional<Smoothing> smooth = smooth_decisions(in, p, progress)) {
        ChainParams decided = p;
        decided.color_smooth.reset();
        ChainResult out = chain_of(std::move(in), decided, progress);
        smooth->finish(out.labelled, out.steps.front());
        return out;
    }
    if (p.color) {
        return chain_after(apply_color_filter(std::move(in), *p.color), p, progress);
    }
    if (p.fruit_color) {
        filters::FruitColorChoice c = choose_fruit_color(in, *p.fruit_color);
        if ((c.classes.size() == 2 || c.greens || c.pale) && p.split &&
            p.split->rule == segmentation::SplitRule::kSpheres) {
            return by_shape(std::move(in), p, std::move(c), progress);
        }
        return chain_after(apply_choice(std::move(in), std::move(c)), p, progress);
    }
    return rest_of_chain({}, std::move(in), p, progress);
}

/// Whether run_chain() ends with the wood step.
bool wood_step(const ChainParams& p) { return p.split && drops_wood(*p.split, p.wood); }

/// Where the wood step told the wood apart and dropped this share of the counted points or more,
/// the split had measured the fruit radius mostly on the wood: the points beside the wood (those
/// the wood step kept, and the first count's noise: at the wood's size small fruit are dropped
/// whole, as parts too small beside the median part; session 47) are counted again from DBSCAN
/// on, at their own spacing and fruit radius. On the 52 scenes of the matrix
/// whose wood step told a giant apart (session 43, by hand: the kept points recounted), the 12
/// that dropped 0.76-0.98 of the points: 10 up, among them small fruit beside a trunk in their
/// own hues (2453, currants of 2.2 mm beside near-black bark, split with R 9 mm: F1 0 -> 0.64;
/// 2825, 2911, 3207, 3212), 2 down by 0.005-0.01; 2 that dropped 0.68-0.69 went down (0.77 ->
/// 0.61, 0.85 -> 0.83). With the noise recounted too, over the 19 scenes of 3640 that recount
/// (session 47): 12 up by more than 0.01 F1 (3569, mulberries beside bark: 22 -> 127 of 160; 3212
/// 45 -> 104 of 120; 2453 108 -> 193 of 200), 2 down (2911 58 -> 20 of 80: 69 points more, and
/// its bunch recheck no longer took the smaller radius; 2825 93 -> 84 of 150).
constexpr double kMostlyWood = 0.75;

ChainResult with_wood(ChainResult out, const ChainParams& p, const Progress& progress) {
    const std::vector<std::uint32_t> labels =
        out.labelled.size() > 0 ? io::labels(out.labelled, "label") : std::vector<std::uint32_t>{};
    const auto counted = static_cast<std::size_t>(
        std::count_if(labels.begin(), labels.end(), [](std::uint32_t l) { return l != 0; }));
    out.labelled = take(out, apply_wood_parts(std::move(out.labelled), *p.wood), progress);
    const std::size_t by_wood = out.steps.back().points_out;  // the counted points it kept
    if (step_value(out, "wood_parts", "giants").value_or(0) > 0 && by_wood > 0 &&
        static_cast<double>(by_wood) <= (1 - kMostlyWood) * static_cast<double>(counted)) {
        // Every point but the wood's: the first count's noise too (at the wood's size it drops
        // small fruit whole as parts too small beside the median part).
        const std::vector<std::uint32_t> after = io::labels(out.labelled, "label");
        Indices kept;
        for (std::uint32_t i = 0; i < after.size(); ++i) {
            if (after[i] != 0 || labels[i] == 0) {
                kept.push_back(i);
            }
        }
        const double first = step_value(out, "recursive_split", "fruit_radius").value_or(0);
        ChainParams again = p;  // the points kept passed the steps before DBSCAN already
        again.crop.reset();
        again.voxel.reset();
        again.knn.reset();
        io::Blob recount = io::copy_points(out.labelled, kept);
        out = rest_of_chain(std::move(out), std::move(recount), again, progress);
        out.labelled = take(out, apply_wood_parts(std::move(out.labelled), *p.wood), progress);
        out.warnings.push_back(
            "the wood step dropped " + std::to_string(counted - by_wood) + " of " +
            std::to_string(counted) + " counted points: the fruit radius " + format_rounded(first) +
            " was measured mostly on the wood, and the " + std::to_string(kept.size()) +
            " points beside the wood (those it kept and the count's noise) were counted again "
            "(fruit radius " +
            format_rounded(step_value(out, "recursive_split", "fruit_radius").value_or(0)) +
            "); the warnings before this one are of the first count");
    }
    return out;
}

}  // namespace

ChainResult run_chain(io::Blob in, const ChainParams& p, const Progress& progress) {
    ChainResult out = chain_of(std::move(in), p, progress);
    return wood_step(p) ? with_wood(std::move(out), p, progress) : out;
}

namespace {

ChainResult by_shape(io::Blob in,
                     const ChainParams& p,
                     filters::FruitColorChoice c,
                     const Progress& progress) {
    // A cloud of over p.judge_points: the classes are judged on every `every`-th point, and the
    // one kept is counted on `all` the points.
    const std::size_t points_in = in.size();
    const std::size_t every =
        p.judge_points > 0 ? (points_in + p.judge_points - 1) / p.judge_points : 1;
    std::optional<io::Blob> all;
    if (every > 1) {
        Indices judged;
        judged.reserve(points_in / every + 1);
        for (std::size_t i = 0; i < points_in; i += every) {
            judged.push_back(static_cast<std::uint32_t>(i));
        }
        io::Blob few = io::copy_points(in, judged);
        all = std::move(in);
        in = std::move(few);
    }
    ChainParams rest = p;
    rest.fruit_color.reset();
    // The candidates compete with R as first measured (kBranchAgain): the claims that choose
    // between them were judged that way.
    rest.split->branch_recheck = false;
    // The share its fruit centres claimed; none when they are no fruit: parts far from filling
    // a ball (solid clouds) or a sphere's surface (surface clouds) of the fruit radius (the
    // tree's wood counted alone: a few "fruit" the size of the tree), or a fruit radius over
    // kLargestFruit of the points' spread.
    const auto too_large = [](const ChainResult& run) {
        const double r = step_value(run, "recursive_split", "fruit_radius").value_or(0);
        return r > kLargestFruit * spread(run.labelled);
    };
    const auto claims = [&](const ChainResult& run) {
        const auto ball = step_value(run, "recursive_split", "ball_fill");
        const auto shell = step_value(run, "recursive_split", "shell_fill");
        return (ball && *ball < kNoBall) || (shell && *shell < kNoShell) || too_large(run)
                   ? 0.0
                   : step_value(run, "recursive_split", "claimed").value_or(0);
    };
    // The claim of `run` counted again beside the wood (kWoodJudged), where the wood step does
    // so and keeps enough of its points; 0 otherwise.
    const auto claims_beside_wood = [&](const ChainResult& run) {
        const ChainResult judged = with_wood(run, p);
        std::vector<std::size_t> split_in;  // the points each split was handed
        for (const StepRecord& s : judged.steps) {
            if (s.name == "recursive_split") {
                split_in.push_back(s.points_in);
            }
        }
        return split_in.size() > 1 && static_cast<double>(split_in.back()) >=
                                          kWoodJudged * static_cast<double>(split_in.front())
                   ? claims(judged)
                   : 0.0;
    };
    // The chain on the points of `from` (the input, or a copy of a class's points that holds
    // them) that `rule` keeps, its colour step counted against the input.
    const auto count_class = [&](const io::Blob& from, const filters::ColorFilterParams& rule) {
        return chain_after(
            colour_step(io::copy_points(from, colour_kept(from, rule)), points_in, rule), rest, {});
    };
    // Two colour classes, each counted alone on `from`: the runs and their claims.
    const auto each_alone = [&](const std::vector<filters::ColourClass>& two,
                                const io::Blob& from) {
        std::pair<std::vector<ChainResult>, std::vector<double>> out;
        for (const filters::ColourClass& k : two) {
            out.first.push_back(count_class(from, k.rule));
            out.second.push_back(claims(out.first.back()));
        }
        return out;
    };
    const auto share = [](double x) { return format_number(std::round(100 * x)) + " %"; };
    // The run kept: where its centres claim few points, split again with R measured without
    // the points on branches (kBranchAgain); `before` go first among its warnings. Judged on
    // every `every`-th point, the class kept is counted on `all` of them, split again or not as
    // the judged run says.
    const auto done = [&](ChainResult out, const filters::ColorFilterParams* colour,
                          std::string rule, std::vector<std::string> before = {}) {
        ChainParams again = p;
        again.fruit_color.reset();
        const bool branches = colour != nullptr && p.split->branch_recheck && !p.crop && !p.voxel &&
                              !p.knn && claims(out) < kBranchAgain;
        if (all) {
            const ChainParams& q = branches ? again : rest;
            out = colour != nullptr
                      ? chain_after(apply_color_filter(std::move(*all), *colour), q, {})
                      : rest_of_chain({}, std::move(*all), q, {});
            rule += "; the classes judged on one point in " + std::to_string(every);
        } else if (branches) {
            const std::size_t n = out.steps.front().points_in;
            out = chain_after(colour_step(std::move(out.labelled), n, *colour), again, {});
        }
        if (too_large(out)) {
            before.push_back(kTooLarge);
        }
        out.warnings.insert(out.warnings.begin(), before.begin(), before.end());
        out.steps.front().rule = rule;
        out.notes.front() += " (" + rule + ")";
        if (progress) {
            for (const std::string& note : out.notes) {
                progress(note);
            }
        }
        return out;
    };
    // The fruit's two colour sides (kOwnGreens): where the points of `other` (those of `which`,
    // or all) lie on the fruit counted in `run`, every saturated point is counted, from the input
    // where it is intact, else from the points of `one` and `two` joined (each side's, a label
    // field dropped), and the run kept where its centres claim kDoubtfulRule of its points or
    // more (leaves or bark with the fruit lower the claim): the run and its rule's text, `reason`
    // (which ends in the note that opens the parenthesis) followed by the share near, the claim
    // and what it was compared with (`compared`).
    struct Sides {
        ChainResult run;
        std::string rule;
    };
    // Every saturated point, whatever its hue (the green points' rule without its hue band): both
    // colour sides of a fruit; none where the colours offer no green points.
    std::optional<filters::ColorFilterParams> saturated;
    if (c.greens) {
        saturated = c.greens->rule;
        saturated->hue_deg.reset();
    }
    const auto both_sides = [&](const ChainResult& run, const io::Blob& other, const Indices* which,
                                const io::Blob* one, const io::Blob* two, const std::string& reason,
                                const std::string& compared) -> std::optional<Sides> {
        const double r = step_value(run, "recursive_split", "fruit_radius").value_or(0);
        const double near = share_near_parts(other, which, run.labelled, r);
        if (!saturated || near < kOwnGreens) {
            return std::nullopt;
        }
        io::Blob joined;
        if (one == nullptr) {
            joined = io::copy_points(in, colour_kept(in, *saturated));
        } else {
            joined = *one;
            io::remove_field(joined, "label");
            std::optional<io::Blob> unlabelled;  // a copy only where `two` has labels
            if (io::find_field(*two, "label") != nullptr) {
                unlabelled = *two;
                io::remove_field(*unlabelled, "label");
            }
            if (!io::append_points(joined, unlabelled ? *unlabelled : *two)) {
                return std::nullopt;
            }
        }
        ChainResult both =
            chain_after(colour_step(std::move(joined), points_in, *saturated), rest, {});
        const double g = claims(both);
        if (g < kDoubtfulRule) {
            return std::nullopt;
        }
        return Sides{std::move(both), reason + share(near) +
                                          " of them lie on it; its fruit centres claim " +
                                          share(g) + " of the points, " + compared + ")"};
    };
    // The fruit's other side (kOtherSideAdds): a run kept clearly, counted again with every
    // saturated point lying on its fruit, where those add to its points and are claimed as
    // clearly. Not where the classes were judged on a share of the points (the near points are
    // those of the share).
    const auto other_side = [&](const Kept& k) -> std::optional<Sides> {
        if (!saturated || all || k.claim < kDoubtfulRule) {
            return std::nullopt;
        }
        const double r = step_value(k.run, "recursive_split", "fruit_radius").value_or(0);
        const Indices near = near_parts(in, colour_kept(in, *saturated), k.run.labelled, r);
        const auto had = static_cast<double>(k.run.steps.front().points_out);
        if (static_cast<double>(near.size()) < (1 + kOtherSideAdds) * had) {
            return std::nullopt;
        }
        ChainResult both =
            chain_after(colour_step(io::copy_points(in, near), points_in, *saturated), rest, {});
        const double g = claims(both);
        if (g < kDoubtfulRule) {
            return std::nullopt;
        }
        return Sides{std::move(both), k.rule + kOtherSideNote + share(near.size() / had - 1) +
                                          " more points; its fruit centres claim " + share(g) +
                                          " of them)"};
    };
    const auto kept_run = [&](Kept k) {
        if (auto both = other_side(k)) {
            return done(std::move(both->run), &*saturated, std::move(both->rule));
        }
        return done(std::move(k.run), k.colour, std::move(k.rule));
    };
    // Where the colours offer no groups, the rule, the green and the pale points are the only
    // candidates: the green and the pale points are set aside (a copy of each alone) and the rule
    // counted on the input itself, not on a copy of it (a cloud of 1M points would peak at over
    // 4 times its size).
    const bool offered = c.classes.size() == 2 || !c.rule_classes.empty();
    const auto aside = [&](const std::optional<filters::ColourClass>& k) {
        return !offered && k ? std::optional(io::copy_points(in, colour_kept(in, k->rule)))
                             : std::nullopt;
    };
    std::optional<io::Blob> greens = aside(c.greens);
    const std::optional<io::Blob> pale = aside(c.pale);
    std::optional<ChainResult> by_rule;
    double rule_claimed = 0;
    if (c.rule_competes || !offered || !c.rule_classes.empty()) {
        rest.color = c.rule;
        by_rule = offered ? chain_of(in, rest) : chain_of(std::move(in), rest);
        rule_claimed = claims(*by_rule);
        if (rule_claimed < kDoubtfulRule && wood_step(p)) {
            rule_claimed = std::max(rule_claimed, claims_beside_wood(*by_rule));
        }
    }
    // Bark or ground kept with the fruit: the rule's own groups, each counted alone, where its
    // centres claim few of its points; a group is the fruit where it is claimed as fruit are,
    // more than `than` (the rule's claim), and the other is claimed as bark is (kBarkClaims).
    // A group kept that is itself claimed little (fruit beside shaded bark whose dark points'
    // noisy hues reach the fruit's) gives way to one of its own groups claimed clearly more
    // (kClaimsMore: a group of the fruit's shaded or lit points alone is claimed a little more).
    // `first_claims`, when given, gets the first groups' claims.
    const auto fruit_group = [&](const std::vector<filters::ColourClass>* two, double than,
                                 std::vector<double>* first_claims, const io::Blob& from) {
        std::optional<Kept> kept;
        while (two != nullptr && !two->empty()) {
            auto [groups, g] = each_alone(*two, from);
            if (first_claims != nullptr) {
                *first_claims = g;
                first_claims = nullptr;
            }
            const std::size_t b = g[1] > g[0] ? 1 : 0;
            if (!(g[b] >= kFruitClaims && g[1 - b] < kBarkClaims * g[b] && g[b] > than)) {
                break;
            }
            kept.emplace(Kept{std::move(groups[b]),
                              (*two)[b].reason +
                                  ", the group whose fruit centres claim its points (" +
                                  share(g[b]) + "; " + share(g[1 - b]) + " of the other's, " +
                                  share(rule_claimed) + " of the rule's)",
                              &(*two)[b].rule, g[b]});
            than = g[b] + kClaimsMore;
            two = g[b] < kDoubtfulRule ? &(*two)[b].groups : nullptr;
        }
        return kept;
    };
    // Neither of two classes of `from` (claimed `claimed`) is kept: one may hold the fruit in its
    // own groups, where they are claimed more than `than` and their class by kClaimsMore.
    const auto within = [&](const std::vector<filters::ColourClass>& two,
                            const std::vector<double>& claimed, double than, const io::Blob& from) {
        std::optional<Kept> kept;
        for (std::size_t k = 0; k < two.size() && !kept; ++k) {
            kept = fruit_group(&two[k].groups, std::max(than, claimed.at(k) + kClaimsMore), nullptr,
                               from);
        }
        return kept;
    };
    // A group of the rule kept competes with the greens (green fruit among leaves beside bark:
    // a group of bark pieces may be claimed as fruit are, kFruitClaims, but less than the fruit).
    std::optional<Kept> ruled;
    if (!c.rule_classes.empty() && rule_claimed < kDoubtfulRule) {
        std::vector<double> claimed;
        ruled = fruit_group(&c.rule_classes, rule_claimed, &claimed, in);
        if (!ruled && rule_claimed < kFewClaimed) {  // and the rule far from fruit
            ruled = within(c.rule_classes, claimed, rule_claimed + kClaimsMore, in);
        }
    }
    const double beat = ruled ? ruled->claim : rule_claimed;  // what the greens must beat
    const auto ruled_run = [&] { return done(std::move(ruled->run), ruled->colour, ruled->rule); };
    if (ruled && ruled->claim >= kDoubtfulRule) {
        return kept_run(std::move(*ruled));
    }
    // Pale fruit (under the saturation line: cream, lavender, mint): the rule kept the bark or
    // the leaves, or is claimed in doubt (kDoubtfulRule: mint fruit among leaves whose lit points
    // pass the rule, claimed 51-76 %). The run of the pale points, where their centres claim as
    // fruit's do and more than `than`; where the rule is far from fruit (kFewClaimed), of one of
    // their own groups (the fruit beside dark ground) where it is claimed more.
    const auto pale_fruit = [&](double than) -> std::optional<ChainResult> {
        if (!c.pale || rule_claimed >= kDoubtfulRule) {
            return std::nullopt;
        }
        // ... and always clearly more than the rule (against a group of it, the group's claim is
        // `than`: grey-blue dates in SfM whose pale points were claimed 87 %, the rule 89.6 %,
        // 1665: 152 -> 105 of 150 where they were kept).
        than = std::max(than, rule_claimed + kClaimsMore);
        const io::Blob& from = pale ? *pale : in;
        ChainResult run = count_class(from, c.pale->rule);
        const double g = claims(run);
        // The pale points counted are a surface, not a scatter of stray colours (under colour
        // noise a few of the saturated fruit's and bark's points pass for pale, far apart):
        // their points lie within kScattered times the spacing of the denser of the rule's and
        // the pale points (2958, tan fruit under colour noise 25: a group of them 17 times
        // further apart than the rule's points was claimed 72 %, 1852 counted of 120; 5467,
        // kiwi-brown fruit the bark's colour under colour noise 25: all of them, 14 times, 57 %,
        // 1385 of 200; the pale fruit counted, 0.79-1.99: kScattered).
        const auto spacing = [](const ChainResult& r) {
            return step_value(r, "dbscan", "spacing").value_or(0);
        };
        const double own = spacing(run), of_rule = by_rule ? spacing(*by_rule) : 0.0;
        const double dense = own > 0 && of_rule > 0 ? std::min(own, of_rule)  // 0: unknown
                                                    : std::max(own, of_rule);
        std::optional<Kept> kept;
        if (!(g >= kFruitClaims && g > than)) {
            // (A rule claimed as fruit's are, more than kFewClaimed, is not given up for a group
            // of the pale points: the grey bark's lit pieces beside chartreuse fruit at 2
            // spacings, claimed 71 % against the rule's group's 59 %, 3305: 40 -> 17 of 49.)
            if (rule_claimed >= kFewClaimed) {
                return std::nullopt;
            }
            // Bark as unsaturated as the fruit (grey-brown beside cream) is among the pale
            // points, claimed little together: one of their groups, or of a group's own groups
            // (their hues split the greys, their values the lit fruit from the dark bark), may
            // be the fruit.
            std::vector<double> claimed;
            than = std::max(than, g + kClaimsMore);
            kept = fruit_group(&c.pale->groups, than, &claimed, from);
            if (!kept && !claimed.empty()) {
                kept = within(c.pale->groups, claimed, than, from);
            }
            if (!kept) {
                return std::nullopt;
            }
        } else if (g < kDoubtfulRule) {
            kept = fruit_group(&c.pale->groups, g + kClaimsMore, nullptr, from);
        }
        if (!kept) {
            kept.emplace(Kept{std::move(run),
                              c.pale->reason + " (their fruit centres claim " + share(g) +
                                  " of their points, " + share(rule_claimed) + " of the rule's)",
                              &c.pale->rule, g});
        }
        if (dense > 0 && spacing(kept->run) > kScattered * dense) {
            return std::nullopt;
        }
        return done(std::move(kept->run), kept->colour, kept->rule, {kPaleKept});
    };
    // Green fruit beside bark: the rule kept the bark (its centres claim under kDoubtfulRule of
    // its points: a rule smoothed over noisy colours keeps some of the fruit's darker side too,
    // claimed 45 %) and the greens form no two groups: the green points, where their centres
    // claim more by kClaimsMore, and more than the pale points'.
    if (c.greens && c.classes.size() != 2 && rule_claimed < kDoubtfulRule) {
        ChainResult green = count_class(greens ? *greens : in, c.greens->rule);
        const double g = claims(green);
        if (auto out = pale_fruit(std::max(g, beat + kClaimsMore))) {
            return std::move(*out);
        }
        // ... and the rule's points, where they lie on the green fruit: the fruit's other side
        // (yellow-green fruit under a red blush on a small cap), not bark.
        std::optional<Sides> both;
        if (g > beat + kClaimsMore && by_rule) {
            both = both_sides(green, by_rule->labelled, nullptr, greens ? &*greens : nullptr,
                              &by_rule->labelled, c.greens->reason + kOwnBlushNote,
                              share(g) + " of the green points'");
        }
        greens.reset();
        if (both) {
            return done(std::move(both->run), &*saturated, std::move(both->rule), c.warnings);
        }
        if (g > beat + kClaimsMore) {
            return done(std::move(green), &c.greens->rule,
                        c.greens->reason + " (their fruit centres claim " + share(g) +
                            " of their points, " + share(rule_claimed) + " of the rule's)",
                        {kBarkKept});
        }
    } else if (c.classes.size() != 2) {
        if (auto out = pale_fruit(beat + kClaimsMore)) {
            return std::move(*out);
        }
    }
    if (ruled && c.classes.size() != 2) {
        return ruled_run();
    }
    // The rule is clean fruit and its green points lie on its fruit: the fruit's green side.
    if (by_rule && c.greens && rule_claimed >= kDoubtfulRule &&
        (c.classes.size() != 2 || c.rule_first)) {
        const Indices green = greens ? Indices{} : colour_kept(in, c.greens->rule);
        const std::string reason = c.reason + kOwnGreensNote;
        const std::string compared = share(rule_claimed) + " of the rule's";
        auto both = greens ? both_sides(*by_rule, *greens, nullptr, &by_rule->labelled, &*greens,
                                        reason, compared)
                           : both_sides(*by_rule, in, &green, nullptr, nullptr, reason, compared);
        if (both) {
            return done(std::move(both->run), &*saturated, std::move(both->rule), c.warnings);
        }
    }
    if (c.classes.size() != 2 || (c.rule_first && rule_claimed >= kDoubtfulRule)) {
        return done(std::move(*by_rule), c.rule ? &*c.rule : nullptr,
                    c.reason + (too_large(*by_rule)
                                    ? " (its fruit radius is over a tenth of its points' spread)"
                                    : " (its fruit centres claim " + share(rule_claimed) +
                                          " of its points)"),
                    c.warnings);
    }
    auto [runs, claimed] = each_alone(c.classes, in);
    const std::size_t best = claimed[1] > claimed[0] ? 1 : 0, other = 1 - best;
    const std::string of_rule =
        c.rule_competes ? ", " + share(rule_claimed) + " of the rule's" : "";
    const bool kept_best = claimed[best] >= kFruitClaims &&
                           claimed[other] < kOtherClaims * claimed[best] &&
                           claimed[best] > (ruled ? beat + kClaimsMore : rule_claimed);
    if (ruled && !kept_best) {
        // ... unless the pale points are claimed clearly more than the rule's group kept (in
        // doubt here: one claimed kDoubtfulRule returned above; mint fruit: a group of the
        // saturated points claimed 54 %, the pale points 99 %).
        if (auto out = pale_fruit(beat + kClaimsMore)) {
            return std::move(*out);
        }
        return ruled_run();
    }
    // A class that is not the fruit alone (green fruit beside bark: a class of hue holds the fruit
    // and the bark) may hold it in one of its own groups.
    runs[other] = {};
    std::optional<Kept> finer;
    if (kept_best && claimed[best] < kDoubtfulRule) {
        finer = fruit_group(&c.classes[best].groups, claimed[best] + kClaimsMore, nullptr, in);
    } else if (!kept_best) {
        runs.clear();
        finer = within(c.classes, claimed, rule_claimed + kClaimsMore, in);
    }
    if (finer) {
        return kept_run(std::move(*finer));
    }
    // Neither group is clearly the fruit (none kept, or the one kept is claimed under
    // kDoubtfulRule): pale fruit (sage, 150, 165, 130) whose colours lie within the foliage's
    // hues, where the saturated points' values offered the two groups, may be the pale points.
    if (!kept_best || claimed[best] < kDoubtfulRule) {
        if (auto out = pale_fruit(claimed[best] + kClaimsMore)) {
            return std::move(*out);
        }
    }
    if (kept_best) {
        return kept_run(Kept{std::move(runs[best]),
                             c.classes[best].reason +
                                 ", the group whose fruit centres claim its points (" +
                                 share(claimed[best]) + "; " + share(claimed[other]) +
                                 " of the other's" + of_rule + ")",
                             &c.classes[best].rule, claimed[best]});
    }
    const std::string each = " (each group counted alone: fruit centres claimed " +
                             share(claimed[0]) + " and " + share(claimed[1]) + " of their points" +
                             of_rule + ")";
    // Neither group is the fruit: green fruit darker than the leaves (hass, 55, 70, 45), whose
    // points fall with the shaded leaves and the bark in the darker group of value, may be the
    // green points, where their centres claim as a group kept must (kFruitClaims) and clearly
    // more than either group and the rule (kClaimsMore, as the greens where no groups are offered).
    if (c.greens) {
        ChainResult green = count_class(in, c.greens->rule);
        const double g = claims(green);
        if (g >= kFruitClaims && g > std::max(claimed[best], rule_claimed) + kClaimsMore) {
            return done(std::move(green), &c.greens->rule,
                        c.greens->reason + " (their fruit centres claim " + share(g) +
                            " of their points; " + each.substr(2),
                        {kBarkKept});
        }
    }
    if (!c.rule) {  // grey colours whose groups are no fruit: every point, as without groups
        c.reason += each;
        return chain_after(apply_choice(all ? std::move(*all) : std::move(in), std::move(c)), p,
                           progress);
    }
    rest.color = c.rule;
    ChainResult out = by_rule ? std::move(*by_rule) : chain_of(std::move(in), rest);
    return done(std::move(out), &*c.rule, c.reason + each, c.warnings);
}

}  // namespace

MarkedChain run_chain_marked(io::Blob in,
                             const ChainParams& p,
                             const std::function<void(const std::string&)>& progress) {
    if (p.voxel) {
        throw InvalidArgument(
            "the whole cloud cannot be labelled after a voxel step (its points are voxel "
            "centroids, not the input's): drop --leaf");
    }
    // Each point carries its index through the steps, which pass every field through.
    constexpr const char* kSource = "pc_source_index";
    const std::size_t n = in.size();
    std::vector<std::uint32_t> index(n);
    std::iota(index.begin(), index.end(), 0u);
    io::Blob work = in;
    io::set_field(work, kSource, index);
    MarkedChain out{run_chain(std::move(work), p, progress), std::move(in)};
    std::vector<std::uint32_t> labels(n, 0);
    io::Blob& labelled = out.chain.labelled;
    if (labelled.size() > 0) {
        const std::vector<std::uint32_t> source = io::labels(labelled, kSource);
        const std::vector<std::uint32_t> label = io::labels(labelled, "label");
        for (std::size_t j = 0; j < source.size(); ++j) {
            labels[source[j]] = label[j];
        }
    }
    io::remove_field(labelled, kSource);  // its bytes too: no `_` padding in the labelled cloud
    io::set_field(out.marked, "label", labels);
    return out;
}

segmentation::ClusterSummary summarize(const io::Blob& labelled, std::size_t min_points) {
    const auto labels =
        labelled.size() ? io::labels(labelled, "label") : std::vector<std::uint32_t>{};
    // A view of the points (a copy only when x y z are not F 4): no cloud of 16 bytes a point.
    return segmentation::summarize_clusters(io::XyzPoints(labelled).view(), labels, min_points);
}

bool eps_sensitive(const ChainResult& chain) {
    const std::optional<double> claimed = step_value(chain, "recursive_split", "claimed");
    return claimed && *claimed < kEpsSensitive;
}

EpsCheck check_eps(const ChainResult& chain,
                   const ChainParams& p,
                   const std::vector<double>& factors) {
    const io::Blob& labelled = chain.labelled;
    const double eps_used = step_value(chain, "dbscan", "eps").value_or(p.dbscan.eps);
    std::vector<double> tried = factors;
    tried.push_back(1.0);
    std::sort(tried.begin(), tried.end());
    EpsCheck out;
    const Cloud points = labelled.size() ? io::xyz(labelled) : Cloud{};
    for (double f : tried) {
        std::size_t count = 0;
        if (f == 1.0) {
            count = summarize(labelled, p.count_min_points).clusters.size();
        } else if (!points.empty()) {
            segmentation::DbscanParams d = p.dbscan;
            d.eps = f * eps_used;
            std::vector<std::uint32_t> labels = segmentation::dbscan(points, d).labels;
            if (p.split) {
                labels = segmentation::recursive_split(XyzView(points), std::move(labels), *p.split)
                             .labels;
            }
            if (wood_step(p) && wood_coloured(labelled)) {
                labels =
                    filters::wood_parts(io::colours(labelled), std::move(labels), *p.wood).labels;
            }
            count = segmentation::summarize_clusters(XyzView(points), labels, p.count_min_points)
                        .clusters.size();
        }
        out.eps.push_back(f * eps_used);
        out.counts.push_back(count);
    }
    const auto [lo, hi] = std::minmax_element(out.counts.begin(), out.counts.end());
    if (*hi > 2 * *lo) {
        std::string counts;
        for (std::size_t k = 0; k < out.counts.size(); ++k) {
            counts += (k ? ", " : "") + std::to_string(out.counts[k]) + " at eps " +
                      format_rounded(out.eps[k]);
        }
        out.warning = "the count swings by more than 2x under a small change of eps (" + counts +
                      (p.eps.mode == EpsRule::Mode::kSpacing
                           ? "): it depends on which points DBSCAN joins (scan lines, gaps "
                             "between fruit); treat it as rough"
                           : "): eps is near a scale of this cloud; try --eps auto");
    }
    return out;
}

std::vector<std::string> count_warnings(const segmentation::ClusterSummary& s, std::size_t points) {
    std::vector<std::string> w;
    if (s.clusters.empty() && points > 0) {
        w.push_back("no cluster counted in a cloud of " + std::to_string(points) +
                    " points: see the steps' points in and out");
    }
    // Below about 40 points a fruit is 2 point spacings in radius or less: touching fruit merge
    // or split by chance (docs/robustness.md: F1 about 0.55 there, 0.94 and more from 3).
    std::vector<double> sizes;
    for (const auto& c : s.clusters) {
        sizes.push_back(static_cast<double>(c.points));
    }
    const double typical = sizes.empty() ? 0.0 : median(sizes);
    if (!sizes.empty() && typical < 40) {
        w.push_back("the median cluster has only " + format_rounded(typical) +
                    " points: at this resolution touching fruit merge or split by chance; treat "
                    "the count as rough");
    }
    return w;
}

}  // namespace pc::pipeline
