#include <cstring>
#include <string>

#include <pc/core/error.h>
#include <pc/io/lzf.h>

namespace pc::io {

namespace {
constexpr std::size_t kMaxLiteral = 32;         // control byte 0..31 = run of 1..32 literals
constexpr std::size_t kMaxOffset = 1u << 13;    // 13-bit back-reference distance
constexpr std::size_t kMaxMatch = 7 + 255 + 2;  // length code 7 plus one extension byte
constexpr unsigned kHashBits = 14;

void emit_literals(const std::uint8_t* p, std::size_t n, std::vector<std::uint8_t>& out) {
    while (n > 0) {
        const std::size_t run = n < kMaxLiteral ? n : kMaxLiteral;
        out.push_back(static_cast<std::uint8_t>(run - 1));
        out.insert(out.end(), p, p + run);
        p += run;
        n -= run;
    }
}

std::uint32_t hash3(const std::uint8_t* p) {
    const std::uint32_t v = (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
    return (v * 2654435761u) >> (32 - kHashBits);
}
}  // namespace

std::vector<std::uint8_t> lzf_compress(std::span<const std::uint8_t> in) {
    std::vector<std::uint8_t> out;
    out.reserve(in.size() + in.size() / 32 + 16);
    std::vector<std::size_t> table(std::size_t{1} << kHashBits, 0);  // position + 1, 0 = empty
    const std::uint8_t* src = in.data();
    const std::size_t n = in.size();
    std::size_t ip = 0;
    std::size_t literal_start = 0;
    while (ip + 2 < n) {
        const std::uint32_t h = hash3(src + ip);
        const std::size_t ref = table[h];
        table[h] = ip + 1;
        if (ref != 0) {
            const std::size_t rp = ref - 1;
            const std::size_t distance = ip - rp;
            if (distance <= kMaxOffset && std::memcmp(src + rp, src + ip, 3) == 0) {
                const std::size_t max_len = std::min(kMaxMatch, n - ip);
                std::size_t len = 3;
                while (len < max_len && src[rp + len] == src[ip + len]) {
                    ++len;
                }
                emit_literals(src + literal_start, ip - literal_start, out);
                const std::size_t code = len - 2;
                const std::size_t off = distance - 1;
                if (code < 7) {
                    out.push_back(static_cast<std::uint8_t>((code << 5) | (off >> 8)));
                } else {
                    out.push_back(static_cast<std::uint8_t>((7u << 5) | (off >> 8)));
                    out.push_back(static_cast<std::uint8_t>(code - 7));
                }
                out.push_back(static_cast<std::uint8_t>(off & 0xff));
                ip += len;
                literal_start = ip;
                continue;
            }
        }
        ++ip;
    }
    emit_literals(src + literal_start, n - literal_start, out);
    return out;
}

void lzf_decompress(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) {
    const auto corrupt = [](const std::string& what, std::size_t at) {
        return IoError("LZF stream corrupt at byte " + std::to_string(at) + ": " + what);
    };
    std::size_t ip = 0;
    std::size_t op = 0;
    const std::size_t in_n = in.size();
    const std::size_t out_n = out.size();
    while (ip < in_n) {
        const std::size_t ctrl = in[ip++];
        if (ctrl < 32) {
            const std::size_t run = ctrl + 1;
            if (ip + run > in_n) {
                throw corrupt("literal run of " + std::to_string(run) + " B past end of input", ip);
            }
            if (op + run > out_n) {
                throw corrupt("output exceeds the declared " + std::to_string(out_n) + " B", ip);
            }
            std::memcpy(out.data() + op, in.data() + ip, run);
            ip += run;
            op += run;
            continue;
        }
        std::size_t len = ctrl >> 5;
        if (len == 7) {
            if (ip >= in_n) {
                throw corrupt("truncated length byte", ip);
            }
            len += in[ip++];
        }
        if (ip >= in_n) {
            throw corrupt("truncated offset byte", ip);
        }
        const std::size_t distance = ((ctrl & 0x1f) << 8) + in[ip++] + 1;
        len += 2;
        if (distance > op) {
            throw corrupt(
                "back-reference " + std::to_string(distance) + " B before the output start", ip);
        }
        if (op + len > out_n) {
            throw corrupt("output exceeds the declared " + std::to_string(out_n) + " B", ip);
        }
        // Overlapping copies repeat the pattern; copy byte by byte.
        std::uint8_t* dst = out.data() + op;
        const std::uint8_t* ref = dst - distance;
        for (std::size_t k = 0; k < len; ++k) {
            dst[k] = ref[k];
        }
        op += len;
    }
    if (op != out_n) {
        throw IoError("LZF stream decodes to " + std::to_string(op) + " B, header declares " +
                      std::to_string(out_n) + " B");
    }
}

}  // namespace pc::io
