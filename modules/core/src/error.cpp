#include <charconv>

#include <pc/core/error.h>

namespace pc {

std::string format_number(double value) {
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, value);
    return std::string(buf, res.ptr);
}

}  // namespace pc
