#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <nlohmann/json.hpp>

#include <pc/cameras/read_cameras.h>
#include <pc/core/error.h>

namespace pc::cameras {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

std::string slurp(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        throw IoError(path + ": cannot open");
    }
    std::ostringstream s;
    s << f.rdbuf();
    if (f.bad()) {
        throw IoError(path + ": cannot read");
    }
    return s.str();
}

json parse_json(std::string_view text, const std::string& name) {
    try {
        return json::parse(text);
    } catch (const json::exception& e) {
        throw IoError(name + ": not JSON (" + e.what() + ")");
    }
}

double finite_number(const json& v, const std::string& what) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
        throw IoError(what + " must be a finite number, got " + v.dump());
    }
    return v.get<double>();
}

/// A rows x 4 matrix of finite numbers (rows 3 or 4; a fourth row must be 0 0 0 1).
Eigen::Matrix4d matrix4(const json& v, const std::string& what) {
    if (!v.is_array() || (v.size() != 3 && v.size() != 4)) {
        throw IoError(what + " must be 3 or 4 rows of 4 numbers, got " + v.dump().substr(0, 80));
    }
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    for (std::size_t r = 0; r < v.size(); ++r) {
        if (!v[r].is_array() || v[r].size() != 4) {
            throw IoError(what + " must be 3 or 4 rows of 4 numbers; row " + std::to_string(r) +
                          " is " + v[r].dump().substr(0, 80));
        }
        for (std::size_t c = 0; c < 4; ++c) {
            m(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) =
                finite_number(v[r][c], what);
        }
    }
    if (!m.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1))) {
        throw IoError(what + ": the last row must be 0 0 0 1");
    }
    return m;
}

/// The image size of `c`; pc::IoError unless both are whole numbers from 1 to 1000000 (`what`
/// names them).
void set_size(Intrinsics& c, double width, double height, const std::string& what) {
    if (width != std::floor(width) || height != std::floor(height) || width < 1 || height < 1 ||
        width > 1e6 || height > 1e6) {
        throw IoError(what + " must be whole numbers from 1 to 1000000");
    }
    c.width = static_cast<int>(width);
    c.height = static_cast<int>(height);
}

/// transforms.json intrinsics, given at the top level and overridden per frame.
struct Partial {
    std::map<std::string, double> v;
    std::string model;

    void take(const json& j, const std::string& what) {
        for (const char* key : {"fl_x", "fl_y", "cx", "cy", "w", "h", "k1", "k2", "k3", "k4", "p1",
                                "p2", "camera_angle_x", "camera_angle_y"}) {
            if (j.contains(key)) {
                v[key] = finite_number(j.at(key), what + ": \"" + key + "\"");
            }
        }
        if (j.contains("camera_model")) {
            if (!j.at("camera_model").is_string()) {
                throw IoError(what + ": \"camera_model\" must be a string");
            }
            model = j.at("camera_model").get<std::string>();
        }
    }

    [[nodiscard]] double get(const char* key, double otherwise) const {
        const auto it = v.find(key);
        return it == v.end() ? otherwise : it->second;
    }

