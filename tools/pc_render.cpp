// pc_render: a cloud drawn into a PNG without a display: from a dataset camera or standard views
// (a contact sheet), coloured by rgb, by label or by any field through a colour map, or as a
// label / fruit mask for pc_maskeval.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <pc/cameras/read_cameras.h>
#include <pc/cameras/render.h>
#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/filters/color_filter.h>
#include <pc/filters/colorize.h>
#include <pc/io/blob.h>
#include <pc/io/points.h>
#include <pc/search/spacing.h>

namespace cam = pc::cameras;

namespace {

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    for (std::string part; std::getline(ss, part, sep);) {
        out.push_back(part);
    }
    return out;
}

/// Standard views of the cloud's bounding sphere (z up), 40° vertical field of view.
cam::View standard_view(
    const std::string& name, const Eigen::Vector3d& centre, double radius, int width, int height) {
    Eigen::Vector3d dir, up = Eigen::Vector3d::UnitZ();
    if (name == "top") {
        dir = {0, 0, 1};
        up = Eigen::Vector3d::UnitY();
    } else if (name == "front") {
        dir = {0, -1, 0};
    } else if (name == "side") {
        dir = {1, 0, 0};
    } else if (name == "iso") {
        dir = Eigen::Vector3d(1, -1, 0.8).normalized();
    } else {
        throw pc::InvalidArgument(
            "--view must be top, front, side or iso (comma-separated), got '" + name + "'");
    }
    const double fov = 40 * 3.141592653589793 / 180;
    const double aspect = std::min(1.0, static_cast<double>(width) / height);
    const double distance = 1.05 * radius / std::sin(0.5 * fov * aspect);
    return cam::look_at(centre + distance * dir, centre, up, width, height, fov);
}

cv::Vec3b bgr(const pc::filters::Rgb8& c) { return {c[2], c[1], c[0]}; }

}  // namespace

