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
/// Natural colours darker than this (HSV value) are black: their hue and saturation are noise.
constexpr double kBlack = 0.04;

/// A histogram holds two groups when Otsu's threshold leaves the means of its two sides at least
/// this many times their root-mean-square spread apart. One normal distribution cut at its
/// Otsu threshold gives 2.7, an even one 3.5; two normal groups of equal spread give their
/// distance in spreads (4 and more: hardly overlapping).
constexpr double kTwoGroups = 4;
/// The groups of the rule's points are offered from this separation: looser than kTwoGroups (a
/// shape test chooses between them), above one normal distribution's 2.7. On 13 scenes of the
/// matrix's wood part, the best of the three splits lay 2.7-9.0 spreads apart, 7 of them 3-4.
constexpr double kSomeGroups = 3;
/// From this share of the saturated points outside foliage hue, the rule's fruit are likely the
/// fruit: the green groups are tried only where its centres claim too little (bark, not fruit).
constexpr double kFewFruitish = 0.1;
/// The pale points are offered from this share of the colours.
constexpr double kLeastPale = 0.03;
/// Each group holds at least this share of the histogram.
constexpr double kLeastGroup = 0.05;
/// Saturation is not lowered below this for pale fruit (greys of 8-bit colour reach it) ...
constexpr double kLeastSaturation = 0.1;
/// ... and only when min_saturation would cut off at least this share of the upper group.
constexpr double kStraddle = 0.1;

struct Groups {
    double at = 0;          ///< Otsu's threshold (a bin edge)
    double separation = 0;  ///< the distance of the sides' means over their rms spread
};

/// Otsu's threshold on a histogram of bins `width` wide from `from`, and how far apart it leaves
/// the two sides (each at least kLeastGroup of the whole).
Groups otsu(const std::vector<double>& histogram, double from, double width) {
    double n = 0, sum = 0, sum2 = 0;
    for (std::size_t b = 0; b < histogram.size(); ++b) {
        const double x = static_cast<double>(b);
        n += histogram[b];
        sum += histogram[b] * x;
        sum2 += histogram[b] * x * x;
    }
    double best = 0;
    Groups g;
    double below = 0, below_sum = 0, below_sum2 = 0;
    for (std::size_t b = 0; b + 1 < histogram.size(); ++b) {
        const double x = static_cast<double>(b);
        below += histogram[b];
        below_sum += histogram[b] * x;
        below_sum2 += histogram[b] * x * x;
        const double above = n - below;
        if (below < kLeastGroup * n || above < kLeastGroup * n) {
            continue;
        }
        const double m0 = below_sum / below, m1 = (sum - below_sum) / above;
        const double between = below * above * (m1 - m0) * (m1 - m0);
        if (between > best) {
            best = between;
            // bins' own width (1/12) keeps a spread of one-bin groups finite
            const double v0 = below_sum2 / below - m0 * m0 + 1.0 / 12;
            const double v1 = (sum2 - below_sum2) / above - m1 * m1 + 1.0 / 12;
            g = {from + static_cast<double>(b + 1) * width, (m1 - m0) / std::sqrt((v0 + v1) / 2)};
        }
    }
    return g;
}

bool is_foliage(const Hsv& c) { return c.h >= kFoliage.lo && c.h <= kFoliage.hi; }

/// The saturations of the points that are not foliage green nor black, in bins of 0.01, and
/// their Otsu split: grey or dark ground, bark, sky, pale and saturated fruit.
struct Saturations {
    std::vector<double> histogram = std::vector<double>(100, 0.0);
    Groups split;
};

Saturations not_foliage_saturations(const std::vector<Hsv>& sample) {
    Saturations out;
    for (const Hsv& c : sample) {
        if (c.v >= kBlack && !is_foliage(c)) {
            ++out.histogram[std::min<std::size_t>(99, static_cast<std::size_t>(100 * c.s))];
        }
    }
    out.split = otsu(out.histogram, 0, 0.01);
    return out;
}