    [[nodiscard]] Intrinsics finish(const std::string& what) const {
        Intrinsics c;
        if (!v.count("w") || !v.count("h")) {
            throw IoError(what + ": no image size (\"w\" and \"h\")");
        }
        const double w = get("w", 0), h = get("h", 0);
        set_size(c, w, h, what + ": \"w\" and \"h\"");
        if (v.count("fl_x")) {
            c.fx = get("fl_x", 0);
        } else if (v.count("camera_angle_x")) {
            c.fx = 0.5 * w / std::tan(0.5 * get("camera_angle_x", 0));
        } else {
            throw IoError(what + ": no focal length (\"fl_x\" or \"camera_angle_x\")");
        }
        c.fy = v.count("fl_y")             ? get("fl_y", 0)
               : v.count("camera_angle_y") ? 0.5 * h / std::tan(0.5 * get("camera_angle_y", 0))
                                           : c.fx;
        c.cx = get("cx", 0.5 * w);
        c.cy = get("cy", 0.5 * h);
        c.k1 = get("k1", 0);
        c.k2 = get("k2", 0);
        c.k3 = get("k3", 0);
        c.k4 = get("k4", 0);
        c.p1 = get("p1", 0);
        c.p2 = get("p2", 0);
        if (model.empty()) {
            const bool distorted = c.k1 != 0 || c.k2 != 0 || c.k3 != 0 || c.p1 != 0 || c.p2 != 0;
            c.model = distorted ? Model::kOpenCv : Model::kPinhole;
        } else if (const auto m = model_from_name(model)) {
            c.model = *m;
        } else {
            throw IoError(what + ": unknown camera model \"" + model +
                          "\" (known: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, "
                          "OPENCV_FISHEYE)");
        }
        try {
            c.validate();
        } catch (const InvalidArgument& e) {
            throw IoError(what + ": " + e.what());
        }
        return c;
    }
};

std::string string_key(const json& frame, const char* key, const std::string& what) {
    if (!frame.contains(key)) {
        return {};
    }
    if (!frame.at(key).is_string()) {
        throw IoError(what + ": \"" + key + "\" must be a string");
    }
    return frame.at(key).get<std::string>();
}

}  // namespace

Dataset parse_transforms(std::string_view text, const std::string& path) {
    const json j = parse_json(text, path);
    if (!j.is_object() || !j.contains("frames") || !j.at("frames").is_array()) {
        throw IoError(path + ": no \"frames\" array (not a transforms.json)");
    }
    Partial global;
    global.take(j, path);
    Dataset d;
    if (j.contains("applied_transform")) {
        const Eigen::Matrix4d a = matrix4(j.at("applied_transform"), path + ": applied_transform");
        d.applied = Similarity{1, a.topLeftCorner<3, 3>(), a.topRightCorner<3, 1>()};
    }
    const json& frames = j.at("frames");
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const json& f = frames[k];
        const std::string what = path + ": frame " + std::to_string(k);
        if (!f.is_object() || !f.contains("transform_matrix")) {
            throw IoError(what + ": no \"transform_matrix\"");
        }
        Partial own = global;
        own.take(f, what);
        View view;
        view.camera = own.finish(what);
        // camera-to-world in OpenGL axes (y up, z back) -> OpenCV axes (y down, z forward)
        Eigen::Matrix4d c2w = matrix4(f.at("transform_matrix"), what + ": transform_matrix");
        c2w.col(1) *= -1;
        c2w.col(2) *= -1;
        if (std::abs(c2w.topLeftCorner<3, 3>().determinant()) < 1e-12) {
            throw IoError(what + ": transform_matrix is singular");
        }
        const Eigen::Matrix4d w2c = c2w.inverse();
        view.rotation = w2c.topLeftCorner<3, 3>();
        view.translation = w2c.topRightCorner<3, 1>();
        view.image = string_key(f, "file_path", what);
        view.mask = string_key(f, "mask_path", what);
        if (view.mask.empty()) {
            view.mask = string_key(f, "semantic_path", what);
        }
        d.views.push_back(std::move(view));
    }
    if (d.views.empty()) {
        throw IoError(path + ": no frames");
    }
    return d;
}

