#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <pc/core/error.h>
#include <pc/core/names.h>
#include <pc/filters/fruit_color.h>

namespace pc::filters {

namespace {

constexpr std::pair<std::string_view, FruitColor> kWords[] = {
    {"auto", FruitColor::kAuto},     {"mask", FruitColor::kMask},     {"red", FruitColor::kRed},
    {"orange", FruitColor::kOrange}, {"yellow", FruitColor::kYellow}, {"green", FruitColor::kGreen},
    {"purple", FruitColor::kPurple}, {"any", FruitColor::kAny}};

/// Foliage: hue 70..170 degrees (yellow-green to cyan-green).
constexpr Interval kFoliage{70, 170};

/// Green hues whose Otsu threshold separates at least this share of their variance form two
/// groups. A normal distribution reaches 0.64 (2/pi) and a uniform one 0.75 at best; two groups
/// of spread sigma whose means are d apart reach 1 / (1 + 4 sigma^2 / d^2) when even: 0.8 at
/// d = 4 sigma.
constexpr double kTwoGreens = 0.8;
/// Each group holds at least this share of the green hues.
constexpr double kLeastGroup = 0.05;

/// Otsu's threshold on a histogram of 1-degree bins from `from` degrees: the boundary (degrees)
/// and the share of the variance it separates.
std::pair<double, double> otsu(const std::vector<double>& histogram, double from) {
    double n = 0, sum = 0, sum2 = 0;
    for (std::size_t b = 0; b < histogram.size(); ++b) {
        const double x = static_cast<double>(b);
        n += histogram[b];
        sum += histogram[b] * x;
        sum2 += histogram[b] * x * x;
    }
    const double variance = n > 0 ? sum2 / n - (sum / n) * (sum / n) : 0;
    double best = 0, at = from, below = 0, below_sum = 0;
    for (std::size_t b = 0; b + 1 < histogram.size(); ++b) {
        below += histogram[b];
        below_sum += histogram[b] * static_cast<double>(b);
        const double above = n - below;
        if (below < kLeastGroup * n || above < kLeastGroup * n) {
            continue;
        }
        const double d = below_sum / below - (sum - below_sum) / above;
        const double between = below / n * above / n * d * d;
        if (between > best) {
            best = between;
            at = from + static_cast<double>(b + 1);
        }
    }
    return {at, variance > 0 ? best / variance : 0};
}

ColorFilterParams hue_rule(Interval hue, double min_saturation) {
    return {.hue_deg = hue, .saturation = Interval{min_saturation, 1}, .value = Interval{0.04, 1}};
}

std::string percent(std::size_t part, std::size_t whole) {
    return format_number(std::round(1000.0 * static_cast<double>(part) /
                                    static_cast<double>(std::max<std::size_t>(whole, 1))) /
                         10) +
           "%";
}

}  // namespace

FruitColor parse_fruit_color(const std::string& text) {
    return parse_name<FruitColor>(kWords, text, "--fruit-color");
}

std::string fruit_color_name(FruitColor c) { return name_of<FruitColor>(kWords, c); }

std::string fruit_color_names() {
    std::string words;
    for (const auto& [word, c] : kWords) {
        words += (words.empty() ? "" : ", ") + std::string(word);
    }
    return words;
}

void FruitColorParams::validate() const {
    if (!(min_saturation >= 0 && min_saturation < 1)) {
        throw InvalidArgument("fruit_color: min_saturation must be in [0, 1), got " +
                              format_number(min_saturation));
    }
}

FruitColorChoice choose_fruit_color(std::span<const io::Rgb> colours, const FruitColorParams& p) {
    p.validate();
    const double s = p.min_saturation;
    switch (p.color) {
        case FruitColor::kMask:
            return {ColorFilterParams{.min_mean = 0.5}, "mask: mean RGB > 0.5", {}};
        case FruitColor::kRed:
            return {hue_rule({320, 35}, s), "red: hue 320..35 deg", {}};
        case FruitColor::kOrange:
            return {hue_rule({10, 55}, s), "orange: hue 10..55 deg", {}};
        case FruitColor::kYellow:
            return {hue_rule({35, 80}, s), "yellow: hue 35..80 deg", {}};
        case FruitColor::kGreen:
            return {hue_rule({55, 170}, s), "green: hue 55..170 deg", {}};
        case FruitColor::kPurple:
            return {hue_rule({240, 350}, s), "purple: hue 240..350 deg", {}};
        case FruitColor::kAny:
            return {std::nullopt, "any: no colour rule", {}};
        case FruitColor::kAuto:
            break;
    }
    // A strided sample: the decision needs proportions, not every point.
    const std::size_t n = colours.size(), stride = std::max<std::size_t>(1, n / 100000);
    std::size_t seen = 0, grey = 0, mid_grey = 0, saturated = 0, foliage = 0;
    // the foliage hues in 1-degree bins, from half a degree below the band (8-bit colours hit
    // whole degrees, not the bins' edges)
    const double from = kFoliage.lo - 0.5;
    std::vector<double> greens(static_cast<std::size_t>(kFoliage.hi - kFoliage.lo) + 1, 0.0);
    for (std::size_t i = 0; i < n; i += stride) {
        const Hsv c = hsv(colours[i]);
        if (!(std::isfinite(c.s) && std::isfinite(c.v))) {
            continue;
        }
        ++seen;
        if (c.s < s) {
            ++grey;
            mid_grey += c.v > 0.25 && c.v < 0.75;
        } else {
            ++saturated;
            if (c.h >= kFoliage.lo && c.h <= kFoliage.hi) {
                ++foliage;
                ++greens[std::min(greens.size() - 1, static_cast<std::size_t>(c.h - from))];
            }
        }
    }
    FruitColorChoice out;
    if (seen == 0) {
        out.reason = "auto: no colours to look at: no colour rule";
        return out;
    }
    if (static_cast<double>(grey) >= 0.9 * static_cast<double>(seen)) {
        if (static_cast<double>(mid_grey) < 0.2 * static_cast<double>(grey)) {
            out.rule = ColorFilterParams{.min_mean = 0.5};
            out.reason =
                "auto: mask colours (" + percent(grey, seen) + " grey, two-toned): mean RGB > 0.5";
            return out;
        }
        out.reason =
            "auto: grey colours (" + percent(grey, seen) + " grey, not two-toned): no colour rule";
        out.warnings.push_back(
            "the colours are grey and not a two-toned mask, so they cannot tell fruit from the "
            "rest: "
            "no colour filter was applied; give --fruit-color or a colour rule if they can");
        return out;
    }
    const std::size_t fruitish = saturated - foliage;
    if (static_cast<double>(fruitish) < 0.03 * static_cast<double>(saturated)) {
        out.rule = ColorFilterParams{.saturation = Interval{s, 1}, .value = Interval{0.04, 1}};
        out.reason = "auto: natural colours, " + percent(foliage, saturated) +
                     " of the saturated points foliage green: every saturated point";
        out.warnings.push_back(
            "nearly every coloured point is green: green fruit and leaves cannot be told apart by "
            "colour, so leaves were kept; check the count, or give --fruit-color");
        const auto [at, separated] = otsu(greens, from);
        if (separated >= kTwoGreens) {
            const std::string groups =
                "auto: natural colours, " + percent(foliage, saturated) +
                " of the saturated points foliage green, in two groups of hues split at " +
                format_number(at) + " deg (" +
                percent(static_cast<std::size_t>(std::round(1000 * separated)), 1000) +
                " of their variance between the groups)";
            const double lo = std::fmod(at + 180, 360);
            for (const Interval hue : {Interval{lo, at}, Interval{at, lo}}) {
                out.classes.push_back(
                    {ColorFilterParams{
                         .hue_deg = hue, .saturation = Interval{s, 1}, .value = Interval{0.04, 1}},
                     groups + ": hue " + format_number(hue.lo) + ".." + format_number(hue.hi) +
                         " deg"});
            }
            out.reason = groups + ": every saturated point";
        }
        return out;
    }
    out.rule = ColorFilterParams{.hue_deg = Interval{kFoliage.hi, kFoliage.lo},
                                 .saturation = Interval{s, 1},
                                 .value = Interval{0.04, 1}};
    out.reason = "auto: natural colours (" + percent(saturated, seen) +
                 " saturated): saturated and not foliage green (hue 170..70 deg)";
    return out;
}

}  // namespace pc::filters
