#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include <pc/core/error.h>
#include <pc/evaluation/mask_scores.h>

namespace pc::evaluation {

namespace {

double ratio(std::uint64_t num, std::uint64_t den, bool both_empty) {
    return den == 0 ? (both_empty ? 1.0 : 0.0)
                    : static_cast<double>(num) / static_cast<double>(den);
}

void same_size(std::size_t a, std::size_t b, const char* what) {
    if (a != b) {
        throw InvalidArgument(std::string(what) + ": the images differ in size (" +
                              std::to_string(a) + " and " + std::to_string(b) + " samples)");
    }
}

/// Separable Gaussian filter (σ 1.5, radius 5) with scipy.ndimage's 'reflect' borders.
std::vector<double> blur(const std::vector<double>& in, int w, int h) {
    constexpr int r = 5;
    double k[2 * r + 1], sum = 0;
    for (int i = -r; i <= r; ++i) {
        k[i + r] = std::exp(-0.5 * i * i / (1.5 * 1.5));
        sum += k[i + r];
    }
    for (double& v : k) {
        v /= sum;
    }
    const auto reflect = [](int i, int n) {
        while (i < 0 || i >= n) {
            i = i < 0 ? -i - 1 : 2 * n - i - 1;
        }
        return i;
    };
    std::vector<double> tmp(in.size()), out(in.size());
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            double s = 0;
            for (int i = -r; i <= r; ++i) {
                s += k[i + r] * in[static_cast<std::size_t>(y) * w + reflect(x + i, w)];
            }
            tmp[static_cast<std::size_t>(y) * w + x] = s;
        }
    }
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            double s = 0;
            for (int i = -r; i <= r; ++i) {
                s += k[i + r] * tmp[static_cast<std::size_t>(reflect(y + i, h)) * w + x];
            }
            out[static_cast<std::size_t>(y) * w + x] = s;
        }
    }
    return out;
}

}  // namespace

BinaryScores binary_scores(std::span<const std::uint8_t> pred,
                           std::span<const std::uint8_t> truth) {
    same_size(pred.size(), truth.size(), "binary_scores");
    BinaryScores s;
    for (std::size_t i = 0; i < pred.size(); ++i) {
        const bool p = pred[i] != 0, t = truth[i] != 0;
        s.tp += p && t;
        s.fp += p && !t;
        s.fn += !p && t;
        s.tn += !p && !t;
    }
    const bool empty = s.tp + s.fp + s.fn == 0;
    s.iou = ratio(s.tp, s.tp + s.fp + s.fn, empty);
    s.dice = ratio(2 * s.tp, 2 * s.tp + s.fp + s.fn, empty);
    s.precision = ratio(s.tp, s.tp + s.fp, s.tp + s.fn == 0);
    s.recall = ratio(s.tp, s.tp + s.fn, s.tp + s.fp == 0);
    return s;
}

InstanceMaskScores instance_mask_scores(std::span<const std::uint32_t> pred,
                                        std::span<const std::uint32_t> truth) {
    same_size(pred.size(), truth.size(), "instance_mask_scores");
    std::unordered_map<std::uint32_t, std::uint64_t> area_p, area_t;
    std::unordered_map<std::uint64_t, std::uint64_t> inter;
    for (std::size_t i = 0; i < pred.size(); ++i) {
        if (pred[i] != 0) {
            ++area_p[pred[i]];
        }
        if (truth[i] != 0) {
            ++area_t[truth[i]];
        }
        if (pred[i] != 0 && truth[i] != 0) {
            ++inter[(std::uint64_t{pred[i]} << 32) | truth[i]];
        }
    }
    InstanceMaskScores s;
    s.predicted = area_p.size();
    s.truth = area_t.size();
    double iou_sum = 0;
    for (const auto& [key, n] : inter) {
        const auto p = static_cast<std::uint32_t>(key >> 32), t = static_cast<std::uint32_t>(key);
        const double iou = static_cast<double>(n) / static_cast<double>(area_p[p] + area_t[t] - n);
        if (iou > 0.5) {  // at most one partner each above one half
            ++s.matched;
            iou_sum += iou;
        }
    }
    s.precision = s.predicted == 0
                      ? (s.truth == 0 ? 1.0 : 0.0)
                      : static_cast<double>(s.matched) / static_cast<double>(s.predicted);
    s.recall = s.truth == 0 ? (s.predicted == 0 ? 1.0 : 0.0)
                            : static_cast<double>(s.matched) / static_cast<double>(s.truth);
    s.f1 = s.precision + s.recall > 0 ? 2 * s.precision * s.recall / (s.precision + s.recall) : 0;
    s.mean_iou = s.matched > 0 ? iou_sum / static_cast<double>(s.matched) : 0;
    return s;
}

double psnr(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b) {
    same_size(a.size(), b.size(), "psnr");
    if (a.empty()) {
        throw InvalidArgument("psnr: empty images");
    }
    double se = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const double d = static_cast<double>(a[i]) - static_cast<double>(b[i]);
        se += d * d;
    }
    const double mse = se / static_cast<double>(a.size());
    return mse == 0 ? std::numeric_limits<double>::infinity()
                    : 10 * std::log10(255.0 * 255.0 / mse);
}

double ssim(std::span<const std::uint8_t> a,
            std::span<const std::uint8_t> b,
            int width,
            int height,
            int channels) {
    same_size(a.size(), b.size(), "ssim");
    if (width < 11 || height < 11 || channels < 1 ||
        a.size() != static_cast<std::size_t>(width) * height * channels) {
        throw InvalidArgument(
            "ssim: images must be at least 11 x 11 and width x height x "
            "channels samples");
    }
    const double c1 = std::pow(0.01 * 255, 2), c2 = std::pow(0.03 * 255, 2);
    const std::size_t n = static_cast<std::size_t>(width) * height;
    double total = 0;
    for (int c = 0; c < channels; ++c) {
        std::vector<double> x(n), y(n), xx(n), yy(n), xy(n);
        for (std::size_t i = 0; i < n; ++i) {
            x[i] = a[i * channels + c];
            y[i] = b[i * channels + c];
            xx[i] = x[i] * x[i];
            yy[i] = y[i] * y[i];
            xy[i] = x[i] * y[i];
        }
        const auto ux = blur(x, width, height), uy = blur(y, width, height);
        const auto uxx = blur(xx, width, height), uyy = blur(yy, width, height),
                   uxy = blur(xy, width, height);
        double sum = 0;
        std::size_t count = 0;
        for (int yy0 = 5; yy0 < height - 5; ++yy0) {
            for (int xx0 = 5; xx0 < width - 5; ++xx0) {
                const std::size_t i = static_cast<std::size_t>(yy0) * width + xx0;
                const double vx = uxx[i] - ux[i] * ux[i], vy = uyy[i] - uy[i] * uy[i],
                             vxy = uxy[i] - ux[i] * uy[i];
                sum += ((2 * ux[i] * uy[i] + c1) * (2 * vxy + c2)) /
                       ((ux[i] * ux[i] + uy[i] * uy[i] + c1) * (vx + vy + c2));
                ++count;
            }
        }
        total += sum / static_cast<double>(count);
    }
    return total / channels;
}

}  // namespace pc::evaluation
