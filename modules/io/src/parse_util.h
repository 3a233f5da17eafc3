#pragma once
// Internal helpers shared by the PCD, PLY and text parsers. Not installed.

#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>

#include <pc/core/error.h>

namespace pc::io::detail {

/// One line of a buffer, without its '\n' and a trailing '\r'. `next` is where the next line
/// starts.
struct LineCursor {
    std::string_view bytes;
    std::size_t pos = 0;
    std::size_t line_number = 0;  // 1-based number of the line last returned

    bool next(std::string_view& line) {
        if (pos >= bytes.size()) {
            return false;
        }
        const std::size_t nl = bytes.find('\n', pos);
        const std::size_t end = nl == std::string_view::npos ? bytes.size() : nl;
        line = bytes.substr(pos, end - pos);
        if (!line.empty() && line.back() == '\r') {
            line.remove_suffix(1);
        }
        pos = nl == std::string_view::npos ? bytes.size() : nl + 1;
        ++line_number;
        return true;
    }
};

inline bool is_blank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

/// Splits on blanks (and on `extra` separators) without allocating: call next() until false.
struct Tokens {
    std::string_view s;
    std::size_t pos = 0;
    char extra1 = ' ';
    char extra2 = ' ';

    bool sep(char c) const { return is_blank(c) || c == extra1 || c == extra2; }
    bool next(std::string_view& tok) {
        while (pos < s.size() && sep(s[pos])) {
            ++pos;
        }
        if (pos >= s.size()) {
            return false;
        }
        const std::size_t start = pos;
        while (pos < s.size() && !sep(s[pos])) {
            ++pos;
        }
        tok = s.substr(start, pos - start);
        return true;
    }
};

/// `tok` quoted and shortened for messages, with non-printable bytes escaped.
inline std::string quote(std::string_view tok, std::size_t max_len = 24) {
    std::string out = "'";
    for (std::size_t i = 0; i < tok.size() && i < max_len; ++i) {
        const auto c = static_cast<unsigned char>(tok[i]);
        if (c >= 32 && c < 127) {
            out += static_cast<char>(c);
        } else {
            static const char* hex = "0123456789abcdef";
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
    if (tok.size() > max_len) {
        out += "...";
    }
    return out + "'";
}

/// A non-negative decimal integer (digits only), or false.
inline bool parse_u64(std::string_view tok, std::uint64_t& v) {
    if (tok.empty() || tok.front() < '0' || tok.front() > '9') {
        return false;
    }
    const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    return r.ec == std::errc{} && r.ptr == tok.data() + tok.size();
}

/// A signed integer (std::int64_t) or a real (float, double; nan, inf, infinity in any case) in the
/// C locale, with an optional leading '+'. The whole token must be consumed.
template <class T>
bool parse_signed(std::string_view tok, T& v) {
    if (!tok.empty() && tok.front() == '+') {
        tok.remove_prefix(1);
    }
    if (tok.empty()) {
        return false;
    }
    const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    return r.ec == std::errc{} && r.ptr == tok.data() + tok.size();
}

template <class T>
bool parse_real(std::string_view tok, T& v) {
    return parse_signed(tok, v);
}

inline bool parse_i64(std::string_view tok, std::int64_t& v) { return parse_signed(tok, v); }

/// Longest header (PCD up to DATA, PLY up to end_header) the readers accept.
inline constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

/// a * b, throwing pc::IoError naming `what` if it overflows 64 bits.
inline std::uint64_t checked_mul(std::uint64_t a, std::uint64_t b, const char* what) {
    std::uint64_t r;
    if (__builtin_mul_overflow(a, b, &r)) {
        throw IoError(std::string(what) + " overflows 64 bits: " + std::to_string(a) + " x " +
                      std::to_string(b));
    }
    return r;
}

/// Parses `tok` as a value of PCLPointField `datatype` and stores it at `dst`. False if the token
/// is not a number or does not fit the type.
bool parse_value(std::string_view tok, std::uint8_t datatype, std::uint8_t* dst);

/// Appends the text of the value of `datatype` at `src`: shortest round-trip form for reals,
/// "nan", "inf", "-inf" for non-finite ones.
void format_value(const std::uint8_t* src, std::uint8_t datatype, std::string& out);

}  // namespace pc::io::detail
