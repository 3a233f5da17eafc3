#include <cmath>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include <pc/core/error.h>
#include <pc/evaluation/truth.h>

namespace pc::evaluation {

namespace {

/// A whole number >= 0 and <= `max` (nlohmann's get<unsigned>() wraps -1 and truncates 2.5).
std::uint64_t whole(const nlohmann::json& v, const std::string& what, std::uint64_t max) {
    if (!v.is_number_unsigned() || v.get<std::uint64_t>() > max) {
        throw IoError(what + " must be a whole number from 0 to " + std::to_string(max) + ", got " +
                      v.dump());
    }
    return v.get<std::uint64_t>();
}

}  // namespace

Truth parse_truth(std::string_view json_text) {
    Truth t;
    try {
        const auto j = nlohmann::json::parse(json_text);
        const auto& fruits = j.at("fruits");
        if (!fruits.is_array()) {
            throw IoError("\"fruits\" must be an array");
        }
        for (std::size_t k = 0; k < fruits.size(); ++k) {
            const auto& x = fruits[k];
            TruthFruit fr;
            fr.id = static_cast<std::uint32_t>(
                whole(x.at("id"), "fruit " + std::to_string(k) + ": id", 0xffffffffu));
            fr.centre = x.at("centre").get<std::array<double, 3>>();
            fr.radius = x.at("radius").get<double>();
            if (fr.id == 0 || !(fr.radius > 0) || !std::isfinite(fr.radius) ||
                !std::isfinite(fr.centre[0] + fr.centre[1] + fr.centre[2])) {
                throw IoError("fruit " + std::to_string(k) +
                              ": ids must be > 0, radii > 0 and centres finite");
            }
            t.fruits.push_back(fr);
        }
        t.fruit_count = j.contains("fruit_count")
                            ? whole(j.at("fruit_count"), "fruit_count", std::uint64_t{1} << 32)
                            : t.fruits.size();
    } catch (const nlohmann::json::exception& e) {
        // "[json.exception.out_of_range.403] key 'fruits' not found" -> "key 'fruits' not found"
        std::string what = e.what();
        const std::size_t bracket = what.find("] ");
        if (what.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos) {
            what.erase(0, bracket + 2);
        }
        throw IoError(
            "not a ground-truth file: " + what +
            R"( (expected {"fruits": [{"id": 1, "centre": [x, y, z], "radius": r}, ...]})" +
            R"(, optionally "fruit_count": N}))");
    }
    return t;
}

}  // namespace pc::evaluation
