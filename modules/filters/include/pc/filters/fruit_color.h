#pragma once

#include <span>
#include <string>
#include <vector>

#include <pc/filters/color_filter.h>
#include <pc/io/points.h>

namespace pc::filters {

/// What colour the fruit are: `auto` decides from the cloud (docs/tools/pc_fruitcount.md).
enum class FruitColor { kAuto, kMask, kRed, kOrange, kYellow, kGreen, kPurple, kAny };

/// Parses auto, mask, red, orange, yellow, green, purple or any; throws pc::InvalidArgument.
[[nodiscard]] FruitColor parse_fruit_color(const std::string& text);
[[nodiscard]] std::string fruit_color_name(FruitColor c);
/// The words, in order, for --help.
[[nodiscard]] std::string fruit_color_names();

struct FruitColorParams {
    FruitColor color = FruitColor::kAuto;
    /// Natural colours: fruit are saturated (HSV saturation >= this); grey ground, sky, bark
    /// highlights are not.
    double min_saturation = 0.25;
    void validate() const;
};

/// One of two colour classes the colours alone cannot call fruit or leaves.
struct ColourClass {
    ColorFilterParams rule;
    std::string reason;  ///< why and what, for the report, when this class is kept
    /// Its own points in two groups, where they form them (FruitColorChoice::rule_classes)
    std::vector<ColourClass> groups;
};

/// The colour rule chosen for a cloud.
struct FruitColorChoice {
    std::optional<ColorFilterParams> rule;  ///< empty: keep every point
    std::string reason;                     ///< what was seen and chosen, for the report
    std::vector<std::string> warnings;      ///< the choice is doubtful
    /// When (nearly) every coloured point is green but the greens form two groups (green fruit
    /// among leaves of another green, dark fruit among lighter leaves): the two, for a shape
    /// test to choose between (pipeline::run_chain keeps the one whose points fruit centres
    /// claim, else `rule`). Each with its own two groups where they form them (a class of hue
    /// round the circle may hold the fruit with bark of another hue). Grey colours that are no
    /// two-toned mask (no `rule`): their two groups likewise (ivory fruit beside silver bark).
    std::vector<ColourClass> classes;
    /// `rule` is itself a candidate (3 % or more of the saturated points outside foliage hue):
    /// a class is kept instead only where its fruit centres claim more of its points than the
    /// rule's claim of its own
    bool rule_competes = false;
    /// ... and it is tried first, and kept unless its centres claim too few of its points to
    /// be fruit (10 % or more of the saturated points outside foliage hue: the groups are tried
    /// where those are bark, not fruit)
    bool rule_first = false;
    /// The points `rule` keeps in two groups (of hue, saturation or value): tried, each alone,
    /// where the rule's fruit centres claim too few of its points (bark or ground kept with
    /// the fruit); each with its own two groups (`groups`), tried where neither is the fruit
    std::vector<ColourClass> rule_classes;
    /// The saturated points of foliage hue: counted instead of `rule` where its centres claim
    /// too few of its points and no group was kept (green fruit beside bark: the rule kept the
    /// bark; the leaves are sheets the split drops)
    std::optional<ColourClass> greens;
    /// Natural colours: the points under the saturation line (or under the split of two
    /// saturation groups above it: pale fruit beside brown bark) and not black, where they are 3 %
    /// or more: counted instead of `rule` where its centres claim too few of its points and
    /// nothing else was kept (cream fruit: the rule kept the bark, or the leaves), with their own
    /// two groups (`groups`: the fruit beside dark ground), each with its own two groups (hues
    /// first part the greys, then values the lit fruit from bark as pale as them)
    std::optional<ColourClass> pale;
};

/// Chooses the colour rule. A word other than auto maps to a fixed rule: mask -> the paper's
/// (mean RGB > 0.5), a hue word -> that hue band with saturation >= min_saturation, any -> none.
/// auto looks at the colours (a sample of at most 100000 points):
///  - nine in ten points grey (saturation < min_saturation): a mask export when the greys are
///    two-toned (fewer than one in five between 0.25 and 0.75 in value): the paper's rule; else
///    the colours say nothing about fruit: no rule, and a warning;
///  - otherwise natural colours: keep saturated points whose hue is not foliage green
///    (70..170 degrees); if fewer than 3 % of the saturated points are not green, the fruit look
///    green too: keep every saturated point, with a warning (leaves are kept; give the word);
///    and when the green points form two groups, of hue or of value (the further apart), offer
///    the two as `classes`; with more points outside foliage hue (dark green fruit stray out of
///    it, brown bark), the same, and the rule competes (`rule_competes`; from 10 % it is tried
///    first, `rule_first`); and when the points the rule keeps form two groups of hue,
///    saturation or value (fruit beside bark or ground: looser, 3 spreads apart), offer them as
///    `rule_classes`, each with its own two groups where they form them (`groups`: a hue
///    group of the fruit may hold shaded bark whose dark points' hues are noise); the saturated
///    points of foliage hue are `greens`; the points under the saturation line (or under the
///    split of two saturation groups above it) and not black are `pale`, 3 % of them or more.
/// Two groups: Otsu's threshold on the histogram leaves the means of its sides at least 4 times
/// their rms spread apart, each side 5 % of the points or more. Pale fruit: when the saturations
/// of the points that are not foliage green form two groups split below min_saturation (and at
/// 0.1 or more), and min_saturation would cut off a tenth or more of the upper group,
/// "saturated" means at or above that split.
[[nodiscard]] FruitColorChoice choose_fruit_color(std::span<const io::Rgb> colours,
                                                  const FruitColorParams& params);

}  // namespace pc::filters