namespace {

// ---- COLMAP ----

struct ColmapModel {
    int id;
    Model model;
    int params;
};

/// COLMAP's model ids and parameter counts (those it has that we do not project: named, refused).
constexpr ColmapModel kColmapModels[] = {
    {0, Model::kSimplePinhole, 3}, {1, Model::kPinhole, 4}, {2, Model::kSimpleRadial, 4},
    {3, Model::kRadial, 5},        {4, Model::kOpenCv, 8},  {5, Model::kOpenCvFisheye, 8},
};
constexpr const char* kOtherColmapModels[] = {"FULL_OPENCV", "FOV", "SIMPLE_RADIAL_FISHEYE",
                                              "RADIAL_FISHEYE", "THIN_PRISM_FISHEYE"};

/// Intrinsics from COLMAP's parameter list for `model`.
Intrinsics colmap_intrinsics(Model model,
                             double width,
                             double height,
                             const std::vector<double>& p,
                             const std::string& what) {
    Intrinsics c;
    c.model = model;
    set_size(c, width, height, what + ": width and height");
    switch (model) {
        case Model::kSimplePinhole:
        case Model::kSimpleRadial:
        case Model::kRadial:
            c.fx = c.fy = p[0];
            c.cx = p[1];
            c.cy = p[2];
            c.k1 = p.size() > 3 ? p[3] : 0;
            c.k2 = p.size() > 4 ? p[4] : 0;
            break;
        case Model::kPinhole:
        case Model::kOpenCv:
        case Model::kOpenCvFisheye:
            c.fx = p[0];
            c.fy = p[1];
            c.cx = p[2];
            c.cy = p[3];
            if (model == Model::kOpenCv) {
                c.k1 = p[4];
                c.k2 = p[5];
                c.p1 = p[6];
                c.p2 = p[7];
            } else if (model == Model::kOpenCvFisheye) {
                c.k1 = p[4];
                c.k2 = p[5];
                c.k3 = p[6];
                c.k4 = p[7];
            }
            break;
    }
    try {
        c.validate();
    } catch (const InvalidArgument& e) {
        throw IoError(what + ": " + e.what());
    }
    return c;
}

const ColmapModel& colmap_model_by_name(const std::string& name, const std::string& what) {
    const auto m = model_from_name(name);
    for (const ColmapModel& c : kColmapModels) {
        if (m && c.model == *m) {
            return c;
        }
    }
    throw IoError(what + ": unknown camera model \"" + name +
                  "\" (known: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, "
                  "OPENCV_FISHEYE)");
}

const ColmapModel& colmap_model_by_id(std::int64_t id, const std::string& what) {
    for (const ColmapModel& c : kColmapModels) {
        if (c.id == id) {
            return c;
        }
    }
    const std::string name =
        id >= 6 && id <= 10 ? std::string(kOtherColmapModels[id - 6]) : "id " + std::to_string(id);
    throw IoError(what + ": unknown camera model " + name +
                  " (known: SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, "
                  "OPENCV_FISHEYE)");
}

View colmap_view(const double q[4],
                 const double t[3],
                 const Intrinsics& camera,
                 std::string name,
                 const std::string& what) {
    for (int k = 0; k < 4; ++k) {
        if (!std::isfinite(q[k]) || (k < 3 && !std::isfinite(t[k]))) {
            throw IoError(what + ": pose must be finite numbers");
        }
    }
    const Eigen::Quaterniond quat(q[0], q[1], q[2], q[3]);
    if (!(quat.norm() > 1e-9)) {
        throw IoError(what + ": zero quaternion");
    }
    View v;
    v.camera = camera;
    v.rotation = quat.normalized().toRotationMatrix();
    v.translation = Eigen::Vector3d(t[0], t[1], t[2]);
    v.image = std::move(name);
    return v;
}

/// Lines that are not comments; keeps empty ones (images.txt's empty point lists).
std::vector<std::string> data_lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') {
            line.pop_back();
        }
        if (!line.empty() && line[0] == '#') {
            continue;
        }
        out.push_back(line);
    }
    while (!out.empty() && out.back().find_first_not_of(" \t") == std::string::npos &&
           out.size() % 2 == 1) {
        out.pop_back();  // a trailing newline after the last points line
    }
    return out;
}

