// Camera files: conventions pinned by hand-computed pixels (nerfstudio's camera-to-world in
// OpenGL axes, COLMAP's world-to-camera in OpenCV axes), nerfstudio's own COLMAP conversion
// reproduced step by step, the binary model against the text one, dataparser frames, and every
// malformed file refused with its name.
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <pc/cameras/read_cameras.h>
#include <pc/core/error.h>

#include "support/run_tool.h"

namespace pc::cameras {
namespace {

using nlohmann::json;
using test::TempDir;

void write(const std::string& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

Eigen::Vector2d pixel(const View& v, const Eigen::Vector3d& world) {
    const auto px = project(v.camera, v.to_camera(world));
    EXPECT_TRUE(px);
    return px ? *px : Eigen::Vector2d(-1, -1);
}

/// The error message of read_cameras(path), or "" when it reads.
std::string error_of(const std::string& path) {
    try {
        (void)read_cameras(path);
    } catch (const IoError& e) {
        return e.what();
    }
    return "";
}

TEST(ReadCameras, NerfstudioCameraToWorldIsOpenGl) {
    // A camera at (0, 0, 5) with the identity rotation looks down -z (OpenGL): the origin is 5
    // in front, on the principal point; (1, 1, 0) is right of and above it: u = 320 + 500 / 5,
    // v = 240 - 400 / 5 (v grows downwards).
    TempDir d;
    write(d.file("transforms.json"), R"({"w": 640, "h": 480, "fl_x": 500, "fl_y": 400,
        "cx": 320, "cy": 240, "frames": [{"file_path": "images/a.png",
        "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,5],[0,0,0,1]]}]})");
    const Dataset ds = read_cameras(d.file("transforms.json"));
    ASSERT_EQ(ds.views.size(), 1u);
    const View& v = ds.views[0];
    EXPECT_EQ(v.image, "images/a.png");
    EXPECT_EQ(v.camera.model, Model::kPinhole);
    EXPECT_NEAR((pixel(v, {0, 0, 0}) - Eigen::Vector2d(320, 240)).norm(), 0, 1e-9);
    EXPECT_NEAR((pixel(v, {1, 1, 0}) - Eigen::Vector2d(420, 160)).norm(), 0, 1e-9);
    EXPECT_NEAR((v.centre() - Eigen::Vector3d(0, 0, 5)).norm(), 0, 1e-12);
    EXPECT_FALSE(project(v.camera, v.to_camera({0, 0, 6})));  // behind the camera
    EXPECT_FALSE(ds.applied);
}

TEST(ReadCameras, NerfstudioIntrinsicsPerFrameAnglesMasksAndDefaults) {
    TempDir d;
    write(d.file("t.json"), R"({"w": 800, "h": 600, "camera_angle_x": 1.5707963267948966,
        "k1": 0.01, "frames": [
        {"file_path": "a.jpg", "mask_path": "masks/a.png",
         "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,5]]},
        {"file_path": "b.jpg", "semantic_path": "semantics/b.png", "fl_x": 300, "cx": 410,
         "camera_model": "OPENCV_FISHEYE",
         "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,5],[0,0,0,1]]}],
        "applied_transform": [[1,0,0,0],[0,0,1,0],[0,-1,0,0]]})");
    const Dataset ds = read_cameras(d.file("t.json"));
    ASSERT_EQ(ds.views.size(), 2u);
    const Intrinsics& a = ds.views[0].camera;
    EXPECT_NEAR(a.fx, 400, 1e-9);  // 0.5 w / tan(45°)
    EXPECT_NEAR(a.fy, 400, 1e-9);  // fl_y defaults to fl_x
    EXPECT_EQ(a.cx, 400);          // the image's centre
    EXPECT_EQ(a.cy, 300);
    EXPECT_EQ(a.model, Model::kOpenCv);  // distortion without a model name
    EXPECT_EQ(ds.views[0].mask, "masks/a.png");
    const Intrinsics& b = ds.views[1].camera;
    EXPECT_EQ(b.fx, 300);
    EXPECT_EQ(b.cx, 410);
    EXPECT_EQ(b.k1, 0.01);  // the top level's, not overridden
    EXPECT_EQ(b.model, Model::kOpenCvFisheye);
    EXPECT_EQ(ds.views[1].mask, "semantics/b.png");
    ASSERT_TRUE(ds.applied);
    EXPECT_NEAR((ds.applied->apply({1, 2, 3}) - Eigen::Vector3d(1, 3, -2)).norm(), 0, 1e-12);
}

/// One COLMAP image: quaternion (w, x, y, z), translation, camera id, name.
struct ColmapImage {
    int id;
    double q[4];
    double t[3];
    int camera;
    std::string name;
};

const std::vector<ColmapImage> kImages = {
    {1, {1, 0, 0, 0}, {0, 0, 5}, 1, "a.png"},
    {2, {0.9238795325112867, 0, 0.3826834323650898, 0}, {0.2, -0.1, 4}, 2, "b.png"},
};

void write_colmap_text(const std::string& dir) {
    write(dir + "/cameras.txt",
          "# Camera list with one line of data per camera:\n"
          "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
          "1 PINHOLE 640 480 500 400 320 240\n"
          "2 OPENCV 640 480 510 505 321 239 -0.1 0.02 0.001 -0.002\n");
    std::ostringstream images;
    images << "# Image list with two lines of data per image:\n" << std::fixed;
    for (const ColmapImage& im : kImages) {
        images << im.id;
        for (double x : im.q) {
            images << ' ' << x;
        }
        for (double x : im.t) {
            images << ' ' << x;
        }
        images << ' ' << im.camera << ' ' << im.name << '\n';
        images << (im.id == 1 ? "\n" : "100.5 200.5 -1 110.5 210.5 7\n");  // no points / points
    }
    write(dir + "/images.txt", images.str());
}

template <typename T>
void put(std::string& s, T v) {
    s.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

/// The same model in COLMAP's binary layout (little-endian).
void write_colmap_binary(const std::string& dir) {
    std::string c;
    put<std::uint64_t>(c, 2);
    put<std::int32_t>(c, 1);
    put<std::int32_t>(c, 1);  // PINHOLE
    put<std::uint64_t>(c, 640);
    put<std::uint64_t>(c, 480);
    for (double x : {500.0, 400.0, 320.0, 240.0}) {
        put(c, x);
    }
    put<std::int32_t>(c, 2);
    put<std::int32_t>(c, 4);  // OPENCV
    put<std::uint64_t>(c, 640);
    put<std::uint64_t>(c, 480);
    for (double x : {510.0, 505.0, 321.0, 239.0, -0.1, 0.02, 0.001, -0.002}) {
        put(c, x);
    }
    write(dir + "/cameras.bin", c);
    std::string i;
    put<std::uint64_t>(i, kImages.size());
    for (const ColmapImage& im : kImages) {
        put<std::int32_t>(i, im.id);
        for (double x : im.q) {
            put(i, x);
        }
        for (double x : im.t) {
            put(i, x);
        }
        put<std::int32_t>(i, im.camera);
        i += im.name;
        i += '\0';
        put<std::uint64_t>(i, im.id == 1 ? 0 : 2);
        for (int k = 0; k < (im.id == 1 ? 0 : 2); ++k) {
            put(i, 100.5);
            put(i, 200.5);
            put<std::int64_t>(i, -1);
        }
    }
    write(dir + "/images.bin", i);
}

TEST(ReadCameras, ColmapWorldToCameraIsOpenCv) {
    // Identity rotation, t = (0, 0, 5): (1, 1, 0) is at (1, 1, 5) in the camera, right of and
    // below the centre (y down): u = 320 + 500 / 5, v = 240 + 400 / 5.
    TempDir d;
    write_colmap_text(d.path);
    const Dataset ds = read_cameras(d.path);
    ASSERT_EQ(ds.views.size(), 2u);
    EXPECT_EQ(ds.views[0].image, "a.png");
    EXPECT_NEAR((pixel(ds.views[0], {1, 1, 0}) - Eigen::Vector2d(420, 320)).norm(), 0, 1e-9);
    EXPECT_NEAR((ds.views[0].centre() - Eigen::Vector3d(0, 0, -5)).norm(), 0, 1e-12);
    EXPECT_EQ(ds.views[1].camera.model, Model::kOpenCv);
    EXPECT_EQ(ds.views[1].camera.p2, -0.002);
}

TEST(ReadCameras, ColmapBinaryReadsAsItsText) {
    TempDir t, b;
    write_colmap_text(t.path);
    write_colmap_binary(b.path);
    const Dataset dt = read_cameras(t.path), db = read_cameras(b.path);
    ASSERT_EQ(dt.views.size(), db.views.size());
    for (std::size_t k = 0; k < dt.views.size(); ++k) {
        EXPECT_EQ(dt.views[k].image, db.views[k].image);
        EXPECT_EQ(dt.views[k].camera.fx, db.views[k].camera.fx);
        EXPECT_EQ(dt.views[k].camera.k1, db.views[k].camera.k1);
        // the text holds the quaternion to 6 decimals
        EXPECT_NEAR((dt.views[k].rotation - db.views[k].rotation).norm(), 0, 1e-5);
        EXPECT_NEAR((dt.views[k].translation - db.views[k].translation).norm(), 0, 1e-9);
    }
}

TEST(ReadCameras, NerfstudiosOwnConversionOfColmapSeesThePointsWhereColmapDoes) {
    // nerfstudio's colmap_to_json, step by step: c2w = inv(w2c); c2w[0:3, 1:3] *= -1 (OpenCV to
    // OpenGL axes); c2w = c2w[[0, 2, 1, 3], :]; c2w[2, :] *= -1 (the applied_transform it writes,
    // which also moves COLMAP's points). A COLMAP point p must land where applied(p) does.
    TempDir c, n;
    write_colmap_text(c.path);
    const Dataset colmap = read_cameras(c.path);
    json frames = json::array();
    for (const View& v : colmap.views) {
        Eigen::Matrix4d w2c = Eigen::Matrix4d::Identity();
        w2c.topLeftCorner<3, 3>() = v.rotation;
        w2c.topRightCorner<3, 1>() = v.translation;
        Eigen::Matrix4d c2w = w2c.inverse();
        c2w.block<3, 2>(0, 1) *= -1;
        Eigen::Matrix4d swapped = c2w;
        swapped.row(1) = c2w.row(2);
        swapped.row(2) = -c2w.row(1);
        json m = json::array();
        for (int r = 0; r < 4; ++r) {
            m.push_back({swapped(r, 0), swapped(r, 1), swapped(r, 2), swapped(r, 3)});
        }
        const Intrinsics& k = v.camera;
        frames.push_back({{"file_path", v.image},
                          {"transform_matrix", m},
                          {"w", k.width},
                          {"h", k.height},
                          {"fl_x", k.fx},
                          {"fl_y", k.fy},
                          {"cx", k.cx},
                          {"cy", k.cy},
                          {"k1", k.k1},
                          {"k2", k.k2},
                          {"p1", k.p1},
                          {"p2", k.p2},
                          {"camera_model", std::string(model_name(k.model))}});
    }
    const json t = {{"frames", frames},
                    {"applied_transform", {{1, 0, 0, 0}, {0, 0, 1, 0}, {0, -1, 0, 0}}}};
    write(n.file("transforms.json"), t.dump());
    const Dataset ns = read_cameras(n.file("transforms.json"));
    ASSERT_TRUE(ns.applied);
    ASSERT_EQ(ns.views.size(), colmap.views.size());
    for (std::size_t k = 0; k < ns.views.size(); ++k) {
        for (const Eigen::Vector3d& p :
             {Eigen::Vector3d(0.3, -0.2, 0.1), Eigen::Vector3d(-0.5, 0.4, -0.3)}) {
            EXPECT_NEAR(
                (pixel(colmap.views[k], p) - pixel(ns.views[k], ns.applied->apply(p))).norm(), 0,
                1e-9);
        }
    }
}

TEST(ReadCameras, DataparserTransformsMoveCamerasWithTheExportedCloud) {
    // p' = s (T [p; 1]): an exported point p' lands where its p did once the view is moved.
    TempDir d;
    write(d.file("transforms.json"), R"({"w": 640, "h": 480, "fl_x": 500, "frames": [
        {"file_path": "a.png", "transform_matrix": [[1,0,0,0.2],[0,1,0,-0.1],[0,0,1,5]]}]})");
    write(d.file("dataparser_transforms.json"), R"({"transform": [[0,-1,0,0.5],[1,0,0,0.1],
        [0,0,1,-0.3]], "scale": 0.25})");
    const Similarity s = read_dataparser_transforms(d.file("dataparser_transforms.json"));
    EXPECT_NEAR((s.apply({1, 2, 3}) - 0.25 * Eigen::Vector3d(-2 + 0.5, 1 + 0.1, 3 - 0.3)).norm(), 0,
                1e-12);
    const View v = read_cameras(d.file("transforms.json")).views[0];
    const View w = moved(v, s);
    const Eigen::Vector3d p(0.3, 0.2, -0.4);
    EXPECT_NEAR((pixel(v, p) - pixel(w, s.apply(p))).norm(), 0, 1e-9);
}

TEST(ReadCameras, MalformedFilesAreRefusedNamingTheFile) {
    TempDir d;
    const std::string f = d.file("t.json");
    const std::string frame = R"("transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,5]])";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"{not json", "not JSON"},
        {R"({"w": 640})", "no \"frames\""},
        {R"({"w": 640, "h": 480, "fl_x": 500, "frames": []})", "no frames"},
        {R"({"w": 640, "h": 480, "fl_x": 500, "frames": [{"file_path": "a"}]})",
         "no \"transform_matrix\""},
        {R"({"w": 640, "h": 480, "fl_x": 500, "frames": [{"transform_matrix": [[1,0,0]]}]})",
         "3 or 4 rows"},
        {R"({"w": 640, "h": 480, "fl_x": 500, "frames": [{"transform_matrix":
            [[1,0,0,0],[0,1,0,0],[0,0,1,0],[1,1,1,1]]}]})",
         "last row"},
        {R"({"h": 480, "fl_x": 500, "frames": [{)" + frame + "}]}", "no image size"},
        {R"({"w": 640, "h": 480, "frames": [{)" + frame + "}]}", "no focal length"},
        {R"({"w": 640, "h": 480, "fl_x": 500, "camera_model": "EQUIRECTANGULAR", "frames": [{)" +
             frame + "}]}",
         "unknown camera model \"EQUIRECTANGULAR\""},
        {R"({"w": 640.5, "h": 480, "fl_x": 500, "frames": [{)" + frame + "}]}", "whole numbers"},
        {R"({"w": 640, "h": 480, "fl_x": -1, "frames": [{)" + frame + "}]}", "focal lengths"},
        {R"({"w": 640, "h": 480, "fl_x": "500", "frames": [{)" + frame + "}]}",
         "must be a finite number"},
        {R"({"w": 640, "h": 480, "fl_x": 500, "frames": [{"transform_matrix":
            [[0,0,0,0],[0,0,0,0],[0,0,0,0]]}]})",
         "singular"},
    };
    for (const auto& [text, expected] : cases) {
        write(f, text);
        const std::string e = error_of(f);
        EXPECT_NE(e.find(f), std::string::npos) << text << " -> " << e;
        EXPECT_NE(e.find(expected), std::string::npos) << text << " -> " << e;
    }
    EXPECT_NE(error_of(d.file("missing.json")).find("cannot open"), std::string::npos);
    EXPECT_NE(error_of(d.path).find("without a COLMAP model"), std::string::npos);
}

