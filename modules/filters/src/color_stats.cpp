#include <algorithm>
#include <vector>

#include <pc/core/stats.h>
#include <pc/filters/color_filter.h>
#include <pc/filters/color_stats.h>

namespace pc::filters {

namespace {

Spread spread(std::vector<double>& v) {
    Spread s;
    if (!v.empty()) {
        s.p10 = percentile(v, 10);
        s.median = percentile(v, 50);
        s.p90 = percentile(v, 90);
    }
    return s;
}

}  // namespace

ColorStats color_stats(std::span<const io::Rgb> colours) {
    ColorStats out;
    out.points = colours.size();
    std::vector<double> r, g, b, sat, val;
    for (auto* v : {&r, &g, &b, &sat, &val}) {
        v->reserve(colours.size());
    }
    for (const io::Rgb& c : colours) {
        r.push_back(c.r);
        g.push_back(c.g);
        b.push_back(c.b);
        const Hsv h = hsv(c);
        sat.push_back(h.s);
        val.push_back(h.v);
        if (h.h < 0) {
            ++out.grey;
        } else {
            ++out.hue_histogram[static_cast<std::size_t>((h.h + 15.0) / 30.0) % 12];
        }
    }
    out.red = spread(r);
    out.green = spread(g);
    out.blue = spread(b);
    out.saturation = spread(sat);
    out.value = spread(val);
    return out;
}

}  // namespace pc::filters
