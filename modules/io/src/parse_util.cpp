#include "parse_util.h"

#include <cmath>

#include <pcl/PCLPointField.h>

namespace pc::io::detail {

namespace {
using Field = pcl::PCLPointField;

template <class T>
bool store_int(std::string_view tok, std::uint8_t* dst) {
    T v;
    if constexpr (std::is_signed_v<T>) {
        std::int64_t w;
        if (!parse_i64(tok, w) || w < std::numeric_limits<T>::min() ||
            w > std::numeric_limits<T>::max()) {
            return false;
        }
        v = static_cast<T>(w);
    } else {
        std::uint64_t w;
        if (!tok.empty() && tok.front() == '+') {
            tok.remove_prefix(1);
        }
        if (!parse_u64(tok, w) || w > std::numeric_limits<T>::max()) {
            return false;
        }
        v = static_cast<T>(w);
    }
    std::memcpy(dst, &v, sizeof v);
    return true;
}

template <class T>
bool store_real(std::string_view tok, std::uint8_t* dst) {
    T v;
    if (!parse_real(tok, v)) {
        return false;
    }
    std::memcpy(dst, &v, sizeof v);
    return true;
}

template <class T>
void append_int(const std::uint8_t* src, std::string& out) {
    T v;
    std::memcpy(&v, src, sizeof v);
    char buf[32];
    const auto r = std::to_chars(buf, buf + sizeof buf, v);
    out.append(buf, r.ptr);
}

template <class T>
void append_real(const std::uint8_t* src, std::string& out) {
    T v;
    std::memcpy(&v, src, sizeof v);
    if (std::isnan(v)) {
        out += "nan";
    } else if (std::isinf(v)) {
        out += v > 0 ? "inf" : "-inf";
    } else {
        char buf[64];
        const auto r = std::to_chars(buf, buf + sizeof buf, v);
        out.append(buf, r.ptr);
    }
}
}  // namespace

bool parse_value(std::string_view tok, std::uint8_t datatype, std::uint8_t* dst) {
    switch (datatype) {
        case Field::INT8:
            return store_int<std::int8_t>(tok, dst);
        case Field::UINT8:
            return store_int<std::uint8_t>(tok, dst);
        case Field::INT16:
            return store_int<std::int16_t>(tok, dst);
        case Field::UINT16:
            return store_int<std::uint16_t>(tok, dst);
        case Field::INT32:
            return store_int<std::int32_t>(tok, dst);
        case Field::UINT32:
            return store_int<std::uint32_t>(tok, dst);
        case Field::INT64:
            return store_int<std::int64_t>(tok, dst);
        case Field::UINT64:
            return store_int<std::uint64_t>(tok, dst);
        case Field::FLOAT32:
            return store_real<float>(tok, dst);
        case Field::FLOAT64:
            return store_real<double>(tok, dst);
        default:
            return false;
    }
}

void format_value(const std::uint8_t* src, std::uint8_t datatype, std::string& out) {
    switch (datatype) {
        case Field::INT8:
            append_int<std::int8_t>(src, out);
            break;
        case Field::UINT8:
            append_int<std::uint8_t>(src, out);
            break;
        case Field::INT16:
            append_int<std::int16_t>(src, out);
            break;
        case Field::UINT16:
            append_int<std::uint16_t>(src, out);
            break;
        case Field::INT32:
            append_int<std::int32_t>(src, out);
            break;
        case Field::UINT32:
            append_int<std::uint32_t>(src, out);
            break;
        case Field::INT64:
            append_int<std::int64_t>(src, out);
            break;
        case Field::UINT64:
            append_int<std::uint64_t>(src, out);
            break;
        case Field::FLOAT32:
            append_real<float>(src, out);
            break;
        case Field::FLOAT64:
            append_real<double>(src, out);
            break;
        default:
            out += "?";
            break;
    }
}

}  // namespace pc::io::detail
