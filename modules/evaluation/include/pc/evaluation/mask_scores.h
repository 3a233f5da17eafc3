#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace pc::evaluation {

/// Binary mask agreement: pixels are fruit where non-zero. Ratios with a zero denominator are
/// 1 when both masks are empty there (nothing to find, nothing found), else 0.
struct BinaryScores {
    std::uint64_t tp = 0, fp = 0, fn = 0, tn = 0;
    double iou = 0;        ///< tp / (tp + fp + fn)
    double dice = 0;       ///< 2 tp / (2 tp + fp + fn)
    double precision = 0;  ///< tp / (tp + fp)
    double recall = 0;     ///< tp / (tp + fn)
};

/// Scores `pred` against `truth`, pixel by pixel (the same number of pixels; else
/// pc::InvalidArgument).
[[nodiscard]] BinaryScores binary_scores(std::span<const std::uint8_t> pred,
                                         std::span<const std::uint8_t> truth);

/// Instance masks (one id per pixel, 0 background) matched one to one at IoU > 0.5 (at most one
/// match each at that threshold, so no assignment problem).
struct InstanceMaskScores {
    std::size_t predicted = 0, truth = 0, matched = 0;
    double precision = 0, recall = 0, f1 = 0;
    double mean_iou = 0;  ///< over matched pairs (0 without any)
};

[[nodiscard]] InstanceMaskScores instance_mask_scores(std::span<const std::uint32_t> pred,
                                                      std::span<const std::uint32_t> truth);

/// PSNR in dB of two images of 8-bit samples (any number of channels, the same layout):
/// 10 log10(255² / MSE); infinity for identical images.
[[nodiscard]] double psnr(std::span<const std::uint8_t> a, std::span<const std::uint8_t> b);

/// SSIM (Wang et al. 2004) of two images of 8-bit samples, width × height × channels
/// interleaved: a Gaussian window of σ 1.5 truncated at 3.5σ (as scikit-image's
/// gaussian_weights=True), K1 0.01, K2 0.03, L 255, sample covariances; the mean over the pixels
/// at least 5 from the border (scikit-image's crop) and over the channels.
[[nodiscard]] double ssim(std::span<const std::uint8_t> a,
                          std::span<const std::uint8_t> b,
                          int width,
                          int height,
                          int channels);

}  // namespace pc::evaluation
