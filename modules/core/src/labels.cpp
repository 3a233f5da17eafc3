#include <algorithm>
#include <limits>

#include <pc/core/labels.h>

namespace pc {

std::uint32_t renumber_by_size(std::vector<std::uint32_t>& labels, std::uint32_t min_size) {
    std::uint32_t max_label = 0;
    for (std::uint32_t l : labels) {
        max_label = std::max(max_label, l);
    }
    std::vector<std::uint32_t> size(std::size_t{max_label} + 1, 0);
    std::vector<std::uint32_t> first(std::size_t{max_label} + 1,
                                     std::numeric_limits<std::uint32_t>::max());
    for (std::uint32_t i = 0; i < labels.size(); ++i) {
        ++size[labels[i]];
        first[labels[i]] = std::min(first[labels[i]], i);
    }
    std::vector<std::uint32_t> ids;
    for (std::uint32_t l = 1; l <= max_label; ++l) {
        if (size[l] > 0 && size[l] >= min_size) {
            ids.push_back(l);
        }
    }
    std::sort(ids.begin(), ids.end(), [&](std::uint32_t a, std::uint32_t b) {
        return size[a] != size[b] ? size[a] > size[b] : first[a] < first[b];
    });
    std::vector<std::uint32_t> map(std::size_t{max_label} + 1, 0);
    for (std::uint32_t k = 0; k < ids.size(); ++k) {
        map[ids[k]] = k + 1;
    }
    for (auto& l : labels) {
        l = map[l];
    }
    return static_cast<std::uint32_t>(ids.size());
}

}  // namespace pc
