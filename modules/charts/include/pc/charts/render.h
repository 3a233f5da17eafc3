#pragma once
// Draws plot panels (panel.h) into a PNG with OpenCV, for pc_plot and pc_maskeval.

#include <cstdint>
#include <vector>

#include <pc/charts/panel.h>

namespace pc::charts {

/// The panels side by side (640 x 420 each), as PNG bytes. Non-finite values are left out;
/// an empty panel says "no data". Throws pc::Error when the encoder fails.
[[nodiscard]] std::vector<std::uint8_t> render_png(const std::vector<Panel>& panels);

}  // namespace pc::charts
