#pragma once
// Output names per input for the tools that take several (`--cloud out/{stem}.pcd`).

#include <cstddef>
#include <filesystem>
#include <string>

#include <pc/core/error.h>

namespace pc::tools {

/// `pattern` with every "{stem}" replaced by the input's file name without its extension
/// ("stdin" for "-").
inline std::string with_stem(std::string pattern, const std::string& input) {
    const std::string stem =
        input == "-" ? std::string("stdin") : std::filesystem::path(input).stem().string();
    for (std::size_t at; (at = pattern.find("{stem}")) != std::string::npos;) {
        pattern.replace(at, 6, stem);
    }
    return pattern;
}

/// A usage error when several inputs would write one file: `--option` needs {stem} then.
inline void check_stem(const std::string& option, const std::string& pattern, std::size_t inputs) {
    if (inputs > 1 && !pattern.empty() && pattern.find("{stem}") == std::string::npos) {
        throw InvalidArgument(
            "--" + option + ": with several inputs, name the files with {stem} (for example --" +
            option + " out/{stem}" + std::filesystem::path(pattern).extension().string() + ")");
    }
}

}  // namespace pc::tools
