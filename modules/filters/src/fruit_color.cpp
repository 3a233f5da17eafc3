#include <algorithm>
#include <cmath>

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
            foliage += c.h >= kFoliage.lo && c.h <= kFoliage.hi;
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