Dataset read_colmap_text(const std::string& dir) {
    const std::string cpath = (fs::path(dir) / "cameras.txt").string();
    const std::string ipath = (fs::path(dir) / "images.txt").string();
    std::map<std::int64_t, Intrinsics> cams;
    const std::vector<std::string> clines = data_lines(slurp(cpath));
    for (std::size_t k = 0; k < clines.size(); ++k) {
        if (clines[k].find_first_not_of(" \t") == std::string::npos) {
            continue;
        }
        const std::string what = cpath + ": line " + std::to_string(k + 1) + " (data)";
        std::istringstream in(clines[k]);
        std::int64_t id = 0;
        std::string name;
        double w = 0, h = 0;
        if (!(in >> id >> name >> w >> h)) {
            throw IoError(what + ": expected CAMERA_ID MODEL WIDTH HEIGHT PARAMS...");
        }
        const ColmapModel& m = colmap_model_by_name(name, what);
        std::vector<double> p;
        double x = 0;
        while (in >> x) {
            p.push_back(x);
        }
        if (!in.eof() || static_cast<int>(p.size()) != m.params) {
            throw IoError(what + ": " + name + " takes " + std::to_string(m.params) +
                          " numbers, got " + std::to_string(p.size()));
        }
        cams[id] = colmap_intrinsics(m.model, w, h, p, what);
    }
    const std::vector<std::string> ilines = data_lines(slurp(ipath));
    std::map<std::int64_t, View> views;
    for (std::size_t k = 0; k < ilines.size(); k += 2) {
        const std::string what = ipath + ": image line " + std::to_string(k / 2 + 1);
        std::istringstream in(ilines[k]);
        std::int64_t id = 0, cam = 0;
        double q[4], t[3];
        if (!(in >> id >> q[0] >> q[1] >> q[2] >> q[3] >> t[0] >> t[1] >> t[2] >> cam)) {
            throw IoError(what + ": expected IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME");
        }
        std::string name;
        std::getline(in >> std::ws, name);
        if (name.empty()) {
            throw IoError(what + ": no image name");
        }
        const auto c = cams.find(cam);
        if (c == cams.end()) {
            throw IoError(what + ": camera " + std::to_string(cam) + " is not in cameras.txt");
        }
        views[id] = colmap_view(q, t, c->second, name, what);
    }
    Dataset d;
    for (auto& [id, v] : views) {
        d.views.push_back(std::move(v));
    }
    return d;
}

/// Little-endian reads with bounds checks over a whole file.
class Bytes {
public:
    Bytes(std::string data, std::string path) : d_(std::move(data)), path_(std::move(path)) {}

