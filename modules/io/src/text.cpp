#include <algorithm>
#include <cmath>
#include <cstring>

#include <pc/core/error.h>
#include <pc/io/text.h>

#include "parse_util.h"

namespace pc::io {

namespace {

using detail::quote;
using Field = pcl::PCLPointField;

bool is_comment(std::string_view tok) {
    return tok.front() == '#' || (tok.size() >= 2 && tok[0] == '/' && tok[1] == '/');
}

}  // namespace

ReadResult parse_text(std::string_view bytes) {
    ReadResult r;
    r.format = "xyz text";
    detail::LineCursor cur{bytes};
    std::string_view line;
    std::vector<double> values;
    std::size_t columns = 0;
    bool colour_is_real = false;
    bool header_allowed = true;
    while (cur.next(line)) {
        detail::Tokens toks{line, 0, ',', ';'};
        std::string_view tok;
        if (!toks.next(tok) || is_comment(tok)) {
            continue;
        }
        const std::size_t start = values.size();
        std::size_t got = 0;
        bool numeric = true;
        do {
            double v;
            if (!detail::parse_real(tok, v)) {
                numeric = false;
                break;
            }
            if (got >= 3 && (tok.find_first_of(".eE") != std::string_view::npos)) {
                colour_is_real = true;
            }
            values.push_back(v);
            ++got;
        } while (toks.next(tok));
        if (!numeric) {
            if (header_allowed && columns == 0) {  // one line of column names
                values.resize(start);
                header_allowed = false;
                continue;
            }
            throw IoError("line " + std::to_string(cur.line_number) + ": " + quote(tok) +
                          " is not a number");
        }
        header_allowed = false;
        if (columns == 0) {
            if (got != 3 && got != 4 && got != 6) {
                throw IoError("line " + std::to_string(cur.line_number) +
                              ": expected 3 (x y z), 4 (x y z intensity) or 6 (x y z r g b) "
                              "values, found " +
                              std::to_string(got));
            }
            columns = got;
        } else if (got != columns) {
            throw IoError("line " + std::to_string(cur.line_number) + ": expected " +
                          std::to_string(columns) + " values, found " + std::to_string(got));
        }
    }
    if (columns == 0) {
        throw IoError("text input has no data rows");
    }
    const std::size_t n = values.size() / columns;
    if (n > 0xffffffffu) {
        throw IoError("text input has more than 4294967295 rows");
    }
    Blob& blob = r.blob;
    std::size_t step = 0;
    const auto add = [&](const char* name, std::uint8_t type) {
        Field f;
        f.name = name;
        f.offset = static_cast<std::uint32_t>(step);
        f.datatype = type;
        f.count = 1;
        blob.cloud.fields.push_back(f);
        step += type_size(type);
    };
    add("x", Field::FLOAT32);
    add("y", Field::FLOAT32);
    add("z", Field::FLOAT32);
    if (columns == 4) {
        add("intensity", Field::FLOAT32);
    } else if (columns == 6) {
        add("rgb", Field::UINT32);
    }
    blob.cloud.point_step = static_cast<std::uint32_t>(step);
    blob.cloud.width = static_cast<std::uint32_t>(n);
    blob.cloud.height = 1;
    blob.cloud.row_step = static_cast<std::uint32_t>(n * step);
    reserve_points(blob, n);
    blob.cloud.data.assign(n * step, 0);
    for (std::size_t i = 0; i < n; ++i) {
        const double* row = values.data() + i * columns;
        std::uint8_t* dst = blob.cloud.data.data() + i * step;
        const std::size_t reals = columns == 6 ? 3 : columns;  // x y z (+ intensity)
        for (std::size_t c = 0; c < reals; ++c) {
            const auto f = static_cast<float>(row[c]);
            std::memcpy(dst + 4 * c, &f, 4);
        }
        if (columns == 6) {
            std::uint32_t word = 0;
            for (int c = 0; c < 3; ++c) {
                const double v = colour_is_real ? row[3 + c] * 255.0 : row[3 + c];
                if (!(v >= -0.5 && v < 255.5) || (!colour_is_real && v != std::floor(v))) {
                    throw IoError(
                        "row " + std::to_string(i + 1) + ": colour value " +
                        format_number(row[3 + c]) +
                        (colour_is_real ? " is outside 0..1" : " is not an integer 0..255"));
                }
                word |= static_cast<std::uint32_t>(std::lround(v)) << (8 * (2 - c));
            }
            std::memcpy(dst + 12, &word, 4);
        }
    }
    update_is_dense(blob);
    return r;
}

}  // namespace pc::io
