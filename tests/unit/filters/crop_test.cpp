#include <gtest/gtest.h>

#include <pc/core/error.h>
#include <pc/filters/crop.h>

#include "support/clouds.h"

namespace pc::filters {
namespace {

TEST(Crop, BoxEndsAreIncluded) {
    const Cloud c = test::grid({0, 0, 0}, 3, 1.0f);  // coordinates 0, 1, 2
    const CropResult r = crop(c, {.min = {0, 0, 0}, .max = {1, 1, 1}});
    EXPECT_EQ(r.kept.size(), 8u);  // 2 x 2 x 2, faces included
}

TEST(Crop, InvertIsTheComplementAndNanIsOutside) {
    Cloud c = test::grid({0, 0, 0}, 3, 1.0f);
    c.push_back(test::nan_point());
    const CropParams in{.min = {0.5, -1, -1}, .max = {2, 2, 2}};
    CropParams out = in;
    out.invert = true;
    const auto a = crop(c, in).kept, b = crop(c, out).kept;
    EXPECT_EQ(a.size() + b.size(), c.size());
    EXPECT_EQ(b.back(), c.size() - 1);  // the NaN point is outside
}

TEST(Crop, RejectsMinAboveMax) {
    EXPECT_THROW((void)crop(test::grid({0, 0, 0}, 2, 1.0f), {.min = {1, 0, 0}, .max = {0, 1, 1}}),
                 InvalidArgument);
}

}  // namespace
}  // namespace pc::filters
