// pc_lift: 2D fruit masks of calibrated views lifted onto the cloud's points by majority vote
// (paper 2.3.1).
#include <algorithm>
#include <filesystem>
#include <string>

#include <pc/cameras/lift.h>
#include <pc/cameras/read_cameras.h>
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/io/blob.h>
#include <pc/io/points.h>
#include <pc/search/spacing.h>

#include "images.h"

namespace cam = pc::cameras;
namespace fs = std::filesystem;

namespace {

/// pc_lift warns when more of the fruit points than this have a doubtful label. On the scenes of
/// bench/instances.sh the share is at most 0.08 where F1 >= 0.89 and 0.23-0.65 where 3-5 of 8 views
/// merge every touching instance (F1 0.35-0.91); one scene there (F1 0.73) stays under it (0.08).
constexpr double kDoubtful = 0.15;

/// A binary mask (FruitNeRF's rules) or, with `instances`, a PNG of instance ids.
cam::Mask read_mask(const std::string& path, bool instances) {
    const cv::Mat m = pc::tools::read_image(path);
    cam::Mask out{m.cols, m.rows, {}};
    if (instances) {
        const std::vector<std::uint32_t> ids = pc::tools::instance_ids(m, path);
        out.id.assign(ids.begin(), ids.end());  // one channel of at most 16 bits
    } else {
        const std::vector<std::uint8_t> fruit = pc::tools::binary_mask(m, path);
        out.id.assign(fruit.begin(), fruit.end());
    }
    return out;
}

/// The mask file of a view: DIR/<stem of its image>.png|.jpg|.jpeg with --masks DIR, else the
/// source's mask_path / semantic_path, relative to the camera file's directory.
std::string mask_path(const cam::View& v, const std::string& masks_dir, const fs::path& base) {
    if (!masks_dir.empty()) {
        const std::string stem = fs::path(v.image).stem().string();
        for (const char* ext : {".png", ".jpg", ".jpeg", ".PNG", ".JPG"}) {
            const fs::path p = fs::path(masks_dir) / (stem + ext);
            std::error_code ec;
            if (fs::exists(p, ec)) {
                return p.string();
            }
        }
        throw pc::IoError(masks_dir + ": no mask " + stem + ".png or .jpg for image " + v.image);
    }
    if (v.mask.empty()) {
        throw pc::IoError(v.image +
                          ": the camera file names no mask for this view; give --masks DIR");
    }
    const fs::path m(v.mask);
    return m.is_absolute() ? m.string() : (base / m).lexically_normal().string();
}

}  // namespace

