#include <charconv>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <nlohmann/json.hpp>

#include <pc/core/error.h>
#include <pc/features/transform.h>

namespace pc::features {

Matrix4 parse_matrix(const std::string& text, const std::string& what) {
    std::vector<double> v;
    std::size_t at = 0;
    const auto sep = [](char c) {
        return c == ' ' || c == ',' || c == '\n' || c == '\t' || c == '\r' || c == ';';
    };
    while (at < text.size()) {
        while (at < text.size() && sep(text[at])) {
            ++at;
        }
        std::size_t end = at;
        while (end < text.size() && !sep(text[end])) {
            ++end;
        }
        if (end == at) {
            break;
        }
        double x = 0;
        const char* b = text.data() + at;
        const char* e = text.data() + end;
        if (*b == '+') {
            ++b;
        }
        const auto r = std::from_chars(b, e, x);
        if (r.ec != std::errc{} || r.ptr != e) {
            throw InvalidArgument(what + ": '" + text.substr(at, end - at) + "' is not a number");
        }
        v.push_back(x);
        at = end;
    }
    if (v.size() != 16 && v.size() != 12) {
        throw InvalidArgument(what + ": expected 16 (4x4) or 12 (3x4) numbers, got " +
                              std::to_string(v.size()));
    }
    Matrix4 m = Matrix4::Identity();
    for (std::size_t k = 0; k < v.size(); ++k) {
        m(static_cast<Eigen::Index>(k / 4), static_cast<Eigen::Index>(k % 4)) = v[k];
    }
    check_affine(m, what);
    return m;
}

Matrix4 rotation(const std::array<double, 3>& axis, double angle_deg) {
    const Eigen::Vector3d a(axis[0], axis[1], axis[2]);
    if (!(a.norm() > 0) || !std::isfinite(angle_deg)) {
        throw InvalidArgument("--rotate: the axis must be non-zero and the angle finite");
    }
    Matrix4 m = Matrix4::Identity();
    m.topLeftCorner<3, 3>() =
        Eigen::AngleAxisd(angle_deg * std::numbers::pi / 180.0, a.normalized()).toRotationMatrix();
    return m;
}

Matrix4 nerfstudio_forward(const std::string& json_text, const std::string& what) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(json_text);
    } catch (const nlohmann::json::exception& e) {
        throw IoError(what + ": not JSON: " + e.what());
    }
    if (!j.contains("transform") || !j.contains("scale") || !j["scale"].is_number() ||
        !j["transform"].is_array() || j["transform"].size() != 3) {
        throw IoError(what + ": expected {\"transform\": 3x4, \"scale\": number}");
    }
    Matrix4 t = Matrix4::Identity();
    for (int r = 0; r < 3; ++r) {
        const auto& row = j["transform"][r];
        if (!row.is_array() || row.size() != 4) {
            throw IoError(what + ": transform row " + std::to_string(r) + " must have 4 numbers");
        }
        for (int c = 0; c < 4; ++c) {
            if (!row[c].is_number()) {
                throw IoError(what + ": transform must hold numbers");
            }
            t(r, c) = row[c].get<double>();
        }
    }
    const double s = j["scale"].get<double>();
    if (!(s > 0) || !std::isfinite(s)) {
        throw IoError(what + ": scale must be > 0, got " + format_number(s));
    }
    Matrix4 scale = Matrix4::Identity();
    scale.topLeftCorner<3, 3>() *= s;
    const Matrix4 m = scale * t;
    check_affine(m, what);
    return m;
}

void check_affine(const Matrix4& m, const std::string& what) {
    if (!m.allFinite()) {
        throw InvalidArgument(what + ": the matrix must be finite");
    }
    if (m(3, 0) != 0 || m(3, 1) != 0 || m(3, 2) != 0 || m(3, 3) != 1) {
        throw InvalidArgument(what + ": the last row must be 0 0 0 1 (affine)");
    }
    if (m.topLeftCorner<3, 3>().determinant() == 0) {
        throw InvalidArgument(what + ": the 3x3 part is singular");
    }
}

}  // namespace pc::features
