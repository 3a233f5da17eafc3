#include <cmath>
#include <cstring>

#include <Eigen/LU>

#include <pc/core/error.h>
#include <pc/pipeline/transform.h>

namespace pc::pipeline {

namespace {

using Field = pcl::PCLPointField;

struct Triple {
    const Field* f[3];
};

Triple real_triple(const io::Blob& b, const char* x, const char* y, const char* z, bool required) {
    Triple t{{io::find_field(b, x), io::find_field(b, y), io::find_field(b, z)}};
    const bool all = t.f[0] && t.f[1] && t.f[2];
    if (!all) {
        if (required) {
            throw IoError(std::string("cloud has no ") + x + " " + y + " " + z + " fields");
        }
        return {{nullptr, nullptr, nullptr}};
    }
    for (const Field* f : t.f) {
        if (f->datatype != Field::FLOAT32 && f->datatype != Field::FLOAT64) {
            throw IoError("field '" + f->name + "' must be F 4 or F 8 to be transformed");
        }
    }
    return t;
}

Eigen::Vector3d load(const std::uint8_t* p, const Triple& t) {
    return {io::value_as_double(p + t.f[0]->offset, t.f[0]->datatype),
            io::value_as_double(p + t.f[1]->offset, t.f[1]->datatype),
            io::value_as_double(p + t.f[2]->offset, t.f[2]->datatype)};
}

void store(std::uint8_t* p, const Triple& t, const Eigen::Vector3d& v) {
    for (int a = 0; a < 3; ++a) {
        if (t.f[a]->datatype == Field::FLOAT32) {
            const auto x = static_cast<float>(v[a]);
            std::memcpy(p + t.f[a]->offset, &x, 4);
        } else {
            std::memcpy(p + t.f[a]->offset, &v[a], 8);
        }
    }
}

}  // namespace

Step apply_transform(const io::Blob& in, const TransformSpec& spec) {
    features::check_affine(spec.matrix, "transform");
    io::Blob out = in;
    const Triple xyz = real_triple(out, "x", "y", "z", true);
    const Triple nrm = real_triple(out, "normal_x", "normal_y", "normal_z", false);
    const std::size_t n = out.size();
    const std::size_t step = out.cloud.point_step;
    std::uint8_t* data = out.cloud.data.data();
    // The data-dependent part (centre, normalise) is measured on the transformed points.
    features::Matrix4 total = spec.matrix;
    if (spec.center || spec.normalize != TransformSpec::Normalize::kNone) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero(), lo = Eigen::Vector3d::Constant(INFINITY),
                        hi = Eigen::Vector3d::Constant(-INFINITY);
        std::vector<Eigen::Vector3d> moved;
        for (std::size_t i = 0; i < n; ++i) {
            const Eigen::Vector3d p = (total * load(data + i * step, xyz).homogeneous()).head<3>();
            if (p.allFinite()) {
                moved.push_back(p);
                sum += p;
                lo = lo.cwiseMin(p);
                hi = hi.cwiseMax(p);
            }
        }
        if (!moved.empty()) {
            const Eigen::Vector3d c = sum / static_cast<double>(moved.size());
            double s = 1.0;
            if (spec.normalize == TransformSpec::Normalize::kMeanRadius) {
                double r = 0;
                for (const auto& p : moved) {
                    r += (p - c).norm();
                }
                r /= static_cast<double>(moved.size());
                s = r > 0 ? 1.0 / r : 1.0;
            } else if (spec.normalize == TransformSpec::Normalize::kDiagonal) {
                const double d = (hi - lo).norm();
                s = d > 0 ? 1.0 / d : 1.0;
            }
            // p -> (center ? 0 : c) + s (p - c)
            features::Matrix4 post = features::Matrix4::Identity();
            post.topLeftCorner<3, 3>() *= s;
            post.topRightCorner<3, 1>() = (spec.center ? Eigen::Vector3d::Zero() : c) - s * c;
            total = post * total;
        }
    }
    const Eigen::Matrix3d normal_map = total.topLeftCorner<3, 3>().inverse().transpose();
    for (std::size_t i = 0; i < n; ++i) {
        std::uint8_t* p = data + i * step;
        store(p, xyz, (total * load(p, xyz).homogeneous()).head<3>());
        if (nrm.f[0] != nullptr) {
            const Eigen::Vector3d v = normal_map * load(p, nrm);
            const double len = v.norm();
            store(p, nrm, len > 0 ? Eigen::Vector3d(v / len) : v);
        }
    }
    io::update_is_dense(out);
    std::string note = "transform: matrix";
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) {
            note += ' ';  // (not `" " + s`: GCC 12 -Wrestrict false positive)
            note += format_number(total(r, c));
        }
    }
    return {std::move(out), note};
}

}  // namespace pc::pipeline
