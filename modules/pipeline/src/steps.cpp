#include <cmath>
#include <limits>

#include <nlohmann/json.hpp>

#include <pc/core/error.h>
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

}  // namespace

Step apply_color_filter(io::Blob in, const filters::ColorFilterParams& p) {
    p.validate();
    // io::colours() rejects a non-empty cloud without colour; an empty one passes through.
    const auto kept = in.size() == 0 ? Indices{} : filters::color_filter(io::colours(in), p).kept;
    std::string note = kept_note("color_filter", kept.size(), in.size());
    io::keep_points(in, kept);
    return {std::move(in), std::move(note)};
}

Step apply_crop(io::Blob in, const filters::CropParams& p) {
    const auto kept = filters::crop(io::XyzPoints(in).view(), p).kept;
    std::string note = kept_note("crop", kept.size(), in.size());
    io::keep_points(in, kept);
    return {std::move(in), std::move(note)};
}

Step apply_voxel(io::Blob in, const filters::VoxelParams& p) {
    const filters::VoxelResult v = filters::voxel_downsample(io::XyzPoints(in).view(), p);
    return {io::aggregate(in, v.voxel, v.count), "voxel: " + std::to_string(in.size()) +
                                                     " points into " + std::to_string(v.count) +
                                                     " voxels of " + format_number(p.leaf)};
}

Step apply_knn_outlier(io::Blob in, const filters::KnnOutlierParams& p, const KnnOutput& o) {
    const filters::KnnOutlierResult r = filters::knn_outlier(io::XyzSortable(in).records(), p);
    std::size_t outliers = 0;
    for (auto f : r.outlier) {
        outliers += f;
    }
    const std::string note = "knn_outlier: threshold " + format_number(r.threshold) + ", " +
                             std::to_string(outliers) + " of " + std::to_string(in.size()) +
                             " points are outliers";
    if (!o.mark_field.empty()) {
        const std::vector<std::uint32_t> mark(r.outlier.begin(), r.outlier.end());
        io::set_field(in, o.mark_field, mark);
        return {std::move(in), note};
    }
    io::keep_flagged(in, r.outlier, o.invert);  // the outliers when inverted, else the inliers
    return {std::move(in), note};
}

Step apply_dbscan(io::Blob in, segmentation::DbscanParams p, const EpsRule& eps) {
    std::string note;
    if (eps.mode == EpsRule::Mode::kKnee) {
        p.eps = segmentation::estimate_eps(io::XyzPoints(in).view(), p.min_points);
        note = "dbscan: eps auto (knee) = " + format_number(p.eps) + "; ";
    } else if (eps.mode == EpsRule::Mode::kSpacing) {
        const double s = search::median_spacing(io::XyzPoints(in).view());
        // Fewer than two distinct points: no spacing; only coincident points can be neighbours.
        p.eps = s > 0 ? eps.factor * s : std::numeric_limits<double>::min();
        note = "dbscan: eps = " + format_number(eps.factor) + " x spacing " + format_number(s) +
               " = " + format_number(p.eps) + "; ";
    }
    const segmentation::DbscanResult r = segmentation::dbscan(io::XyzSortable(in).records(), p);
    std::size_t noise = 0;
    for (auto l : r.labels) {
        noise += l == segmentation::kNoise;
    }
    note += "dbscan: " + std::to_string(r.cluster_count) + " clusters, " + std::to_string(noise) +
            " noise points (eps " + format_number(p.eps) + ", min_points " +
            std::to_string(p.min_points) + ")";
    io::set_field(in, "label", r.labels);
    return {std::move(in), note};
}

Step apply_recursive_split(io::Blob in, const segmentation::RecursiveSplitParams& p) {
    segmentation::RecursiveSplitResult r =
        segmentation::recursive_split(io::XyzPoints(in).view(), io::labels(in, "label"), p);
    io::set_field(in, "label", r.labels);
    const std::string how =
        p.rule == segmentation::SplitRule::kCores
            ? "clusters cut at their cores" + std::string(" (spacing ") + format_number(r.spacing) +
                  ", estimated fruit radius " + format_number(r.fruit_radius) +
                  (r.hollow_radius > 0 ? ", on hollow surfaces " + format_number(r.hollow_radius)
                                       : "") +
                  ")"
            : "splits (thresholds: points > " + format_number(r.size_threshold) +
                  ", AABB volume > " + format_number(r.volume_threshold) + ")";
    return {std::move(in), "recursive_split: " + std::to_string(r.splits) + " " + how + ", " +
                               std::to_string(r.cluster_count) + " clusters"};
}

ChainResult run_chain(io::Blob in,
                      const ChainParams& p,
                      const std::function<void(const std::string&)>& progress) {
    ChainResult out;
    io::Blob cur = std::move(in);
    const auto take = [&](Step s) {
        cur = std::move(s.blob);
        if (progress) {
            progress(s.note);
        }
        out.notes.push_back(std::move(s.note));
    };
    if (p.color) {
        take(apply_color_filter(std::move(cur), *p.color));
    }
    if (p.crop) {
        take(apply_crop(std::move(cur), *p.crop));
    }
    if (p.voxel) {
        take(apply_voxel(std::move(cur), *p.voxel));
    }
    if (p.knn) {
        take(apply_knn_outlier(std::move(cur), *p.knn));
    }
    take(apply_dbscan(std::move(cur), p.dbscan, p.eps));
    if (p.split) {
        take(apply_recursive_split(std::move(cur), *p.split));
    }
    out.labelled = std::move(cur);
    return out;
}

segmentation::ClusterSummary summarize(const io::Blob& labelled, std::size_t min_points) {
    const auto labels =
        labelled.size() ? io::labels(labelled, "label") : std::vector<std::uint32_t>{};
    // A view of the points (a copy only when x y z are not F 4): no cloud of 16 bytes a point.
    return segmentation::summarize_clusters(io::XyzPoints(labelled).view(), labels, min_points);
}

std::string count_report(const segmentation::ClusterSummary& s, std::optional<double> gt) {
    using nlohmann::ordered_json;
    ordered_json j;
    j["count"] = s.clusters.size();
    if (gt) {
        j["gt"] = *gt;
        j["error"] = static_cast<double>(s.clusters.size()) - *gt;
        j["recovery"] = *gt > 0 ? ordered_json(static_cast<double>(s.clusters.size()) / *gt)
                                : ordered_json(nullptr);
    }
    j["noise_points"] = s.noise_points;
    j["small_clusters"] = s.small_clusters;
    ordered_json cl = ordered_json::array();
    for (const auto& c : s.clusters) {
        cl.push_back({{"id", c.id},
                      {"points", c.points},
                      {"centroid", c.centroid},
                      {"aabb", {{"min", c.min}, {"max", c.max}}}});
    }
    j["clusters"] = cl;
    return j.dump(1) + "\n";
}

}  // namespace pc::pipeline
