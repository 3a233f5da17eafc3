#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include <pc/core/error.h>
#include <pc/core/labels.h>
#include <pc/core/stats.h>
#include <pc/filters/wood_parts.h>

namespace pc::filters {

namespace {

/// The wood's pieces found before a gap is judged: a spread to judge it by (one or two pieces
/// are none: judged from the second piece, scene 1999's five bark pieces 3.8-4.7 ΔE from the
/// trunk's colour, after one at 0.6, were kept as fruit).
constexpr std::size_t kPieces = 3;

using Lab = std::array<double, 3>;

double distance(const Lab& a, const Lab& b) {
    return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

}  // namespace

void WoodPartsParams::validate() const {
    if (!(giant > 1 && std::isfinite(giant))) {
        throw InvalidArgument("wood_parts: giant must be > 1");
    }
    if (!(share >= 0 && share <= 1)) {
        throw InvalidArgument("wood_parts: share must be in [0, 1]");
    }
    if (!(apart > 0 && std::isfinite(apart))) {
        throw InvalidArgument("wood_parts: apart must be > 0");
    }
    if (!(min_apart >= 0 && std::isfinite(min_apart))) {
        throw InvalidArgument("wood_parts: min_apart must be >= 0");
    }
    if (!((gap == 0 || gap >= 1) && std::isfinite(gap))) {
        throw InvalidArgument("wood_parts: gap must be 0 or >= 1");
    }
    if (!(stray_share >= 0 && stray_share <= 1)) {
        throw InvalidArgument("wood_parts: stray_share must be in [0, 1]");
    }
}

std::array<double, 3> cielab(const io::Rgb& c) {
    const auto linear = [](double v) {
        return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    };
    const double r = linear(c.r), g = linear(c.g), b = linear(c.b);
    // sRGB to XYZ, relative to the D65 white
    const double x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
    const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    const double z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
    const auto f = [](double t) {
        return t > 216.0 / 24389 ? std::cbrt(t) : (24389.0 / 27 * t + 16) / 116;
    };
    return {116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))};
}