TEST(ReadCameras, MalformedColmapModelsAreRefusedNamingTheFile) {
    TempDir d;
    write_colmap_text(d.path);
    write(d.file("cameras.txt"), "1 FOV 640 480 500 320 240 0.1\n");
    EXPECT_NE(error_of(d.path).find("unknown camera model \"FOV\""), std::string::npos);
    write(d.file("cameras.txt"), "1 PINHOLE 640 480 500 400 320\n");
    EXPECT_NE(error_of(d.path).find("PINHOLE takes 4 numbers, got 3"), std::string::npos);
    write(d.file("cameras.txt"), "1 PINHOLE 640 480 500 400 320 240\n");  // camera 2 missing
    EXPECT_NE(error_of(d.path).find("camera 2 is not in cameras.txt"), std::string::npos);
    write(d.file("images.txt"), "1 1 0 0 0 0 0\n\n");
    EXPECT_NE(error_of(d.path).find(d.file("images.txt")), std::string::npos);

    TempDir b;
    write_colmap_binary(b.path);
    std::ifstream in(b.file("images.bin"), std::ios::binary);
    const std::string whole((std::istreambuf_iterator<char>(in)), {});
    for (const std::size_t cut : {std::size_t{4}, std::size_t{20}, whole.size() - 3}) {
        write(b.file("images.bin"), whole.substr(0, cut));
        const std::string e = error_of(b.path);
        EXPECT_NE(e.find(b.file("images.bin")), std::string::npos) << cut << ": " << e;
    }
    std::string huge = whole;
    const std::uint64_t n = 1ull << 60;  // a count the file cannot hold: no allocation, an error
    std::memcpy(huge.data(), &n, sizeof n);
    write(b.file("images.bin"), huge);
    EXPECT_NE(error_of(b.path).find("records announced"), std::string::npos);
    write(b.file("images.bin"), whole);
    std::ifstream cin(b.file("cameras.bin"), std::ios::binary);
    std::string cams((std::istreambuf_iterator<char>(cin)), {});
    const std::int32_t fov = 7;
    std::memcpy(cams.data() + 12, &fov, sizeof fov);
    write(b.file("cameras.bin"), cams);
    EXPECT_NE(error_of(b.path).find("unknown camera model FOV"), std::string::npos);
}

}  // namespace
}  // namespace pc::cameras
