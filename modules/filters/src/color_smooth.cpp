#include <algorithm>
#include <array>
#include <cmath>

#include <pc/core/error.h>
#include <pc/filters/color_smooth.h>
#include <pc/search/grid.h>

namespace pc::filters {

namespace {

/// Points whose distance to their neighbours' median colour estimates the noise.
constexpr std::size_t kNoiseSample = 20000;

/// The median of the first n values of v (the upper one of an even n), reordering them.
float median(std::array<float, 65>& v, std::size_t n) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n / 2),
                     v.begin() + static_cast<std::ptrdiff_t>(n));
    return v[n / 2];
}

/// Each channel's median over `first`'s colour (when given) and its neighbours' `idx`.
io::Rgb median_colour(std::span<const io::Rgb> colors,
                      const io::Rgb* first,
                      const std::vector<std::uint32_t>& idx) {
    std::array<float, 65> r{}, g{}, b{};
    std::size_t n = 0;
    const auto add = [&](const io::Rgb& c) {
        r[n] = c.r;
        g[n] = c.g;
        b[n] = c.b;
        ++n;
    };
    if (first != nullptr) {
        add(*first);
    }
    for (const std::uint32_t j : idx) {
        add(colors[j]);
    }
    return {median(r, n), median(g, n), median(b, n)};
}

/// The finite points of whole blocks (side 8 cells of about 16 points) chosen by a hash of the
/// block, about kNoiseBlockPoints of them or every point: their neighbourhoods keep the cloud's
/// density, as every stride-th point would not.
constexpr std::size_t kNoiseBlockPoints = 50000;
std::vector<std::uint32_t> block_sample(const XyzView& points) {
    const double block = 8 * search::Grid::suggest_cell(points, 16);
    std::vector<std::uint32_t> out;
    for (std::size_t stride = std::max<std::size_t>(1, points.size / kNoiseBlockPoints);;
         stride = std::max<std::size_t>(1, stride / 4)) {
        out.clear();
        for (std::size_t i = 0; i < points.size; ++i) {
            const pcl::PointXYZ q = points[i];
            if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) {
                continue;
            }
            const auto at = [&](float v) {
                return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / block)));
            };
            const std::uint64_t h =
                (at(q.x) * 73856093u) ^ (at(q.y) * 19349663u) ^ (at(q.z) * 83492791u);
            if (stride == 1 || (h * 0x9E3779B97F4A7C15ull) >> 40 < (1ull << 24) / stride) {
                out.push_back(static_cast<std::uint32_t>(i));
            }
        }
        if (stride == 1 || out.size() >= kNoiseBlockPoints / 4) {
            return out;
        }
    }
}

/// SmoothedColors::noise, over up to kNoiseSample points of block_sample() and their neighbours
/// among its points.
double colour_noise(const XyzView& points, std::span<const io::Rgb> colors, std::size_t k) {
    const std::vector<std::uint32_t> kept = block_sample(points);
    const XyzView sample = points.subset(kept);
    const search::Grid grid(sample, search::Grid::suggest_cell(sample, 16));
    std::vector<float> away;
    std::vector<std::uint32_t> idx;
    std::vector<double> d2;
    const std::size_t stride = std::max<std::size_t>(1, kept.size() / kNoiseSample);
    for (std::size_t i = 0; i < kept.size(); i += stride) {
        grid.knn(static_cast<std::uint32_t>(i), k, idx, d2);
        if (idx.size() < k) {
            continue;  // too few others
        }
        for (std::uint32_t& j : idx) {
            j = kept[j];
        }
        const io::Rgb m = median_colour(colors, nullptr, idx), &c = colors[kept[i]];
        away.insert(away.end(), {std::abs(c.r - m.r), std::abs(c.g - m.g), std::abs(c.b - m.b)});
    }
    if (away.empty()) {
        return 0;
    }
    const auto mid = away.begin() + static_cast<std::ptrdiff_t>(away.size() / 2);
    std::nth_element(away.begin(), mid, away.end());
    return *mid / 0.6745;
}

}  // namespace

void ColorSmoothParams::validate() const {
    if (k < 1 || k > 64) {
        throw InvalidArgument("smooth_colors: k must be in [1, 64]");
    }
    if (!(min_noise >= 0 && min_noise <= 1)) {
        throw InvalidArgument("smooth_colors: min_noise must be in [0, 1]");
    }
}

SmoothedColors smooth_colors(const XyzView& points,
                             std::span<const io::Rgb> colors,
                             const ColorSmoothParams& params) {
    params.validate();
    if (colors.size() != points.size) {
        throw InvalidArgument("smooth_colors: one colour a point");
    }
    SmoothedColors out;
    if (points.size < 2) {
        if (params.min_noise == 0) {
            out.colors.assign(colors.begin(), colors.end());
        }
        return out;
    }
    out.noise = colour_noise(points, colors, params.k);
    if (out.noise < params.min_noise) {
        return out;
    }
    out.colors.assign(colors.begin(), colors.end());
    const search::Grid grid(points, search::Grid::suggest_cell(points, 16));
    grid.all_knn(params.k, [&](std::uint32_t i, const std::vector<std::uint32_t>& idx,
                               const std::vector<double>&) {
        out.colors[i] = median_colour(colors, &colors[i], idx);
    });
    return out;
}

}  // namespace pc::filters
