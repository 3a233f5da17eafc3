#pragma once
// Enumerations read from and printed as words (--rule cores, --mode implicit): one table per
// enumeration gives both directions, so a word and its value are written once.

#include <span>
#include <string>
#include <string_view>
#include <utility>

#include <pc/core/error.h>

namespace pc {

template <class E>
using NameTable = std::span<const std::pair<std::string_view, E>>;

/// The value named `text` in `table`; pc::InvalidArgument "<what> must be a, b or c, got 'x'".
template <class E>
[[nodiscard]] E parse_name(NameTable<E> table, std::string_view text, const std::string& what) {
    std::string words;
    for (std::size_t k = 0; k < table.size(); ++k) {
        if (table[k].first == text) {
            return table[k].second;
        }
        words += std::string(k == 0 ? "" : (k + 1 == table.size() ? " or " : ", ")) +
                 std::string(table[k].first);
    }
    throw InvalidArgument(what + " must be " + words + ", got '" + std::string(text) + "'");
}

/// The word for `value` in `table` ("?" when it has none).
template <class E>
[[nodiscard]] std::string name_of(NameTable<E> table, E value) {
    for (const auto& [word, v] : table) {
        if (v == value) {
            return std::string(word);
        }
    }
    return "?";
}

}  // namespace pc
