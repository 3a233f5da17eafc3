#include <algorithm>
#include <cctype>
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

std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return out;
}

/// The column names of a header line ("//X,Y,Z,R,G,B,Nx,Ny,Nz", "x y z intensity"): split on
/// commas if it has any, else on semicolons, else on blanks; a leading `//` or `#` dropped.
std::vector<std::string> header_names(std::string_view line) {
    while (!line.empty() &&
           (detail::is_blank(line.front()) || line.front() == '/' || line.front() == '#')) {
        line.remove_prefix(1);
    }
    const char sep = line.find(',') != std::string_view::npos   ? ','
                     : line.find(';') != std::string_view::npos ? ';'
                                                                : ' ';
    std::vector<std::string> names;
    std::size_t start = 0;
    while (start <= line.size()) {
        std::size_t end = sep == ' ' ? line.find_first_of(" \t", start) : line.find(sep, start);
        end = end == std::string_view::npos ? line.size() : end;
        std::string_view tok = line.substr(start, end - start);
        while (!tok.empty() && detail::is_blank(tok.front())) {
            tok.remove_prefix(1);
        }
        while (!tok.empty() && detail::is_blank(tok.back())) {
            tok.remove_suffix(1);
        }
        if (!tok.empty() || sep != ' ') {
            names.emplace_back(tok);
        }
        start = end + 1;
    }
    return names;
}

/// What a column is: an axis, a colour channel, a normal, or a field of its own.
enum class Role { kX, kY, kZ, kRed, kGreen, kBlue, kField };

struct Column {
    Role role = Role::kField;
    std::string name;   // the field's name (kField, normals), sanitised
    bool infer = true;  // a named column of whole numbers becomes U 4 / I 4 (labels, classes)
    bool has_fraction = false;
    bool integral = true;
    double lo = INFINITY, hi = -INFINITY;
};

/// The columns named by `names` (case-insensitive: x y z; r g b or red green blue; nx ny nz or
/// normal_x ...; anything else a field of that name), or empty when the names do not include
/// x, y and z (then the line was not a header).
std::vector<Column> named_columns(const std::vector<std::string>& names) {
    std::vector<Column> cols;
    bool x = false, y = false, z = false;
    for (const std::string& raw : names) {
        const std::string n = lower(raw);
        Column c;
        if (n == "x") {
            c.role = Role::kX;
            x = true;
        } else if (n == "y") {
            c.role = Role::kY;
            y = true;
        } else if (n == "z") {
            c.role = Role::kZ;
            z = true;
        } else if (n == "r" || n == "red") {
            c.role = Role::kRed;
        } else if (n == "g" || n == "green") {
            c.role = Role::kGreen;
        } else if (n == "b" || n == "blue") {
            c.role = Role::kBlue;
        } else if (n == "nx" || n == "ny" || n == "nz") {
            c.name = std::string("normal_") + n[1];
            c.infer = false;  // unit vectors, whatever a small file happens to hold
        } else {
            for (char ch : n) {
                c.name += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
            }
            if (c.name.empty() || std::isdigit(static_cast<unsigned char>(c.name[0]))) {
                c.name = "f_" + c.name;
            }
        }
        cols.push_back(c);
    }
    if (!(x && y && z)) {
        return {};
    }
    return cols;
}

/// The columns of a file without a header, by their number.
std::vector<Column> default_columns(std::size_t count, std::size_t line) {
    std::vector<Column> cols(count);
    if (count != 3 && count != 4 && count != 6 && count != 9) {
        throw IoError("line " + std::to_string(line) +
                      ": expected 3 (x y z), 4 (x y z intensity), 6 (x y z r g b) or 9 (x y z r g "
                      "b nx ny nz) values, found " +
                      std::to_string(count) +
                      "; for other columns, name them in a first line (x "
                      "y z ...)");
    }
    const Role roles[] = {Role::kX, Role::kY, Role::kZ, Role::kRed, Role::kGreen, Role::kBlue};
    for (std::size_t c = 0; c < count; ++c) {
        cols[c].infer = false;  // unnamed: F 4, as every reader of such files does
        if (count == 4 && c == 3) {
            cols[c].name = "intensity";
        } else if (c < 6) {
            cols[c].role = roles[c];
        } else {
            cols[c].name = std::string("normal_") + "xyz"[c - 6];
        }
    }
    return cols;
}

}  // namespace