    template <typename T>
    T get() {
        if (d_.size() - at_ < sizeof(T)) {
            throw IoError(path_ + ": truncated at byte " + std::to_string(at_));
        }
        T v;
        std::memcpy(&v, d_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return v;
    }
    std::string cstring() {
        const auto end = d_.find('\0', at_);
        if (end == std::string::npos || end - at_ > 4096) {
            throw IoError(path_ + ": image name not terminated at byte " + std::to_string(at_));
        }
        std::string s = d_.substr(at_, end - at_);
        at_ = end + 1;
        return s;
    }
    void skip(std::uint64_t count, std::uint64_t size) {
        if (size != 0 && count > (d_.size() - at_) / size) {
            throw IoError(path_ + ": truncated (" + std::to_string(count) + " records of " +
                          std::to_string(size) + " bytes announced at byte " + std::to_string(at_) +
                          ")");
        }
        at_ += count * size;
    }
    /// A record count that fits in the bytes left, each at least `size` bytes.
    std::uint64_t count(std::uint64_t size) {
        const auto n = get<std::uint64_t>();
        if (n > (d_.size() - at_) / size) {
            throw IoError(path_ + ": " + std::to_string(n) + " records announced, the file holds " +
                          "fewer");
        }
        return n;
    }
    [[nodiscard]] bool done() const { return at_ == d_.size(); }
    [[nodiscard]] const std::string& path() const { return path_; }

private:
    std::string d_;
    std::string path_;
    std::size_t at_ = 0;
};

Dataset read_colmap_binary(const std::string& dir) {
    const std::string cpath = (fs::path(dir) / "cameras.bin").string();
    const std::string ipath = (fs::path(dir) / "images.bin").string();
    Bytes cb(slurp(cpath), cpath);
    std::map<std::int64_t, Intrinsics> cams;
    for (std::uint64_t n = cb.count(24), k = 0; k < n; ++k) {
        const std::string what = cpath + ": camera " + std::to_string(k);
        const auto id = cb.get<std::int32_t>();
        const auto model = cb.get<std::int32_t>();
        const auto w = cb.get<std::uint64_t>(), h = cb.get<std::uint64_t>();
        const ColmapModel& m = colmap_model_by_id(model, what);
        std::vector<double> p(static_cast<std::size_t>(m.params));
        for (double& x : p) {
            x = cb.get<double>();
        }
        cams[id] =
            colmap_intrinsics(m.model, static_cast<double>(w), static_cast<double>(h), p, what);
    }
    if (!cb.done()) {
        throw IoError(cpath + ": bytes after the last camera");
    }
    Bytes ib(slurp(ipath), ipath);
    std::map<std::int64_t, View> views;
    for (std::uint64_t n = ib.count(64), k = 0; k < n; ++k) {
        const std::string what = ipath + ": image " + std::to_string(k);
        const auto id = ib.get<std::int32_t>();
        double q[4], t[3];
        for (double& x : q) {
            x = ib.get<double>();
        }
        for (double& x : t) {
            x = ib.get<double>();
        }
        const auto cam = ib.get<std::int32_t>();
        std::string name = ib.cstring();
        ib.skip(ib.get<std::uint64_t>(), 24);  // 2D points: x, y, point3D id
        const auto c = cams.find(cam);
        if (c == cams.end()) {
            throw IoError(what + ": camera " + std::to_string(cam) + " is not in cameras.bin");
        }
        views[id] = colmap_view(q, t, c->second, std::move(name), what);
    }
    if (!ib.done()) {
        throw IoError(ipath + ": bytes after the last image");
    }
    Dataset d;
    for (auto& [id, v] : views) {
        d.views.push_back(std::move(v));
    }
    return d;
}

}  // namespace

Dataset read_cameras(const std::string& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
        const fs::path dir(path);
        Dataset d;
        if (fs::exists(dir / "cameras.txt") || fs::exists(dir / "images.txt")) {
            d = read_colmap_text(path);
        } else if (fs::exists(dir / "cameras.bin") || fs::exists(dir / "images.bin")) {
            d = read_colmap_binary(path);
        } else {
            throw IoError(path +
                          ": a directory without a COLMAP model (cameras.txt and images.txt, "
                          "or cameras.bin and images.bin)");
        }
        if (d.views.empty()) {
            throw IoError(path + ": no images in the COLMAP model");
        }
        return d;
    }
    return parse_transforms(slurp(path), path);
}

Similarity read_dataparser_transforms(const std::string& path) {
    return parse_dataparser_transforms(slurp(path), path);
}

Similarity parse_dataparser_transforms(std::string_view text, const std::string& path) {
    const json j = parse_json(text, path);
    if (!j.is_object() || !j.contains("transform") || !j.contains("scale")) {
        throw IoError(path + ": no \"transform\" and \"scale\" (not a dataparser_transforms.json)");
    }
    const Eigen::Matrix4d t = matrix4(j.at("transform"), path + ": transform");
    const double s = finite_number(j.at("scale"), path + ": scale");
    if (!(s > 0)) {
        throw IoError(path + ": scale must be > 0");
    }
    return Similarity{s, t.topLeftCorner<3, 3>(), s * t.topRightCorner<3, 1>()};
}

}  // namespace pc::cameras