/// The saturation from which a colour counts as saturated: `line`, or lower for pale fruit
/// (cream, pale yellow: saturation about 0.2, straddling 0.25). Where the saturations of the
/// points that are not foliage green form two groups (grey or dark ground, bark, sky; fruit)
/// split between kLeastSaturation and `line`, and `line` would cut off kStraddle of the upper
/// group, the split.
double saturation_line(const Saturations& not_foliage, double line) {
    const Groups& pale = not_foliage.split;
    double upper = 0, under_line = 0;  // the upper group, and its part under `line`
    for (std::size_t b = 0; b < not_foliage.histogram.size(); ++b) {
        const double lo = 0.01 * static_cast<double>(b);
        if (lo >= pale.at - 1e-9) {
            upper += not_foliage.histogram[b];
            under_line += lo + 0.01 <= line + 1e-9 ? not_foliage.histogram[b] : 0.0;
        }
    }
    return pale.separation >= kTwoGroups && pale.at < line && pale.at >= kLeastSaturation &&
                   under_line >= kStraddle * upper
               ? pale.at
               : line;
}

/// Where the pale points end: the saturation line `s`, or, where the points that are not
/// foliage green form two groups of saturation split above it (pale fruit under brown bark or
/// red fruit), the split.
double pale_line(const Saturations& not_foliage, double s) {
    const Groups& g = not_foliage.split;
    return g.separation >= kTwoGroups && g.at > s ? g.at : s;
}

/// Saturated (>= min_saturation) and not black.
ColorFilterParams saturated_rule(double min_saturation) {
    return {.saturation = Interval{min_saturation, 1}, .value = Interval{kBlack, 1}};
}

/// Saturated, not black, of that hue.
ColorFilterParams hue_rule(Interval hue, double min_saturation) {
    ColorFilterParams rule = saturated_rule(min_saturation);
    rule.hue_deg = hue;
    return rule;
}

/// A colour axis a rule can be narrowed on.
enum class Axis { kHue, kSaturation, kValue };

/// `rule` narrowed on `axis` to each side of `at` within `whole` (for hue, round from
/// whole.lo through `at` to whole.hi), each described as `head` + the side in words ("hue
/// 170..20 deg") + `tail`.
std::vector<ColourClass> two_sides(const ColorFilterParams& rule,
                                   Axis axis,
                                   Interval whole,
                                   double at,
                                   const std::string& head,
                                   const std::string& tail) {
    const char* name = axis == Axis::kHue          ? "hue "
                       : axis == Axis::kSaturation ? "saturation "
                                                   : "value ";
    std::vector<ColourClass> out;
    for (const Interval side : {Interval{whole.lo, at}, Interval{at, whole.hi}}) {
        ColorFilterParams r = rule;
        (axis == Axis::kHue          ? r.hue_deg
         : axis == Axis::kSaturation ? r.saturation
                                     : r.value) = side;
        out.push_back({r, head + name + format_number(side.lo) + ".." + format_number(side.hi) +
                              (axis == Axis::kHue ? " deg" : "") + tail});
    }
    return out;
}