WoodPartsResult wood_parts(std::span<const io::Rgb> colours,
                           std::vector<std::uint32_t> labels,
                           const WoodPartsParams& params) {
    params.validate();
    if (colours.size() != labels.size()) {
        throw InvalidArgument("wood_parts: one colour per label needed (" +
                              std::to_string(labels.size()) + " labels, " +
                              std::to_string(colours.size()) + " colours)");
    }
    WoodPartsResult r;
    std::uint32_t top = 0;
    for (const std::uint32_t l : labels) {
        top = std::max(top, l);
    }
    // Each part's points and mean colour (of its points with a finite colour).
    std::vector<double> points(std::size_t{top} + 1, 0.0), coloured(std::size_t{top} + 1, 0.0);
    std::vector<Lab> mean(std::size_t{top} + 1, Lab{0, 0, 0});
    for (std::size_t i = 0; i < labels.size(); ++i) {
        const std::uint32_t l = labels[i];
        points[l] += 1;
        const io::Rgb& c = colours[i];
        if (l != 0 && std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b)) {
            const Lab v = cielab(c);
            for (int k = 0; k < 3; ++k) {
                mean[l][k] += v[k];
            }
            coloured[l] += 1;
        }
    }
    std::vector<double> sizes;
    for (std::uint32_t l = 1; l <= top; ++l) {
        if (points[l] > 0) {
            sizes.push_back(points[l]);
        }
        for (int k = 0; k < 3 && coloured[l] > 0; ++k) {
            mean[l][k] /= coloured[l];
        }
    }
    const double counted = std::accumulate(sizes.begin(), sizes.end(), 0.0);
    const double giant =
        sizes.empty() ? 0.0 : std::max(params.giant * median(sizes), params.share * counted);
    // The parts' median colour and spread (giants and parts without colour aside).
    std::vector<std::uint32_t> giants, others;
    for (std::uint32_t l = 1; l <= top; ++l) {
        if (coloured[l] > 0) {
            (points[l] > giant ? giants : others).push_back(l);
        }
    }
    const auto median_colour = [&](const std::vector<std::uint32_t>& of) {
        Lab out{};
        for (int k = 0; k < 3; ++k) {
            std::vector<double> channel;
            for (const std::uint32_t l : of) {
                channel.push_back(mean[l][k]);
            }
            out[k] = median(channel);
        }
        return out;
    };
    std::vector<bool> drop(std::size_t{top} + 1, false);
    const auto finish = [&] {
        for (const std::uint32_t l : others) {
            r.dropped += drop[l] ? 1 : 0;
        }
        for (std::uint32_t& l : labels) {
            l = drop[l] ? 0 : l;
        }
        r.count = renumber_by_size(labels);
        r.labels = std::move(labels);
        return r;
    };
    if (others.empty()) {
        return finish();
    }
    if (giants.empty()) {
        // No giant: wood given fruit centres along its branches is all in pieces. The parts'
        // median colour (each part one vote) is the fruit's where the fruit are most parts; the
        // parts more than `apart` × the parts' spread from it (and min_apart) go where they hold
        // under `stray_share` of the parts' points and their median part is smaller than the
        // others' (pieces: a second colour of fruit, or green fruit outnumbered by the leaves
        // kept beside them, has parts of a fruit's size).
        const Lab colour = median_colour(others);
        std::vector<double> off;
        for (const std::uint32_t l : others) {
            off.push_back(distance(mean[l], colour));
        }
        std::vector<double> reordered = off;
        const double limit = std::max(params.apart * median(reordered), params.min_apart);
        std::vector<double> stray_sizes, kept_sizes;
        for (std::size_t j = 0; j < others.size(); ++j) {
            (off[j] > limit ? stray_sizes : kept_sizes).push_back(points[others[j]]);
        }
        const double held = std::accumulate(stray_sizes.begin(), stray_sizes.end(), 0.0);
        if (params.stray_share > 0 && !stray_sizes.empty() && !kept_sizes.empty() &&
            held < params.stray_share * counted && median(stray_sizes) < median(kept_sizes)) {
            for (std::size_t j = 0; j < others.size(); ++j) {
                drop[others[j]] = off[j] > limit;
            }
        }
        return finish();
    }
    // Each giant's colour against the other parts': the fruit's colour is the median colour
    // (per channel, each part one vote) of the parts nearer it than the giant's, found from
    // those further from the giant than the median part is (two means, one held at the giant's).
    for (const std::uint32_t g : giants) {
        std::vector<double> to_giant;  // of each of `others`
        for (const std::uint32_t l : others) {
            to_giant.push_back(distance(mean[l], mean[g]));
        }
        std::vector<double> reordered = to_giant;  // median() reorders its argument
        const double middle = median(reordered);
        std::vector<std::uint32_t> fruit;
        for (std::size_t j = 0; j < others.size(); ++j) {
            if (to_giant[j] >= middle) {
                fruit.push_back(others[j]);
            }
        }
        Lab colour = median_colour(fruit);
        for (int round = 0; round < 20; ++round) {
            fruit.clear();
            for (std::size_t j = 0; j < others.size(); ++j) {
                if (distance(mean[others[j]], colour) <= to_giant[j]) {
                    fruit.push_back(others[j]);
                }
            }
            const Lab next = median_colour(fruit);  // `fruit` holds the furthest part at least
            if (next == colour) {
                break;
            }
            colour = next;
        }
        std::vector<double> off;
        for (const std::uint32_t l : fruit) {
            off.push_back(distance(mean[l], colour));
        }
        const double spread = median(off);
        if (!(distance(mean[g], colour) > std::max(params.apart * spread, params.min_apart))) {
            continue;
        }
        r.fruit_colour_spread = r.giants == 0 ? spread : r.fruit_colour_spread;
        ++r.giants;
        drop[g] = true;
        // The parts nearer the giant's colour than the fruit's, nearest first, are the wood's
        // pieces up to a gap (params.gap, after kPieces of them); the parts past it are fruit.
        std::vector<std::size_t> nearer;
        for (std::size_t j = 0; j < others.size(); ++j) {
            if (distance(mean[others[j]], colour) > to_giant[j]) {
                nearer.push_back(j);
            }
        }
        std::stable_sort(nearer.begin(), nearer.end(),
                         [&](std::size_t a, std::size_t b) { return to_giant[a] < to_giant[b]; });
        for (std::size_t k = 0; k < nearer.size(); ++k) {
            const double before = k == 0 ? 0.0 : to_giant[nearer[k - 1]];
            const double here = to_giant[nearer[k]];
            if (k >= kPieces && params.gap > 0 && here > params.gap * before &&
                here > before + params.min_apart) {
                break;
            }
            drop[others[nearer[k]]] = true;
        }
    }
    return finish();
}

}  // namespace pc::filters