ReadResult parse_text(std::string_view bytes) {
    ReadResult r;
    r.format = "xyz text";
    detail::LineCursor cur{bytes};
    std::string_view line, header;
    std::vector<double> values;
    std::vector<Column> cols;
    // per column: a value written with '.', 'e' or 'E' (this row's, then all data rows')
    std::vector<std::uint8_t> row_fraction, fraction;
    bool header_allowed = true;
    while (cur.next(line)) {
        detail::Tokens toks{line, 0, ',', ';'};
        std::string_view tok;
        if (!toks.next(tok)) {
            continue;
        }
        if (is_comment(tok)) {
            if (cols.empty() && header.empty()) {
                header = line;  // CloudCompare writes its column names as "//X,Y,Z,..."
            }
            continue;
        }
        const std::size_t start = values.size();
        row_fraction.clear();
        std::size_t got = 0;
        bool numeric = true;
        do {
            double v;
            if (!detail::parse_real(tok, v)) {
                numeric = false;
                break;
            }
            row_fraction.push_back(tok.find_first_of(".eE") != std::string_view::npos);
            values.push_back(v);
            ++got;
        } while (toks.next(tok));
        if (!numeric) {
            if (header_allowed && cols.empty()) {  // one line of column names
                values.resize(start);
                header_allowed = false;
                header = line;
                continue;
            }
            throw IoError("line " + std::to_string(cur.line_number) + ": " + quote(tok) +
                          " is not a number");
        }
        header_allowed = false;
        fraction.resize(std::max(fraction.size(), row_fraction.size()), 0);
        for (std::size_t c = 0; c < row_fraction.size(); ++c) {
            fraction[c] |= row_fraction[c];
        }
        if (cols.empty()) {
            const auto names = header.empty() ? std::vector<std::string>{} : header_names(header);
            if (names.size() == got) {
                cols = named_columns(names);
            }
            if (cols.empty()) {
                cols = default_columns(got, cur.line_number);
            }
        } else if (got != cols.size()) {
            throw IoError("line " + std::to_string(cur.line_number) + ": expected " +
                          std::to_string(cols.size()) + " values, found " + std::to_string(got));
        }
    }
    if (cols.empty()) {
        throw IoError("text input has no data rows");
    }
    const std::size_t columns = cols.size();
    const std::size_t n = values.size() / columns;
    if (n > 0xffffffffu) {
        throw IoError("text input has more than 4294967295 rows");
    }
    for (std::size_t c = 0; c < columns; ++c) {  // what the column's values say of its type
        cols[c].has_fraction = fraction[c] != 0;
        for (std::size_t i = c; i < values.size(); i += columns) {
            cols[c].integral = cols[c].integral && values[i] == std::floor(values[i]);
            cols[c].lo = std::min(cols[c].lo, values[i]);
            cols[c].hi = std::max(cols[c].hi, values[i]);
        }
    }
    int colour_channels = 0;
    for (const Column& c : cols) {
        colour_channels += c.role == Role::kRed || c.role == Role::kGreen || c.role == Role::kBlue;
    }
    if (colour_channels != 0 && colour_channels != 3) {
        throw IoError("text columns name " + std::to_string(colour_channels) +
                      " colour channels; r g b (or red green blue) go together");
    }
    // A colour is 0..1 reals when any channel is written with a fraction, else 0..255 integers.
    bool colour_is_real = false;
    for (const Column& c : cols) {
        const bool channel =
            c.role == Role::kRed || c.role == Role::kGreen || c.role == Role::kBlue;
        colour_is_real = colour_is_real || (channel && c.has_fraction);
    }

    Blob& blob = r.blob;
    std::size_t step = 0;
    const auto add = [&](const std::string& name, std::uint8_t type) {
        for (const Field& f : blob.cloud.fields) {
            if (f.name == name) {
                throw IoError("text columns name field " + quote(name) + " twice");
            }
        }
        Field f;
        f.name = name;
        f.offset = static_cast<std::uint32_t>(step);
        f.datatype = type;
        f.count = 1;
        blob.cloud.fields.push_back(f);
        step += type_size(type);
        return f.offset;
    };
    std::vector<std::uint32_t> offset(columns, 0);
    std::vector<std::uint8_t> type(columns, Field::FLOAT32);
    for (Role axis : {Role::kX, Role::kY, Role::kZ}) {
        const auto it = std::find_if(cols.begin(), cols.end(),
                                     [axis](const Column& c) { return c.role == axis; });
        const auto c = static_cast<std::size_t>(it - cols.begin());
        if (std::count_if(cols.begin(), cols.end(),
                          [axis](const Column& k) { return k.role == axis; }) != 1) {
            throw IoError("text columns name an axis twice");
        }
        offset[c] = add(std::string(1, "xyz"[static_cast<int>(axis)]), Field::FLOAT32);
    }
    const std::uint32_t rgb_offset = colour_channels ? add("rgb", Field::UINT32) : 0;
    for (std::size_t c = 0; c < columns; ++c) {
        if (cols[c].role != Role::kField) {
            continue;
        }
        // Whole numbers stay whole (labels, classes, counts): U 4 or I 4 when they fit.
        const Column& k = cols[c];
        const bool whole = k.infer && k.integral && !k.has_fraction && n > 0;
        type[c] = whole && k.lo >= 0 && k.hi <= 4294967295.0               ? Field::UINT32
                  : whole && k.lo >= -2147483648.0 && k.hi <= 2147483647.0 ? Field::INT32
                                                                           : Field::FLOAT32;
        offset[c] = add(k.name, type[c]);
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
        std::uint32_t word = 0;
        for (std::size_t c = 0; c < columns; ++c) {
            const Role role = cols[c].role;
            if (role == Role::kRed || role == Role::kGreen || role == Role::kBlue) {
                const double v = colour_is_real ? row[c] * 255.0 : row[c];
                if (!(v >= -0.5 && v < 255.5) || (!colour_is_real && v != std::floor(v))) {
                    throw IoError(
                        "row " + std::to_string(i + 1) + ": colour value " + format_number(row[c]) +
                        (colour_is_real ? " is outside 0..1" : " is not an integer 0..255"));
                }
                const int shift = 8 * (2 - (static_cast<int>(role) - static_cast<int>(Role::kRed)));
                word |= static_cast<std::uint32_t>(std::lround(v)) << shift;
            } else if (type[c] == Field::UINT32) {
                const auto u = static_cast<std::uint32_t>(row[c]);
                std::memcpy(dst + offset[c], &u, 4);
            } else if (type[c] == Field::INT32) {
                const auto s = static_cast<std::int32_t>(row[c]);
                std::memcpy(dst + offset[c], &s, 4);
            } else {
                const auto f = static_cast<float>(row[c]);
                std::memcpy(dst + offset[c], &f, 4);
            }
        }
        if (colour_channels) {
            std::memcpy(dst + rgb_offset, &word, 4);
        }
    }
    update_is_dense(blob);
    return r;
}

