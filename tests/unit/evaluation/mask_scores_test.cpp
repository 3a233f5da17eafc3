// Mask and image scores: confusion counts by hand, instance matching at IoU > 0.5, PSNR and SSIM
// against scipy.ndimage's Gaussian filter with scikit-image's SSIM formula (gaussian weights,
// σ 1.5, truncate 3.5, no sample covariance, 5-pixel crop).
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/evaluation/mask_scores.h>

namespace pc::evaluation {
namespace {

TEST(MaskScores, BinaryCountsAndRatios) {
    const std::vector<std::uint8_t> pred{1, 1, 1, 0, 0, 255, 0, 0};
    const std::vector<std::uint8_t> truth{1, 1, 0, 1, 0, 0, 0, 0};
    const BinaryScores s = binary_scores(pred, truth);
    EXPECT_EQ(s.tp, 2u);
    EXPECT_EQ(s.fp, 2u);
    EXPECT_EQ(s.fn, 1u);
    EXPECT_EQ(s.tn, 3u);
    EXPECT_DOUBLE_EQ(s.iou, 2.0 / 5);
    EXPECT_DOUBLE_EQ(s.dice, 4.0 / 7);
    EXPECT_DOUBLE_EQ(s.precision, 0.5);
    EXPECT_DOUBLE_EQ(s.recall, 2.0 / 3);
    const std::vector<std::uint8_t> none(8, 0);
    const BinaryScores e = binary_scores(none, none);  // nothing to find, nothing found
    EXPECT_EQ(e.iou, 1);
    EXPECT_EQ(e.recall, 1);
    EXPECT_EQ(binary_scores(pred, none).precision, 0);
    EXPECT_THROW((void)binary_scores(pred, std::vector<std::uint8_t>(3, 0)), InvalidArgument);
}

TEST(MaskScores, InstancesMatchAboveOneHalf) {
    // truth: A = 4 pixels, B = 4 pixels; pred: 7 covers A exactly, 8 covers 2 of B and 2 empty
    // pixels (IoU 2/6), 9 covers nothing true.
    const std::vector<std::uint32_t> truth{1, 1, 1, 1, 2, 2, 2, 2, 0, 0, 0};
    const std::vector<std::uint32_t> pred{7, 7, 7, 7, 8, 8, 0, 0, 8, 8, 9};
    const InstanceMaskScores s = instance_mask_scores(pred, truth);
    EXPECT_EQ(s.predicted, 3u);
    EXPECT_EQ(s.truth, 2u);
    EXPECT_EQ(s.matched, 1u);
    EXPECT_DOUBLE_EQ(s.precision, 1.0 / 3);
    EXPECT_DOUBLE_EQ(s.recall, 0.5);
    EXPECT_DOUBLE_EQ(s.mean_iou, 1.0);
}

TEST(MaskScores, PsnrAndSsimMatchTheReference) {
    constexpr int w = 24, h = 17;
    std::vector<std::uint8_t> a, b;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            a.push_back(static_cast<std::uint8_t>((x * 7 + y * 13) % 256));
            b.push_back(static_cast<std::uint8_t>((x * 7 + y * 13 + ((x * y) % 11) * 3) % 256));
        }
    }
    EXPECT_NEAR(psnr(a, b), 12.881607635862428, 1e-9);
    EXPECT_NEAR(ssim(a, b, w, h, 1), 0.5655108741005239, 1e-9);
    EXPECT_EQ(ssim(a, a, w, h, 1), 1.0);
    EXPECT_TRUE(std::isinf(psnr(a, a)));
    // two channels: the mean of the channels' SSIM
    std::vector<std::uint8_t> a2, b2;
    for (std::size_t i = 0; i < a.size(); ++i) {
        a2.insert(a2.end(), {a[i], a[i]});
        b2.insert(b2.end(), {b[i], a[i]});
    }
    EXPECT_NEAR(ssim(a2, b2, w, h, 2), (0.5655108741005239 + 1) / 2, 1e-9);
    EXPECT_THROW((void)ssim(a, b, 10, 10, 1), InvalidArgument);
}

}  // namespace
}  // namespace pc::evaluation
