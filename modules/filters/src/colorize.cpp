#include <algorithm>
#include <cmath>

#include <pc/core/error.h>
#include <pc/core/stats.h>
#include <pc/filters/colorize.h>
#include <pc/io/points.h>

namespace pc::filters {

namespace {

constexpr Rgb8 kGrey{160, 160, 160};

/// viridis at 0, 8, 16, ..., 248 and 255 of 255: sampled from OpenCV 4.6's COLORMAP_VIRIDIS
/// (itself matplotlib's viridis, by van der Walt and Smith, CC0), interpolated linearly between.
constexpr Rgb8 kViridis[33] = {
    {68, 1, 84},    {71, 13, 96},   {72, 24, 106},  {72, 35, 116},  {71, 45, 123},  {69, 55, 129},
    {66, 64, 134},  {62, 73, 137},  {59, 82, 139},  {55, 91, 141},  {51, 99, 141},  {47, 107, 142},
    {44, 114, 142}, {41, 122, 142}, {38, 130, 142}, {35, 137, 142}, {33, 145, 140}, {31, 152, 139},
    {31, 160, 136}, {34, 167, 133}, {40, 174, 128}, {50, 182, 122}, {63, 188, 115}, {78, 195, 107},
    {94, 201, 98},  {112, 207, 87}, {132, 212, 75}, {152, 216, 62}, {173, 220, 48}, {194, 223, 35},
    {216, 226, 25}, {236, 229, 27}, {253, 231, 37}};

/// HSV (h in [0, 1)) to 8-bit RGB.
Rgb8 from_hsv(double h, double s, double v) {
    const double h6 = h * 6;
    const int sector = static_cast<int>(h6) % 6;
    const double f = h6 - std::floor(h6);
    const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
    double r = v, g = t, b = p;
    switch (sector) {
        case 1:
            r = q, g = v, b = p;
            break;
        case 2:
            r = p, g = v, b = t;
            break;
        case 3:
            r = p, g = q, b = v;
            break;
        case 4:
            r = t, g = p, b = v;
            break;
        case 5:
            r = v, g = p, b = q;
            break;
        default:
            break;
    }
    const auto byte = [](double x) { return static_cast<std::uint8_t>(std::lround(x * 255)); };
    return {byte(r), byte(g), byte(b)};
}

std::vector<double> values_of(const io::Blob& blob, const std::string& by) {
    std::vector<double> v(blob.size());
    if (by == "x" || by == "y" || by == "z") {
        const io::XyzPoints points(blob);
        const int axis = by[0] - 'x';
        for (std::size_t i = 0; i < v.size(); ++i) {
            const pcl::PointXYZ p = points.view()[i];
            v[i] = axis == 0 ? p.x : axis == 1 ? p.y : p.z;
        }
        return v;
    }
    const pcl::PCLPointField* f = io::find_field(blob, by);
    if (f == nullptr || f->count != 1 ||
        ((f->name == "rgb" || f->name == "rgba") && io::type_size(f->datatype) == 4)) {
        throw IoError("no numeric field '" + by + "' of one element to colour by (the cloud has: " +
                      io::field_names(blob) + ")");
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
        v[i] = io::value_as_double(blob.cloud.data.data() + i * blob.cloud.point_step + f->offset,
                                   f->datatype);
    }
    return v;
}

}  // namespace

Rgb8 label_color(std::uint32_t label) {
    if (label == 0) {
        return kGrey;
    }
    return from_hsv(std::fmod(label * 0.618033988749895, 1.0), 0.78, 0.9);
}

Rgb8 viridis(double t) {
    if (std::isnan(t)) {
        return kGrey;
    }
    const double x = std::clamp(t, 0.0, 1.0) * 255;
    const int k = std::min(31, static_cast<int>(x / 8));
    const double lo = 8.0 * k, hi = k == 31 ? 255.0 : lo + 8;
    const double f = (x - lo) / (hi - lo);
    Rgb8 out{};
    for (int c = 0; c < 3; ++c) {
        out[c] = static_cast<std::uint8_t>(
            std::lround(kViridis[k][c] + f * (kViridis[k + 1][c] - kViridis[k][c])));
    }
    return out;
}

void ColorizeParams::validate() const {
    if (by.empty()) {
        throw InvalidArgument("colorize: by must name a field, got ''");
    }
    if (range &&
        !((*range)[0] < (*range)[1] && std::isfinite((*range)[0]) && std::isfinite((*range)[1]))) {
        throw InvalidArgument("colorize: range must be LO:HI with LO < HI, got " +
                              format_number((*range)[0]) + ":" + format_number((*range)[1]));
    }
}

Colorized colorize(const io::Blob& blob, const ColorizeParams& params) {
    params.validate();
    Colorized out;
    out.colors.resize(blob.size());
    if (blob.size() == 0) {
        return out;  // nothing to colour, whatever fields the empty cloud declares
    }
    if (params.by == "label") {
        const std::vector<std::uint32_t> l = io::labels(blob, "label");
        std::transform(l.begin(), l.end(), out.colors.begin(), label_color);
        return out;
    }
    const std::vector<double> v = values_of(blob, params.by);
    if (params.range) {
        out.lo = (*params.range)[0];
        out.hi = (*params.range)[1];
    } else if (!v.empty()) {
        out.lo = percentile_of_finite(v, 2);
        out.hi = percentile_of_finite(v, 98);
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
        const double t = out.hi > out.lo ? (v[i] - out.lo) / (out.hi - out.lo) : 0.5;
        out.colors[i] = std::isfinite(v[i]) ? viridis(t) : kGrey;
    }
    return out;
}

std::vector<std::uint32_t> packed(const std::vector<Rgb8>& colors) {
    std::vector<std::uint32_t> out(colors.size());
    std::transform(colors.begin(), colors.end(), out.begin(), [](const Rgb8& c) {
        return (std::uint32_t{c[0]} << 16) | (std::uint32_t{c[1]} << 8) | c[2];
    });
    return out;
}

}  // namespace pc::filters
