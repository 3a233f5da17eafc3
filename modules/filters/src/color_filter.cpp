#include <algorithm>
#include <charconv>
#include <cmath>

#include <pc/core/error.h>
#include <pc/filters/color_filter.h>

namespace pc::filters {

namespace {

bool in(double v, const Interval& r) { return v >= r.lo && v <= r.hi; }

bool passes(const io::Rgb& c, const ColorFilterParams& p) {
    const double r = c.r, g = c.g, b = c.b;
    if (!(std::isfinite(r) && std::isfinite(g) && std::isfinite(b))) {
        return false;
    }
    if (p.min_mean && !((r + g + b) / 3.0 > *p.min_mean)) {
        return false;
    }
    return hsv_passes(hsv(c), p);
}

}  // namespace

Hsv hsv(const io::Rgb& c) {
    const double r = c.r, g = c.g, b = c.b;
    const double mx = std::max({r, g, b}), mn = std::min({r, g, b});
    Hsv out{-1, mx > 0 ? (mx - mn) / mx : 0.0, mx};
    if (mx > mn) {
        const double d = mx - mn;
        const double h = 60.0 * (mx == r   ? std::fmod((g - b) / d, 6.0)
                                 : mx == g ? (b - r) / d + 2
                                           : (r - g) / d + 4);
        out.h = h < 0 ? h + 360.0 : h;
    }
    return out;
}

bool hsv_passes(const Hsv& x, const ColorFilterParams& p) {
    if (p.min_value && !(x.v > *p.min_value)) {
        return false;
    }
    if (p.value && !in(x.v, *p.value)) {
        return false;
    }
    if (p.saturation && !in(x.s, *p.saturation)) {
        return false;
    }
    if (p.hue_deg) {
        if (x.h < 0) {
            return false;  // grey has no hue
        }
        const Interval& w = *p.hue_deg;
        if (!(w.lo <= w.hi ? in(x.h, w) : (x.h >= w.lo || x.h <= w.hi))) {
            return false;
        }
    }
    return true;
}

Interval parse_interval(const std::string& option, const std::string& text) {
    const auto colon = text.find(':');
    Interval r;
    const auto num = [&](std::string_view s, double& v) {
        const auto res = std::from_chars(s.data(), s.data() + s.size(), v);
        return !s.empty() && res.ec == std::errc{} && res.ptr == s.data() + s.size();
    };
    if (colon == std::string::npos || !num(std::string_view(text).substr(0, colon), r.lo) ||
        !num(std::string_view(text).substr(colon + 1), r.hi)) {
        throw InvalidArgument("--" + option + ": expected LO:HI, got '" + text + "'");
    }
    return r;
}

void ColorFilterParams::validate() const {
    const auto unit = [](const char* name, const std::optional<Interval>& r) {
        if (r && !(r->lo >= 0 && r->hi <= 1 && r->lo <= r->hi)) {
            throw InvalidArgument(std::string("color_filter: ") + name +
                                  " must be LO:HI with 0 <= LO <= HI <= 1, got " +
                                  format_number(r->lo) + ":" + format_number(r->hi));
        }
    };
    unit("saturation", saturation);
    unit("value", value);
    if (hue_deg &&
        !(hue_deg->lo >= 0 && hue_deg->lo <= 360 && hue_deg->hi >= 0 && hue_deg->hi <= 360)) {
        throw InvalidArgument("color_filter: hue must be LO:HI degrees in 0..360, got " +
                              format_number(hue_deg->lo) + ":" + format_number(hue_deg->hi));
    }
    for (const auto& [name, v] : {std::pair{"min_mean", min_mean}, {"min_value", min_value}}) {
        if (v && !(*v >= -1 && *v <= 1)) {
            throw InvalidArgument(std::string("color_filter: ") + name +
                                  " must be in [-1, 1], got " + format_number(*v));
        }
    }
}

ColorFilterResult color_filter(std::span<const io::Rgb> colours, const ColorFilterParams& params) {
    params.validate();
    ColorFilterResult r;
    for (std::uint32_t i = 0; i < colours.size(); ++i) {
        if (passes(colours[i], params) != params.invert) {
            r.kept.push_back(i);
        }
    }
    return r;
}

}  // namespace pc::filters
