#include <algorithm>
#include <cmath>
#include <cstdio>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <pc/charts/render.h>
#include <pc/core/error.h>
#include <pc/core/stats.h>

namespace pc::charts {

namespace {

constexpr int kWidth = 640, kHeight = 420;
constexpr int kLeft = 84, kRight = 20, kTop = 40, kBottom = 56;
const cv::Scalar kInk(40, 40, 40), kGrid(225, 225, 225), kFill(140, 104, 59),  // BGR
    kMark(40, 40, 200);

std::string tick(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", std::abs(v) < 1e-12 ? 0.0 : v);
    return buf;
}

/// The smallest of 1, 2, 2.5, 5 x 10^k at least `x` (> 0): a step that reads well.
double nice_step(double x) {
    const double p = std::pow(10.0, std::floor(std::log10(x)));
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0}) {
        if (m * p >= x * (1 - 1e-9)) {
            return m * p;
        }
    }
    return 10 * p;
}

void text(
    cv::Mat& m, const std::string& s, int x, int y, double scale = 0.45, bool centre = false) {
    int base = 0;
    const cv::Size size = cv::getTextSize(s, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base);
    cv::putText(m, s, cv::Point(centre ? x - size.width / 2 : x, y), cv::FONT_HERSHEY_SIMPLEX,
                scale, kInk, 1, cv::LINE_AA);
}

int widest(const std::vector<std::string>& names, double scale) {
    int w = 0;
    for (const auto& n : names) {
        int base = 0;
        w = std::max(w, cv::getTextSize(n, cv::FONT_HERSHEY_SIMPLEX, scale, 1, &base).width);
    }
    return w;
}

/// The plot area and a linear y axis from lo to hi, with grid lines and labels.
struct Axes {
    cv::Rect area{kLeft, kTop, kWidth - kLeft - kRight, kHeight - kTop - kBottom};
    double lo = 0, hi = 1, step = 0.25;
    /// Widens [lo, hi] to multiples of a nice step, about four of them.
    void fit(double from, double to) {
        if (!(to > from)) {
            to = from + 1;
        }
        step = nice_step((to - from) / 4);
        lo = std::floor(from / step) * step;
        hi = std::ceil(to / step) * step;
    }
    [[nodiscard]] int y(double v) const {
        const double t = hi > lo ? (v - lo) / (hi - lo) : 0.5;
        return area.y + area.height - static_cast<int>(std::lround(t * area.height));
    }
    void draw(cv::Mat& m) const {
        for (double v = lo; v <= hi + 0.5 * step; v += step) {
            cv::line(m, {area.x, y(v)}, {area.x + area.width, y(v)}, kGrid, 1);
            int base = 0;
            const int w = cv::getTextSize(tick(v), cv::FONT_HERSHEY_SIMPLEX, 0.4, 1, &base).width;
            text(m, tick(v), area.x - 6 - w, y(v) + 4, 0.4);
        }
        cv::rectangle(m, area, kInk, 1);
    }
};

std::vector<double> finite(const std::vector<double>& v) {
    std::vector<double> out;
    std::copy_if(v.begin(), v.end(), std::back_inserter(out),
                 [](double x) { return std::isfinite(x); });
    return out;
}

void histogram(cv::Mat& m, const Panel& p) {
    const std::vector<double> v = p.values.empty() ? std::vector<double>{} : finite(p.values[0]);
    if (v.empty()) {
        text(m, "no data", kWidth / 2, kHeight / 2, 0.6, true);
        return;
    }
    const auto [mn, mx] = std::minmax_element(v.begin(), v.end());
    const double lo = *mn, hi = *mx > *mn ? *mx : *mn + 1;
    const int bins = std::clamp(static_cast<int>(std::ceil(std::sqrt(v.size()))), 5, 40);
    std::vector<int> count(static_cast<std::size_t>(bins), 0);
    for (double x : v) {
        ++count[static_cast<std::size_t>(
            std::min(bins - 1, static_cast<int>((x - lo) / (hi - lo) * bins)))];
    }
    Axes a;
    a.fit(0, *std::max_element(count.begin(), count.end()));
    a.draw(m);
    const double w = static_cast<double>(a.area.width) / bins;
    for (int b = 0; b < bins; ++b) {
        const int x0 = a.area.x + static_cast<int>(std::lround(b * w));
        const int x1 = a.area.x + static_cast<int>(std::lround((b + 1) * w)) - 1;
        if (count[static_cast<std::size_t>(b)] > 0) {
            cv::rectangle(m, cv::Point(x0, a.y(count[static_cast<std::size_t>(b)])),
                          cv::Point(x1, a.y(0)), kFill, cv::FILLED);
        }
    }
    std::vector<double> copy = v;
    const double med = median(copy);
    const int xm = a.area.x + static_cast<int>(std::lround((med - lo) / (hi - lo) * a.area.width));
    cv::line(m, {xm, a.area.y}, {xm, a.area.y + a.area.height}, kMark, 2);
    text(m, "median " + tick(med), std::min(xm + 4, kWidth - 150), a.area.y + 16, 0.45);
    const int yb = a.area.y + a.area.height + 18;
    text(m, tick(lo), a.area.x, yb, 0.4);
    text(m, tick(hi), a.area.x + a.area.width, yb, 0.4, true);
    text(m, p.xlabel + " (" + std::to_string(v.size()) + " values)", kWidth / 2, yb + 20, 0.45,
         true);
}

