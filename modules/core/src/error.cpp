#include <charconv>
#include <cmath>

#include <pc/core/error.h>

namespace pc {

std::string format_number(double value) {
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, value);
    return std::string(buf, res.ptr);
}

std::string format_rounded(double value, int digits) {
    if (std::abs(value) >= std::pow(10.0, digits)) {  // 1234.5 -> "1235", not "1.23e+03"
        return format_number(std::round(value));
    }
    char buf[64];
    const auto res =
        std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, digits);
    return std::string(buf, res.ptr);
}

std::string csv_cell(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) {
        return text;
    }
    std::string q = "\"";
    for (char c : text) {
        q += c;
        if (c == '"') {
            q += '"';
        }
    }
    return q + "\"";
}

}  // namespace pc
