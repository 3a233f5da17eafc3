#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include <pc/evaluation/instances.h>

namespace pc::evaluation {

/// A ground-truth file: the fruit present and how many there are in all.
struct Truth {
    std::vector<TruthFruit> fruits;
    std::size_t fruit_count = 0;  ///< "fruit_count", or the number of fruits when absent
};

/// Parses {"fruit_count": N, "fruits": [{"id": > 0, "centre": [x, y, z], "radius": > 0}, ...]}
/// (pc_synth --truth; other keys are ignored). Throws pc::IoError naming what is wrong: not
/// JSON, a missing or mistyped key (with its JSON path), a zero id, a radius <= 0 or a
/// non-finite centre.
[[nodiscard]] Truth parse_truth(std::string_view json_text);

}  // namespace pc::evaluation