void boxes(cv::Mat& m, const Panel& p) {
    std::vector<std::vector<double>> groups;
    double lo = INFINITY, hi = -INFINITY;
    for (const auto& g : p.values) {
        groups.push_back(finite(g));
        for (double x : groups.back()) {
            lo = std::min(lo, x);
            hi = std::max(hi, x);
        }
    }
    if (!(lo <= hi)) {
        text(m, "no data", kWidth / 2, kHeight / 2, 0.6, true);
        return;
    }
    Axes a;
    const double pad = hi > lo ? 0.05 * (hi - lo) : 0.5;
    a.fit(lo - pad, hi + pad);
    a.draw(m);
    const double slot = static_cast<double>(a.area.width) / std::max<std::size_t>(1, groups.size());
    for (std::size_t k = 0; k < groups.size(); ++k) {
        const int cx = a.area.x + static_cast<int>(std::lround((k + 0.5) * slot));
        const int half = static_cast<int>(std::min(60.0, slot * 0.3));
        if (k < p.names.size()) {
            text(m, p.names[k], cx, a.area.y + a.area.height + 18, 0.45, true);
        }
        std::vector<double> g = groups[k];
        if (g.empty()) {
            continue;
        }
        std::vector<double> c1 = g, c2 = g, c3 = g;
        const double q1 = percentile(c1, 25), q2 = percentile(c2, 50), q3 = percentile(c3, 75);
        const double iqr = q3 - q1;
        double wlo = q1, whi = q3;
        for (double x : g) {
            if (x >= q1 - 1.5 * iqr) {
                wlo = std::min(wlo, x);
            }
            if (x <= q3 + 1.5 * iqr) {
                whi = std::max(whi, x);
            }
        }
        cv::line(m, {cx, a.y(wlo)}, {cx, a.y(q1)}, kInk, 1);
        cv::line(m, {cx, a.y(q3)}, {cx, a.y(whi)}, kInk, 1);
        cv::line(m, {cx - half / 2, a.y(wlo)}, {cx + half / 2, a.y(wlo)}, kInk, 1);
        cv::line(m, {cx - half / 2, a.y(whi)}, {cx + half / 2, a.y(whi)}, kInk, 1);
        cv::rectangle(m, cv::Point(cx - half, a.y(q3)), cv::Point(cx + half, a.y(q1)), kFill,
                      cv::FILLED);
        cv::rectangle(m, cv::Point(cx - half, a.y(q3)), cv::Point(cx + half, a.y(q1)), kInk, 1);
        cv::line(m, {cx - half, a.y(q2)}, {cx + half, a.y(q2)}, kMark, 2);
        for (double x : g) {
            if (x < wlo || x > whi) {
                cv::circle(m, {cx, a.y(x)}, 3, kInk, 1, cv::LINE_AA);
            }
        }
        text(m, "n " + std::to_string(g.size()) + ", median " + tick(q2), cx,
             a.area.y + a.area.height + 36, 0.38, true);
    }
}

void bars(cv::Mat& m, const Panel& p) {
    const std::vector<double> v = p.values.empty() ? std::vector<double>{} : p.values[0];
    double hi = 0;
    for (double x : v) {
        if (std::isfinite(x)) {
            hi = std::max(hi, x);
        }
    }
    if (v.empty()) {
        text(m, "no data", kWidth / 2, kHeight / 2, 0.6, true);
        return;
    }
    Axes a;
    a.fit(0, hi > 0 ? hi * 1.08 : 1);
    a.draw(m);
    const double slot = static_cast<double>(a.area.width) / v.size();
    const int stagger = widest(p.names, 0.42) > slot - 6 ? 16 : 0;
    for (std::size_t k = 0; k < v.size(); ++k) {
        const int cx = a.area.x + static_cast<int>(std::lround((k + 0.5) * slot));
        const int half = static_cast<int>(std::min(50.0, slot * 0.35));
        if (std::isfinite(v[k]) && v[k] > 0) {
            cv::rectangle(m, cv::Point(cx - half, a.y(v[k])), cv::Point(cx + half, a.y(0)), kFill,
                          cv::FILLED);
        }
        text(m, std::isfinite(v[k]) ? tick(v[k]) : "n/a", cx,
             std::isfinite(v[k]) ? a.y(std::max(0.0, v[k])) - 6 : a.y(0) - 6, 0.4, true);
        if (k < p.names.size()) {  // every other name a line lower when they would touch
            text(m, p.names[k], cx, a.area.y + a.area.height + 18 + (k % 2) * stagger, 0.42, true);
        }
    }
}

}  // namespace

std::vector<std::uint8_t> render_png(const std::vector<Panel>& panels) {
    std::vector<cv::Mat> tiles;
    for (const Panel& p : panels) {
        cv::Mat m(kHeight, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
        text(m, p.title, kWidth / 2, 24, 0.6, true);
        switch (p.kind) {
            case Panel::Kind::kHistogram:
                histogram(m, p);
                break;
            case Panel::Kind::kBox:
                boxes(m, p);
                break;
            case Panel::Kind::kBars:
                bars(m, p);
                break;
        }
        tiles.push_back(m);
    }
    cv::Mat sheet;
    if (tiles.empty()) {
        sheet = cv::Mat(kHeight, kWidth, CV_8UC3, cv::Scalar(255, 255, 255));
    } else {
        cv::hconcat(tiles, sheet);
    }
    std::vector<std::uint8_t> png;
    if (!cv::imencode(".png", sheet, png)) {
        throw Error("plot: the PNG encoder failed");
    }
    return png;
}

}  // namespace pc::charts