void write_text(const Blob& blob, ByteSink& sink) {
    check_layout(blob);
    std::string buf = "//";
    std::vector<const Field*> fields;
    for (const Field& f : blob.cloud.fields) {
        if (f.name == "_") {
            continue;
        }
        fields.push_back(&f);
        const bool packed =
            (f.name == "rgb" || f.name == "rgba") && type_size(f.datatype) == 4 && f.count == 1;
        // CloudCompare's own names for the columns it recognises.
        std::string name = f.name;
        if (f.name == "x" || f.name == "y" || f.name == "z") {
            name = std::string(1, static_cast<char>(std::toupper(f.name[0])));
        } else if (packed) {
            name = "R G B";
        } else if (f.name == "normal_x" || f.name == "normal_y" || f.name == "normal_z") {
            name = std::string("N");
            name += f.name.back();
        }
        for (std::uint32_t c = 0; c < f.count; ++c) {
            if (buf.size() > 2) {
                buf += ' ';
            }
            buf += name;
            if (f.count > 1) {
                buf += '_';
                buf += std::to_string(c);
            }
        }
    }
    buf += '\n';
    const std::size_t n = blob.size();
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* p = blob.cloud.data.data() + i * blob.cloud.point_step;
        bool first = true;
        for (const Field* f : fields) {
            const std::size_t es = type_size(f->datatype);
            if ((f->name == "rgb" || f->name == "rgba") && es == 4 && f->count == 1) {
                std::uint32_t word;
                std::memcpy(&word, p + f->offset, 4);
                for (int shift : {16, 8, 0}) {
                    buf += first ? "" : " ";
                    first = false;
                    buf += std::to_string((word >> shift) & 0xffu);
                }
                continue;
            }
            for (std::uint32_t c = 0; c < f->count; ++c) {
                buf += first ? "" : " ";
                first = false;
                detail::format_value(p + f->offset + c * es, f->datatype, buf);
            }
        }
        buf += '\n';
        if (buf.size() > (1 << 20) - 4096) {
            sink.write(buf);
            buf.clear();
        }
    }
    sink.write(buf);
}

}  // namespace pc::io