int main(int argc, char** argv) {
    std::string cameras_path, views = "iso", color = "auto", range, size = "800x600", mask_field,
                              background = "white";
    int frame = -1;
    double spacing = 0;
    cam::VisibilityParams splat;
    pc::cli::Tool tool("pc_render",
                       "draw the cloud into a PNG: a dataset camera (--cameras, --frame) or "
                       "standard views side by side; colour by rgb, label or any field; or a "
                       "label mask (--mask) for pc_maskeval",
                       pc::cli::Output::kImage);
    tool.option("cameras", &cameras_path,
                "transforms.json or COLMAP model: draw from its camera --frame, at its size");
    tool.option("frame", &frame, "the camera's index in the camera file (0 = first)");
    tool.option("view", &views, "standard views, comma-separated: top, front, side, iso");
    tool.option("size", &size, "WxH of each standard view");
    tool.option("color", &color,
                "auto (rgb if the cloud has colour, else height), rgb, label (distinct colours, "
                "0 grey), or any numeric field through a colour map with a colour bar");
    tool.option("range", &range, "LO:HI of the colour map (default: the field's P2:P98)");
    tool.option("mask", &mask_field,
                "write this integer field per pixel instead of colours (0 background; 8-bit "
                "PNG, 16-bit when a value exceeds 255): label or fruit images for pc_maskeval");
    tool.option("splat", &splat.footprint, "x spacing: the radius of surface a point covers");
    tool.option("spacing", &spacing,
                "point spacing in cloud units; 0: the median nearest-neighbour distance");
    tool.option("background", &background, "white or black");
    tool.epilog(
        "\nStandard views are framed on the cloud's bounding box, z up.\n"
        "See docs/tools/pc_render.md.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        if (background != "white" && background != "black") {
            throw pc::InvalidArgument("--background must be white or black, got '" + background +
                                      "'");
        }
        std::vector<cam::View> cams;
        if (!cameras_path.empty()) {
            const cam::Dataset ds = cam::read_cameras(cameras_path);
            if (frame < 0 || static_cast<std::size_t>(frame) >= ds.views.size()) {
                throw pc::InvalidArgument("--frame must be 0.." +
                                          std::to_string(ds.views.size() - 1) + " for " +
                                          cameras_path);
            }
            cams.push_back(ds.views[static_cast<std::size_t>(frame)]);
        } else if (frame >= 0) {
            throw pc::InvalidArgument("--frame needs --cameras");
        }
        int w = 0, h = 0;
        {
            const auto parts = split(size, 'x');
            if (parts.size() != 2 || (w = std::atoi(parts[0].c_str())) < 16 ||
                (h = std::atoi(parts[1].c_str())) < 16 || w > 8192 || h > 8192) {
                throw pc::InvalidArgument("--size must be WxH, 16 to 8192 each, got '" + size +
                                          "'");
            }
        }
        pc::io::Blob blob = io.read();
        const pc::io::XyzPoints points(blob);
        const pc::XyzView& view = points.view();
        Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
        std::size_t finite = 0;
        for (std::size_t i = 0; i < view.size; ++i) {
            const pcl::PointXYZ p = view[i];
            if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
                lo = lo.cwiseMin(Eigen::Vector3d(p.x, p.y, p.z));
                hi = hi.cwiseMax(Eigen::Vector3d(p.x, p.y, p.z));
                ++finite;
            }
        }
        if (finite == 0) {
            throw pc::IoError(io.input_name() + ": no finite point to draw");
        }
        if (spacing == 0) {
            spacing = pc::search::median_spacing(view);
            if (!(spacing > 0)) {
                spacing = std::max(1e-9, 0.001 * (hi - lo).norm());
            }
        }
        if (cams.empty()) {
            const Eigen::Vector3d centre = 0.5 * (lo + hi);
            const double radius = std::max(0.5 * (hi - lo).norm(), 1e-9);
            for (const std::string& v : split(views, ',')) {
                cams.push_back(standard_view(v, centre, radius, w, h));
            }
        }
        // what each point looks like
        std::vector<cv::Vec3b> colour;
        std::vector<std::uint32_t> mask_values;
        double lo_v = 0, hi_v = 0;
        bool bar = false;
        if (!mask_field.empty()) {
            mask_values = pc::io::labels(blob, mask_field);
        } else {
            const bool has_rgb = pc::io::find_field(blob, "rgb") ||
                                 pc::io::find_field(blob, "rgba") ||
                                 pc::io::find_field(blob, "red");
            std::string by = color == "auto" ? (has_rgb ? "rgb" : "z") : color;
            colour.resize(blob.size());
            if (by == "rgb") {
                const auto rgb = pc::io::colours(blob);
                for (std::size_t i = 0; i < rgb.size(); ++i) {
                    const auto c = [](float x) {
                        return static_cast<std::uint8_t>(std::clamp(x, 0.0f, 1.0f) * 255 + 0.5f);
                    };
                    colour[i] = {c(rgb[i].b), c(rgb[i].g), c(rgb[i].r)};
                }
            } else {
                pc::filters::ColorizeParams cp{.by = by};
                if (!range.empty()) {
                    const pc::filters::Interval r = pc::filters::parse_interval("range", range);
                    cp.range = std::array<double, 2>{r.lo, r.hi};
                }
                const pc::filters::Colorized c = pc::cli::naming(
                    io.input_name(), [&] { return pc::filters::colorize(blob, cp); });
                std::transform(c.colors.begin(), c.colors.end(), colour.begin(), bgr);
                lo_v = c.lo;
                hi_v = c.hi;
                bar = by != "label";
                color = by;
            }
        }
        // draw every view, side by side
        std::vector<cv::Mat> tiles;
        std::uint32_t max_value = 0;
        for (const std::uint32_t m : mask_values) {
            max_value = std::max(max_value, m);
        }
        for (const cam::View& v : cams) {
            const std::vector<std::int32_t> idx = cam::render_nearest(view, v, spacing, splat);
            const int vw = v.camera.width, vh = v.camera.height;
            cv::Mat tile;
            if (!mask_field.empty()) {
                tile = cv::Mat::zeros(vh, vw, max_value > 255 ? CV_16UC1 : CV_8UC1);
                for (int y = 0; y < vh; ++y) {
                    for (int x = 0; x < vw; ++x) {
                        const std::int32_t i = idx[static_cast<std::size_t>(y) * vw + x];
                        const std::uint32_t value =
                            i < 0 ? 0 : mask_values[static_cast<std::size_t>(i)];
                        if (tile.depth() == CV_16U) {
                            tile.at<std::uint16_t>(y, x) =
                                static_cast<std::uint16_t>(std::min<std::uint32_t>(value, 65535));
                        } else {
                            tile.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(value);
                        }
                    }
                }
            } else {
                const cv::Vec3b bg =
                    background == "white" ? cv::Vec3b(255, 255, 255) : cv::Vec3b(0, 0, 0);
                tile = cv::Mat(vh, vw, CV_8UC3, cv::Scalar(bg[0], bg[1], bg[2]));
                for (int y = 0; y < vh; ++y) {
                    for (int x = 0; x < vw; ++x) {
                        const std::int32_t i = idx[static_cast<std::size_t>(y) * vw + x];
                        if (i >= 0) {
                            tile.at<cv::Vec3b>(y, x) = colour[static_cast<std::size_t>(i)];
                        }
                    }
                }
            }
            tiles.push_back(tile);
        }
        if (!mask_field.empty() && tiles.size() > 1) {
            throw pc::InvalidArgument(
                "--mask draws one view: give --cameras and --frame, or one --view");
        }
        cv::Mat sheet;
        cv::hconcat(tiles, sheet);
        if (bar) {  // a colour bar on the right: the map from LO (bottom) to HI (top)
            const int bw = 70;
            cv::Mat strip(sheet.rows, bw, CV_8UC3, cv::Scalar(255, 255, 255));
            const int rows = sheet.rows - 40;
            for (int k = 0; k < rows; ++k) {
                const double t = 1.0 - static_cast<double>(k) / std::max(1, rows - 1);
                strip(cv::Rect(4, 20 + k, 16, 1)) = cv::Scalar(bgr(pc::filters::viridis(t)));
            }
            const auto text = [&](const std::string& t, int y) {
                cv::putText(strip, t, cv::Point(22, y), cv::FONT_HERSHEY_SIMPLEX, 0.35,
                            cv::Scalar(0, 0, 0), 1);
            };
            text(pc::format_number(std::round(hi_v * 1e4) / 1e4), 24);
            text(pc::format_number(std::round(lo_v * 1e4) / 1e4), sheet.rows - 20);
            text(color, 12);
            cv::hconcat(sheet, strip, sheet);
        }
        std::vector<std::uint8_t> png;
        if (!cv::imencode(".png", sheet, png)) {
            throw pc::IoError("could not encode the PNG");
        }
        io.note(std::to_string(tiles.size()) + " view(s), " + std::to_string(sheet.cols) + " x " +
                std::to_string(sheet.rows) + ", spacing " + pc::format_number(spacing));
        io.write_text(std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    });
}
