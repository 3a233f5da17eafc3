// pc_transform: apply an affine transform (matrix, scale, rotation, translation, nerfstudio's
// dataparser transform), then optionally centre and normalise. Normals rotate with the points.
#include <algorithm>
#include <filesystem>

#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/pipeline/transform.h>

namespace pf = pc::features;
namespace pl = pc::pipeline;

int main(int argc, char** argv) {
    std::string matrix_text, nerfstudio;
    double scale = 1.0;
    std::array<double, 3> translate{0, 0, 0};
    std::string rotate_text;
    bool inverse = false;
    pl::TransformSpec spec;
    pc::cli::Tool tool("pc_transform",
                       "apply --nerfstudio, --matrix, --scale, --rotate, --translate (in that "
                       "order), then --center and --normalize");
    tool.option("matrix", &matrix_text,
                "16 numbers (row-major 4x4) or 12 (3x4), or a file holding them");
    tool.option("nerfstudio", &nerfstudio,
                "dataparser_transforms.json: map a nerfstudio export back to the dataset frame");
    tool.option("scale", &scale, "uniform scale factor (about the origin)");
    tool.option("rotate", &rotate_text, "AX,AY,AZ,DEG: rotation by DEG degrees about the axis");
    tool.option("translate", &translate, "translation x,y,z");
    tool.flag("inverse", &inverse, "apply the inverse of the fixed transform above");
    tool.flag("center", &spec.center, "then move the centroid of the finite points to the origin");
    tool.option(
        "normalize", "none",
        [&](const std::string& s) {
            if (s == "none") {
                spec.normalize = pl::TransformSpec::Normalize::kNone;
            } else if (s == "mean-radius") {
                spec.normalize = pl::TransformSpec::Normalize::kMeanRadius;
            } else if (s == "diagonal") {
                spec.normalize = pl::TransformSpec::Normalize::kDiagonal;
            } else {
                throw pc::InvalidArgument(
                    "--normalize: expected none, mean-radius or "
                    "diagonal, got '" +
                    s + "'");
            }
        },
        "then scale about the centroid to unit mean radius or unit bounding-box diagonal");
    tool.epilog("\nSee docs/tools/pc_transform.md for the conventions.\n");
    return tool.run(argc, argv, [&](pc::cli::Streams& io) {
        pf::Matrix4 m = pf::Matrix4::Identity();
        if (!nerfstudio.empty()) {
            // nerfstudio: p_ns = s (T [p; 1]); an export is mapped back with the inverse.
            m = pf::nerfstudio_forward(pc::cli::read_text_file(nerfstudio, "--nerfstudio file"),
                                       nerfstudio)
                    .inverse();
        }
        if (!matrix_text.empty()) {
            const bool is_file = std::filesystem::is_regular_file(matrix_text);
            m = pf::parse_matrix(
                    is_file ? pc::cli::read_text_file(matrix_text, "--matrix file") : matrix_text,
                    "--matrix") *
                m;
        }
        if (!(scale > 0) || !std::isfinite(scale)) {
            throw pc::InvalidArgument("--scale must be > 0, got " + pc::format_number(scale));
        }
        pf::Matrix4 s = pf::Matrix4::Identity();
        s.topLeftCorner<3, 3>() *= scale;
        m = s * m;
        if (!rotate_text.empty()) {
            const auto comma = rotate_text.rfind(',');
            if (std::count(rotate_text.begin(), rotate_text.end(), ',') != 3) {
                throw pc::InvalidArgument(
                    "--rotate: expected AX,AY,AZ,DEG (an axis and an angle in degrees), got '" +
                    rotate_text + "'");
            }
            const auto axis = pc::cli::parse_triple("rotate", rotate_text.substr(0, comma));
            m = pf::rotation(axis, pc::cli::parse_double("rotate", rotate_text.substr(comma + 1))) *
                m;
        }
        pf::Matrix4 t = pf::Matrix4::Identity();
        t.topRightCorner<3, 1>() = Eigen::Vector3d(translate[0], translate[1], translate[2]);
        m = t * m;
        pf::check_affine(m, "transform");
        spec.matrix = inverse ? pf::Matrix4(m.inverse()) : m;
        pl::Step step = pl::apply_transform(io.read(), spec);
        io.note(step.note);
        io.write(step.blob);
    });
}