/// The sample's colours `rule` keeps in two groups (fruit beside bark, ground or another fruit
/// colour): Otsu's split of their hue (round the rule's hue band from its start, or the whole
/// circle), saturation or value, whichever leaves the sides further apart, each side the rule
/// narrowed on that axis, described as `head` + its own words; none under kSomeGroups. With
/// `deeper`, each side's own two groups as well (`groups`: a side may hold the fruit beside
/// shaded bark whose noisy hues reach the fruit's).
std::vector<ColourClass> rule_groups(const std::vector<Hsv>& sample,
                                     const ColorFilterParams& rule,
                                     const std::string& head,
                                     bool deeper) {
    const Interval hue = rule.hue_deg.value_or(Interval{0, 360}),
                   saturation = rule.saturation.value_or(Interval{0, 1}),
                   value = rule.value.value_or(Interval{0, 1});
    const double band = std::fmod(hue.hi - hue.lo + 360, 360);
    std::vector<double> hues(static_cast<std::size_t>(band == 0 ? 360 : band), 0.0),
        saturations(100, 0.0), values(100, 0.0);
    for (const Hsv& c : sample) {
        if (c.h >= 0 && hsv_passes(c, rule)) {
            ++hues[std::min(hues.size() - 1,
                            static_cast<std::size_t>(std::fmod(c.h - hue.lo + 360, 360)))];
            ++saturations[std::min<std::size_t>(99, static_cast<std::size_t>(100 * c.s))];
            ++values[std::min<std::size_t>(99, static_cast<std::size_t>(100 * c.v))];
        }
    }
    const Groups by_hue = otsu(hues, 0, 1), by_saturation = otsu(saturations, 0, 0.01),
                 by_value = otsu(values, 0, 0.01);
    const double best =
        std::max({by_hue.separation, by_saturation.separation, by_value.separation});
    if (best < kSomeGroups) {
        return {};
    }
    const std::string apart =
        " of two groups (their means " + format_rounded(best) + " spreads apart)";
    std::vector<ColourClass> out =
        best == by_hue.separation
            ? two_sides(rule, Axis::kHue, hue, std::fmod(hue.lo + by_hue.at, 360), head, apart)
        : best == by_saturation.separation
            ? two_sides(rule, Axis::kSaturation, saturation, by_saturation.at, head, apart)
            : two_sides(rule, Axis::kValue, value, by_value.at, head, apart);
    if (deeper) {
        for (ColourClass& side : out) {
            side.groups = rule_groups(sample, side.rule, side.reason + ", ", false);
        }
    }
    return out;
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
    const double fixed = p.min_saturation;  // the words: a fixed saturation floor
    switch (p.color) {
        case FruitColor::kMask:
            return {ColorFilterParams{.min_mean = 0.5}, "mask: mean RGB > 0.5", {}};
        case FruitColor::kRed:
            return {hue_rule({320, 35}, fixed), "red: hue 320..35 deg", {}};
        case FruitColor::kOrange:
            return {hue_rule({10, 55}, fixed), "orange: hue 10..55 deg", {}};
        case FruitColor::kYellow:
            return {hue_rule({35, 80}, fixed), "yellow: hue 35..80 deg", {}};
        case FruitColor::kGreen:
            return {hue_rule({55, 170}, fixed), "green: hue 55..170 deg", {}};
        case FruitColor::kPurple:
            return {hue_rule({240, 350}, fixed), "purple: hue 240..350 deg", {}};
        case FruitColor::kAny:
            return {std::nullopt, "any: no colour rule", {}};
        case FruitColor::kAuto:
            break;
    }
    // A strided sample: the decision needs proportions, not every point.
    const std::size_t n = colours.size(), stride = std::max<std::size_t>(1, n / 100000);
    std::vector<Hsv> sample;
    for (std::size_t i = 0; i < n; i += stride) {
        const Hsv c = hsv(colours[i]);
        if (std::isfinite(c.s) && std::isfinite(c.v)) {
            sample.push_back(c);
        }
    }
    const Saturations not_foliage = not_foliage_saturations(sample);
    const double s = saturation_line(not_foliage, p.min_saturation);
    const std::string floor = s < p.min_saturation ? ", saturation >= " + format_number(s) +
                                                         " (the colours' own gap, below " +
                                                         format_number(p.min_saturation) + ")"
                                                   : "";
    std::size_t seen = sample.size(), grey = 0, mid_grey = 0, saturated = 0, foliage = 0;
    // the foliage hues in 1-degree bins, from half a degree below the band (8-bit colours hit
    // whole degrees, not the bins' edges)
    const double from = kFoliage.lo - 0.5;
    std::vector<double> greens(static_cast<std::size_t>(kFoliage.hi - kFoliage.lo) + 1, 0.0);
    std::vector<double> values(100, 0.0);  // their values, in bins of 0.01
    for (const Hsv& c : sample) {
        if (c.s < s) {
            ++grey;
            mid_grey += c.v > 0.25 && c.v < 0.75;
        } else {
            ++saturated;
            if (is_foliage(c)) {
                ++foliage;
                ++greens[std::min(greens.size() - 1, static_cast<std::size_t>(c.h - from))];
                ++values[std::min<std::size_t>(99, static_cast<std::size_t>(100 * c.v))];
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
        const std::string head =
            "auto: grey colours (" + percent(grey, seen) + " grey, not two-toned)";
        out.reason = head + ": no colour rule";
        // The greys may still form two groups (ivory fruit beside silver bark, values 0.96 and
        // 0.69): offered as classes, for the chain to count where one is claimed as fruit.
        out.classes = rule_groups(sample, {}, head + ", ", true);
        out.warnings.push_back(
            "the colours are grey and not a two-toned mask, so they cannot tell fruit from the "
            "rest: "
            "no colour filter was applied; give --fruit-color or a colour rule if they can");
        return out;
    }
    // Green fruit among leaves: the foliage-green points in two groups, of hue (a yellower and
    // a bluer green) or of value (dark fruit among lighter leaves), whichever lie further apart,
    // offered as two classes of the saturated points; returns the groups in words ("" if none).
    const Groups by_hue = otsu(greens, from, 1), by_value = otsu(values, 0, 0.01);
    const bool hue_wins = by_hue.separation >= by_value.separation;
    const Groups& g = hue_wins ? by_hue : by_value;
    const auto offer = [&](const std::string& head) {
        if (g.separation < kTwoGroups) {
            return std::string();
        }
        const std::string groups = head + ", in two groups of " +
                                   (hue_wins ? "hues split at " + format_number(g.at) + " deg"
                                             : "values split at " + format_number(g.at)) +
                                   " (their means " + format_rounded(g.separation) +
                                   " spreads apart)";
        const double lo = std::fmod(g.at + 180, 360);
        out.classes =
            hue_wins
                ? two_sides(saturated_rule(s), Axis::kHue, {lo, lo}, g.at, groups + ": ", "")
                : two_sides(saturated_rule(s), Axis::kValue, {kBlack, 1}, g.at, groups + ": ", "");
        for (ColourClass& k : out.classes) {
            k.groups = rule_groups(sample, k.rule, k.reason + ", ", false);
        }
        return groups;
    };
    // Pale fruit (cream, lavender, pale yellow) are under the saturation line: every rule below
    // misses them; their points are offered, for the chain to count where the rule's are not
    // claimed as fruit.
    const ColorFilterParams pale{.saturation = Interval{0, pale_line(not_foliage, s)},
                                 .value = Interval{kBlack, 1}};
    if (static_cast<double>(std::count_if(sample.begin(), sample.end(), [&](const Hsv& c) {
            return hsv_passes(c, pale);
        })) >= kLeastPale * static_cast<double>(seen)) {
        const std::string reason = "auto: natural colours: the pale points (saturation 0.." +
                                   format_number(pale.saturation->hi) +
                                   ", not black: cream, pale or greyish fruit)";
        out.pale = ColourClass{pale, reason, rule_groups(sample, pale, reason + ", ", true)};
    }
    const std::size_t fruitish = saturated - foliage;
    if (static_cast<double>(fruitish) < 0.03 * static_cast<double>(saturated)) {
        out.rule = saturated_rule(s);
        const std::string head = "auto: natural colours, " + percent(foliage, saturated) +
                                 " of the saturated points foliage green" + floor;
        out.reason = head + ": every saturated point";
        out.warnings.push_back(
            "nearly every coloured point is green: green fruit and leaves cannot be told apart by "
            "colour, so leaves were kept; check the count, or give --fruit-color");
        if (const std::string groups = offer(head); !groups.empty()) {
            out.reason = groups + ": every saturated point";
        }
        return out;
    }
    out.rule = hue_rule({kFoliage.hi, kFoliage.lo}, s);
    const std::string head =
        "auto: natural colours (" + percent(saturated, seen) + " saturated" + floor + ")";
    out.reason = head + ": saturated and not foliage green (hue 170..70 deg)";
    out.greens = ColourClass{hue_rule(kFoliage, s), head + ": saturated and foliage green (hue " +
                                                        format_number(kFoliage.lo) + ".." +
                                                        format_number(kFoliage.hi) + " deg)"};
    out.rule_classes = rule_groups(sample, *out.rule, out.reason + ", ", true);
    // The greens in two groups: the fruit may be among them (dark green fruit whose noisy hue
    // strays out of foliage, green fruit beside brown bark): the rule competes with the groups.
    if (const std::string groups =
            offer(head + ", " + percent(fruitish, saturated) + " of them not foliage green");
        !groups.empty()) {
        out.rule_competes = true;
        out.rule_first =
            static_cast<double>(fruitish) >= kFewFruitish * static_cast<double>(saturated);
        out.reason = groups + ": saturated and not foliage green (hue 170..70 deg)";
    }
    return out;
}

}  // namespace pc::filters
