#include <algorithm>
#include <array>

#include <pc/core/error.h>
#include <pc/filters/color_smooth.h>
#include <pc/search/grid.h>

namespace pc::filters {

void ColorSmoothParams::validate() const {
    if (k < 1 || k > 64) {
        throw InvalidArgument("smooth_colors: k must be in [1, 64]");
    }
}

std::vector<io::Rgb> smooth_colors(const XyzView& points,
                                   std::span<const io::Rgb> colors,
                                   const ColorSmoothParams& params) {
    params.validate();
    if (colors.size() != points.size) {
        throw InvalidArgument("smooth_colors: one colour a point");
    }
    std::vector<io::Rgb> out(colors.begin(), colors.end());
    if (points.size < 2) {
        return out;
    }
    const search::Grid grid(points, search::Grid::suggest_cell(points, 16));
    grid.all_knn(params.k, [&](std::uint32_t i, const std::vector<std::uint32_t>& idx,
                               const std::vector<double>&) {
        std::array<float, 65> r{}, g{}, b{};
        std::size_t n = 0;
        const auto add = [&](const io::Rgb& c) {
            r[n] = c.r;
            g[n] = c.g;
            b[n] = c.b;
            ++n;
        };
        add(colors[i]);
        for (const std::uint32_t j : idx) {
            add(colors[j]);
        }
        const auto median = [&](std::array<float, 65>& v) {
            std::nth_element(v.begin(), v.begin() + n / 2, v.begin() + n);
            return v[n / 2];
        };
        out[i] = {median(r), median(g), median(b)};
    });
    return out;
}

}  // namespace pc::filters
