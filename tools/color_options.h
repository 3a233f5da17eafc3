#pragma once
// The colour step's options, declared once for pc_colorfilter and pc_fruitcount: a fruit-colour
// word (the rule chosen from the cloud or named) or explicit rules, never both.

#include <cmath>
#include <optional>
#include <string>

#include <pc/cli/tool.h>
#include <pc/core/error.h>
#include <pc/filters/color_smooth.h>
#include <pc/filters/fruit_color.h>
#include <pc/pipeline/presets.h>

namespace pc::tools {

struct ColorOptions {
    filters::ColorFilterParams rules;               ///< the preset's rule, then the rule options
    std::optional<filters::FruitColorParams> word;  ///< the preset's word, or --fruit-color
    /// the preset's neighbourhood colours, or --color-smooth
    std::optional<filters::ColorSmoothParams> smooth;
    bool rules_given = false, word_given = false, invert = false;

    /// Starts from a preset's colour step.
    void from_preset(const pipeline::ChainParams& chain) {
        rules = chain.color.value_or(filters::ColorFilterParams{});
        word = chain.color ? std::nullopt : chain.fruit_color;
        smooth = chain.color_smooth;
    }
    /// Sets the chain's colour step (a fixed rule or a word); pc::InvalidArgument when a word and
    /// rules were both given.
    void apply(pipeline::ChainParams& chain) const {
        const bool with_rules = rules_given || invert;
        if (with_rules && word_given) {
            throw InvalidArgument(
                "give either --fruit-color or colour rules (--min-mean, --min-value, --hue, "
                "--saturation, --value, --invert), not both");
        }
        chain.color.reset();
        chain.fruit_color.reset();
        chain.color_smooth = smooth;
        if (word && !with_rules) {
            chain.fruit_color = word;
        } else {
            chain.color = rules;
            chain.color->invert = chain.color->invert || invert;
        }
    }
};

/// Binds --fruit-color, --min-mean, --min-value, --hue, --saturation, --value, --invert and
/// --color-smooth to `c`; each help text starts with `prefix`.
inline void bind_color_options(cli::Tool& tool, ColorOptions& c, const std::string& prefix) {
    tool.option(
        "fruit-color", "auto",
        [&c](const std::string& s) {
            c.word = filters::FruitColorParams{.color = filters::parse_fruit_color(s)};
            c.word_given = true;
        },
        prefix + filters::fruit_color_names() +
            ": auto decides from the cloud (mask exports: mean RGB > 0.5; natural colours: "
            "saturated and not foliage green); a word keeps that hue band; any keeps all");
    // A rule option: its text parsed by `parse(name, text)` into field `field` of the rules.
    const auto rule = [&](const char* name, auto field, auto parse, const std::string& help) {
        tool.option(
            name, "off",
            [&c, name, field, parse](const std::string& s) {
                c.rules.*field = parse(name, s);
                c.rules_given = true;
            },
            prefix + help);
    };
    using P = filters::ColorFilterParams;
    rule("min-mean", &P::min_mean, cli::parse_double,
         "keep iff (R+G+B)/3 > this; channels 0..1 (strict >)");
    rule("min-value", &P::min_value, cli::parse_double,
         "keep iff HSV value max(R,G,B) > this (strict >)");
    rule("hue", &P::hue_deg, filters::parse_interval,
         "keep iff hue in LO:HI degrees, ends included; LO > HI wraps (300:30); grey never "
         "matches");
    rule("saturation", &P::saturation, filters::parse_interval,
         "keep iff HSV saturation in LO:HI (0..1), ends included");
    rule("value", &P::value, filters::parse_interval,
         "keep iff HSV value in LO:HI (0..1), ends included");
    tool.flag("invert", &c.invert, prefix + "keep the points the rules reject instead");
    tool.option(
        "color-smooth", "auto",
        [&c](const std::string& s) {
            if (s == "off" || s == "0") {
                c.smooth.reset();
            } else if (s == "auto") {
                c.smooth = filters::kAutoColorSmooth;
            } else {
                const double k = cli::parse_double("color-smooth", s);
                if (!(k >= 1 && k <= 64 && k == std::floor(k))) {
                    throw InvalidArgument(
                        "--color-smooth: auto, off or a whole number of neighbours in 1..64, "
                        "got '" +
                        s + "'");
                }
                c.smooth = filters::ColorSmoothParams{.k = static_cast<std::uint32_t>(k)};
            }
        },
        prefix +
            "the rules read each point's colour as the median of its own and its K nearest "
            "neighbours' (SfM and NeRF colours vary from point to point): auto (K = 8 where the "
            "colours' noise is 10 of 255 or more), off, or K (always); the output keeps the "
            "cloud's colours",
        [&c] {
            return !c.smooth                 ? std::string("off")
                   : c.smooth->min_noise > 0 ? std::string("auto")
                                             : std::to_string(c.smooth->k);
        });
}

}  // namespace pc::tools