int main(int argc, char** argv) {
    std::string cameras_path, masks_dir, dataparser;
    bool colmap_frame = false;
    double spacing = 0;
    cam::LiftParams p;
    pc::cli::Tool tool("pc_lift",
                       "lift 2D fruit masks of calibrated views onto the points: add fields views "
                       "(views that see the point), votes (of those, views whose mask covers it) "
                       "and fruit (1 iff votes/views >= --min-ratio and views >= --min-views)");
    tool.option("cameras", &cameras_path,
                "camera file: nerfstudio / instant-ngp transforms.json, or a COLMAP sparse model "
                "directory (cameras and images, .txt or .bin)");
    tool.option("masks", &masks_dir,
                "mask directory: DIR/<stem of the image name>.png|.jpg; default: each frame's "
                "mask_path or semantic_path");
    tool.option("min-ratio", &p.min_ratio, "fruit iff votes / views >= this");
    tool.option("min-views", &p.min_views, "... and at least this many views see the point");
    tool.flag("instances", &p.instances,
              "the masks are instance ids (PNG, one channel, 8 or 16 bits, 0 = no fruit): also "
              "join each view's instances into 3D fruit, written as field label (0 = not fruit)");
    tool.option("spacing", &spacing,
                "point spacing in cloud units (splat size, depth tolerance); 0: the median "
                "nearest-neighbour distance");
    tool.option("footprint", &p.visibility.footprint,
                "x spacing: the radius of surface a point covers in the z-buffer");
    tool.option("depth-tolerance", &p.visibility.depth_tolerance,
                "x spacing: a point is seen when at most this behind the nearest surface");
    tool.flag("colmap-frame", &colmap_frame,
              "the cloud is in COLMAP's world frame while the cameras come from a transforms.json "
              "with applied_transform (ns-process-data): undo it for the cameras");
    tool.option("dataparser", &dataparser,
                "nerfstudio's dataparser_transforms.json: the cloud is in the frame nerfstudio "
                "trains and exports in (ns-export); the cameras are moved into it");
    tool.epilog(
        "\nMasks: JPEG fruit where > 125, PNG where not 0 (binary or instance ids).\n"
        "With --instances: pc_count counts the labels, pc_eval scores them.\n"
        "See docs/tools/pc_lift.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (cameras_path.empty()) {
            throw pc::InvalidArgument(
                "--cameras is required (a transforms.json or a COLMAP model)");
        }
        p.validate();
        if (spacing < 0) {
            throw pc::InvalidArgument("--spacing must be >= 0 (0: measured), got " +
                                      pc::format_number(spacing));
        }
        cam::Dataset ds = cam::read_cameras(cameras_path);
        if (colmap_frame) {
            if (!ds.applied) {
                throw pc::InvalidArgument(cameras_path +
                                          " has no applied_transform: "
                                          "--colmap-frame needs one");
            }
            for (cam::View& v : ds.views) {
                v = cam::moved(v, ds.applied->inverse());
            }
        }
        if (!dataparser.empty()) {
            const cam::Similarity s = cam::read_dataparser_transforms(dataparser);
            for (cam::View& v : ds.views) {
                v = cam::moved(v, s);
            }
        }
        std::error_code ec;
        const fs::path base = fs::is_directory(cameras_path, ec)
                                  ? fs::path(cameras_path)
                                  : fs::path(cameras_path).parent_path();
        std::vector<std::string> masks;
        for (const cam::View& v : ds.views) {
            masks.push_back(mask_path(v, masks_dir, base));
        }
        pc::io::Blob blob = io.read();
        const pc::io::XyzPoints points(blob);
        if (spacing == 0) {
            spacing = pc::search::median_spacing(points.view());
            if (!(spacing > 0)) {
                throw pc::IoError(
                    "cannot measure the point spacing (fewer than two distinct "
                    "points): give --spacing");
            }
        }
        io.note("spacing " + pc::format_number(spacing) + ", " + std::to_string(ds.views.size()) +
                " views");
        std::size_t step = std::max<std::size_t>(1, ds.views.size() / 10);
        const cam::LiftResult r = cam::lift(
            points.view(), ds.views,
            [&](std::size_t k) { return read_mask(masks[k], p.instances); }, spacing, p,
            [&](std::size_t done, std::size_t total) {
                if (done % step == 0 || done == total) {
                    io.note("view " + std::to_string(done) + " of " + std::to_string(total));
                }
            });
        std::size_t seen = 0, fruit = 0;
        for (std::size_t i = 0; i < r.views.size(); ++i) {
            seen += r.views[i] > 0;
            fruit += r.fruit[i];
        }
        io.note(std::to_string(seen) + " of " + std::to_string(r.views.size()) + " points seen, " +
                std::to_string(fruit) + " fruit");
        if (blob.size() > 0 && seen == 0) {
            io.warn(
                "no camera sees any point: are the cloud and the cameras in the same frame "
                "(--colmap-frame, --dataparser) and units?");
        } else if (seen > 0 && fruit == 0) {
            io.warn(
                "no point is fruit: do the masks mark fruit as non-zero (PNG) or > 125 (JPEG)?");
        }
        std::vector<std::uint32_t> flag(r.fruit.begin(), r.fruit.end());
        pc::io::set_field(blob, "views", r.views);
        pc::io::set_field(blob, "votes", r.votes);
        pc::io::set_field(blob, "fruit", flag);
        if (p.instances) {
            const std::uint32_t n =
                r.label.empty() ? 0 : *std::max_element(r.label.begin(), r.label.end());
            io.note(std::to_string(n) + " instances");
            if (n == 1 && fruit > 0 && ds.views.size() > 1) {
                io.warn(
                    "every fruit point joined into one instance: do the masks hold an id per "
                    "fruit, or are they binary?");
            } else if (static_cast<double>(r.doubtful) > kDoubtful * static_cast<double>(fruit)) {
                io.warn(std::to_string(r.doubtful) + " of " + std::to_string(fruit) +
                        " fruit points have a doubtful label (seen only in instances that hold "
                        "several fruit, or as often outside their fruit's instances as in them): "
                        "the masks disagree across views; more views or better masks help");
            }
            pc::io::set_field(blob, "label", r.label);
        }
        io.write(blob);
    });
}
