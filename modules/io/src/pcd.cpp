#include <algorithm>
#include <cstring>
#include <limits>
#include <optional>
#include <set>

#include <pc/core/error.h>
#include <pc/io/lzf.h>
#include <pc/io/pcd.h>

#include "parse_util.h"

namespace pc::io {

namespace {

using detail::checked_mul;
using detail::quote;
using Field = pcl::PCLPointField;

using detail::kMaxHeaderBytes;
constexpr std::uint64_t kMaxCount = std::uint64_t{1} << 24;  // elements in one field of one point
constexpr std::uint64_t kMaxPointStep = std::uint64_t{1} << 30;

enum class DataKind { kAscii, kBinary, kCompressed };

struct Header {
    std::vector<std::string> names;
    std::vector<std::uint64_t> sizes;
    std::vector<char> types;
    std::vector<std::uint64_t> counts;
    std::optional<std::uint64_t> width, height, points;
    std::array<float, 7> viewpoint{0, 0, 0, 1, 0, 0, 0};
    DataKind data = DataKind::kAscii;
    std::size_t body_offset = 0;
    std::size_t data_line = 0;
    bool has_version = false;
};

[[noreturn]] void fail_line(std::size_t line, const std::string& what) {
    throw IoError("header line " + std::to_string(line) + ": " + what);
}

std::uint64_t header_uint(std::string_view tok, std::size_t line, const char* key) {
    std::uint64_t v;
    if (!detail::parse_u64(tok, v)) {
        fail_line(line, std::string(key) + " must be a non-negative integer, got " + quote(tok));
    }
    return v;
}

Header parse_header(std::string_view bytes) {
    Header h;
    detail::LineCursor cur{bytes};
    std::set<std::string, std::less<>> seen;
    std::string_view line;
    while (true) {
        if (cur.pos > kMaxHeaderBytes) {
            throw IoError("PCD header is longer than " + std::to_string(kMaxHeaderBytes) +
                          " B without a DATA line");
        }
        if (!cur.next(line)) {
            throw IoError("PCD header has no DATA line (" + std::to_string(cur.line_number) +
                          " lines read)");
        }
        detail::Tokens toks{line};
        std::string_view key;
        if (!toks.next(key) || key.front() == '#') {
            continue;
        }
        const std::size_t ln = cur.line_number;
        std::vector<std::string_view> vals;
        for (std::string_view t; toks.next(t);) {
            vals.push_back(t);
        }
        const std::string k(key);
        if (k != "VERSION" && !seen.insert(k == "COLUMNS" ? "FIELDS" : k).second) {
            fail_line(ln, k + " appears twice");
        }
        const auto one = [&](const char* name) {
            if (vals.size() != 1) {
                fail_line(ln, std::string(name) + " must have 1 value, got " +
                                  std::to_string(vals.size()));
            }
            return header_uint(vals[0], ln, name);
        };
        if (k == "VERSION") {
            h.has_version = true;
        } else if (k == "FIELDS" || k == "COLUMNS") {
            if (vals.empty()) {
                fail_line(ln, "FIELDS names no field");
            }
            for (auto v : vals) {
                h.names.emplace_back(v);
            }
        } else if (k == "SIZE" || k == "COUNT") {
            auto& dst = k == "SIZE" ? h.sizes : h.counts;
            for (auto v : vals) {
                dst.push_back(header_uint(v, ln, k.c_str()));
            }
        } else if (k == "TYPE") {
            for (auto v : vals) {
                if (v.size() != 1 || (v[0] != 'I' && v[0] != 'U' && v[0] != 'F')) {
                    fail_line(ln, "TYPE must be I, U or F, got " + quote(v));
                }
                h.types.push_back(v[0]);
            }
        } else if (k == "WIDTH") {
            h.width = one("WIDTH");
        } else if (k == "HEIGHT") {
            h.height = one("HEIGHT");
        } else if (k == "POINTS") {
            h.points = one("POINTS");
        } else if (k == "VIEWPOINT") {
            if (vals.size() != 7) {
                fail_line(ln, "VIEWPOINT must have 7 values, got " + std::to_string(vals.size()));
            }
            for (std::size_t i = 0; i < 7; ++i) {
                if (!detail::parse_real(vals[i], h.viewpoint[i])) {
                    fail_line(ln, "VIEWPOINT value " + quote(vals[i]) + " is not a number");
                }
            }
        } else if (k == "DATA") {
            const std::string_view kind = vals.size() == 1 ? vals[0] : std::string_view{};
            if (kind == "ascii") {
                h.data = DataKind::kAscii;
            } else if (kind == "binary") {
                h.data = DataKind::kBinary;
            } else if (kind == "binary_compressed") {
                h.data = DataKind::kCompressed;
            } else {
                fail_line(ln, "DATA must be ascii, binary or binary_compressed, got " +
                                  quote(line.substr(std::min<std::size_t>(line.size(), 5))));
            }
            h.body_offset = cur.pos;
            h.data_line = ln;
            return h;
        } else {
            fail_line(ln, "unknown PCD keyword " + quote(key));
        }
    }
}

/// Validated layout: fields with offsets, the point count, and the sizes the body must have.
struct Layout {
    std::vector<Field> fields;
    std::uint64_t point_step = 0;
    std::uint64_t width = 0, height = 0, n = 0;
    std::uint64_t values_per_row = 0;  // ASCII tokens per point
    std::uint64_t packed_step = 0;     // bytes per point without `_` (binary_compressed)
};

Layout validate(const Header& h, std::vector<std::string>& notes) {
    Layout l;
    if (h.names.empty()) {
        throw IoError("PCD header has no FIELDS line");
    }
    const std::size_t nf = h.names.size();
    const auto arity = [&](const char* key, std::size_t got) {
        if (got != nf) {
            throw IoError(std::string("PCD header: ") + key + " has " + std::to_string(got) +
                          " values but FIELDS names " + std::to_string(nf));
        }
    };
    if (h.sizes.empty()) {
        throw IoError("PCD header has no SIZE line");
    }
    if (h.types.empty()) {
        throw IoError("PCD header has no TYPE line");
    }
    arity("SIZE", h.sizes.size());
    arity("TYPE", h.types.size());
    if (!h.counts.empty()) {
        arity("COUNT", h.counts.size());
    }
    std::set<std::string_view> names;
    for (std::size_t i = 0; i < nf; ++i) {
        const std::string& name = h.names[i];
        const std::uint64_t count = h.counts.empty() ? 1 : h.counts[i];
        const std::uint8_t dt =
            h.sizes[i] > 8 ? 0 : datatype_of(h.types[i], static_cast<std::size_t>(h.sizes[i]));
        if (dt == 0) {
            throw IoError("PCD header: field '" + name + "' has TYPE " + h.types[i] +
                          " with SIZE " + std::to_string(h.sizes[i]) +
                          " (valid: I/U 1,2,4,8; F 4,8)");
        }
        if (count < 1 || count > kMaxCount) {
            throw IoError("PCD header: COUNT of field '" + name + "' must be 1.." +
                          std::to_string(kMaxCount) + ", got " + std::to_string(count));
        }
        if (name != "_" && !names.insert(name).second) {
            throw IoError("PCD header: field name '" + name + "' appears twice");
        }
        Field f;
        f.name = name;
        f.offset = static_cast<std::uint32_t>(l.point_step);
        f.datatype = dt;
        f.count = static_cast<std::uint32_t>(count);
        l.fields.push_back(f);
        l.point_step += h.sizes[i] * count;
        l.values_per_row += count;
        if (name != "_") {
            l.packed_step += h.sizes[i] * count;
        }
        if (l.point_step > kMaxPointStep) {
            throw IoError("PCD header: point size exceeds " + std::to_string(kMaxPointStep) + " B");
        }
    }
    // WIDTH x HEIGHT must equal POINTS, in 64-bit arithmetic (PCL checks it in 32 bits and wraps).
    l.height = h.height.value_or(1);
    if (h.width) {
        l.width = *h.width;
    } else if (h.points) {
        if (l.height == 0 || *h.points % l.height != 0) {
            throw IoError("PCD header: no WIDTH, and POINTS " + std::to_string(*h.points) +
                          " is not a multiple of HEIGHT " + std::to_string(l.height));
        }
        l.width = *h.points / l.height;
        notes.push_back("PCD header has no WIDTH; taken from POINTS");
    } else {
        throw IoError("PCD header has neither WIDTH nor POINTS");
    }
    if (!h.height) {
        notes.push_back("PCD header has no HEIGHT; taken as 1");
    }
    const std::uint64_t kU32 = 0xffffffffu;
    if (l.width > kU32 || l.height > kU32) {
        throw IoError("PCD header: WIDTH " + std::to_string(l.width) + " or HEIGHT " +
                      std::to_string(l.height) + " exceeds 4294967295");
    }
    l.n = l.width * l.height;
    if (h.points && *h.points != l.n) {
        throw IoError("PCD header: WIDTH x HEIGHT = " + std::to_string(l.width) + " x " +
                      std::to_string(l.height) + " = " + std::to_string(l.n) + " but POINTS is " +
                      std::to_string(*h.points));
    }
    if (l.n > 0 && l.height == 0) {
        throw IoError("PCD header: HEIGHT must be >= 1 for a non-empty cloud");
    }
    if (!h.has_version) {
        notes.push_back("PCD header has no VERSION line");
    }
    return l;
}

void read_ascii(std::string_view bytes, const Header& h, const Layout& l, Blob& blob) {
    const std::uint64_t available = bytes.size() - h.body_offset;
    // Each value needs at least one character and one separator: bound N before allocating.
    const std::uint64_t min_bytes =
        checked_mul(checked_mul(l.n, l.values_per_row, "ASCII body"), 2, "ASCII body");
    if (l.n > 0 && min_bytes > available + 1) {
        throw IoError("truncated ascii body: header declares " + std::to_string(l.n) +
                      " points x " + std::to_string(l.values_per_row) + " values, only " +
                      std::to_string(available) + " B present");
    }
    auto& data = blob.cloud.data;
    reserve_points(blob, l.n);
    data.assign(l.n * l.point_step, 0);
    detail::LineCursor cur{bytes, h.body_offset, h.data_line};
    std::uint64_t row = 0;
    std::string_view line;
    while (cur.next(line)) {
        detail::Tokens toks{line};
        std::string_view tok;
        if (!toks.next(tok) || tok.front() == '#') {
            continue;
        }
        if (row == l.n) {
            throw IoError("line " + std::to_string(cur.line_number) + ": extra row after the " +
                          std::to_string(l.n) + " points the header declares");
        }
        std::uint8_t* dst = data.data() + row * l.point_step;
        std::uint64_t got = 0;
        bool more = true;
        for (const Field& f : l.fields) {
            const std::size_t es = type_size(f.datatype);
            for (std::uint32_t c = 0; c < f.count; ++c) {
                if (!more) {
                    break;
                }
                ++got;
                if (!detail::parse_value(tok, f.datatype, dst + f.offset + c * es)) {
                    throw IoError("line " + std::to_string(cur.line_number) + ": " + quote(tok) +
                                  " is not a valid " + type_letter(f.datatype) +
                                  std::to_string(es) + " value for field '" + f.name + "'");
                }
                more = toks.next(tok);
            }
        }
        while (more) {
            ++got;
            more = toks.next(tok);
        }
        if (got != l.values_per_row) {
            throw IoError("line " + std::to_string(cur.line_number) + ": expected " +
                          std::to_string(l.values_per_row) + " values, found " +
                          std::to_string(got));
        }
        ++row;
    }
    if (row != l.n) {
        throw IoError("truncated ascii body: header declares " + std::to_string(l.n) + " points, " +
                      std::to_string(row) + " rows present");
    }
}

void read_binary(std::string_view bytes,
                 const Header& h,
                 const Layout& l,
                 Blob& blob,
                 std::vector<std::string>& notes) {
    const std::uint64_t available = bytes.size() - h.body_offset;
    const std::uint64_t need = checked_mul(l.n, l.point_step, "binary body size");
    if (need > available) {
        throw IoError("truncated binary body: header declares " + std::to_string(l.n) +
                      " points x " + std::to_string(l.point_step) + " B = " + std::to_string(need) +
                      " B, " + std::to_string(available) + " B present");
    }
    const auto* src = reinterpret_cast<const std::uint8_t*>(bytes.data() + h.body_offset);
    reserve_points(blob, l.n);
    blob.cloud.data.assign(src, src + need);
    if (available > need) {
        notes.push_back(std::to_string(available - need) + " trailing bytes after the binary body");
    }
}

void read_compressed(std::string_view bytes, const Header& h, const Layout& l, Blob& blob) {
    const std::uint64_t available = bytes.size() - h.body_offset;
    if (available < 8) {
        throw IoError("truncated binary_compressed body: " + std::to_string(available) +
                      " B present, the size prefix alone needs 8 B");
    }
    std::uint32_t csize;
    std::uint32_t usize;
    std::memcpy(&csize, bytes.data() + h.body_offset, 4);
    std::memcpy(&usize, bytes.data() + h.body_offset + 4, 4);
    const std::uint64_t expected = checked_mul(l.n, l.packed_step, "binary_compressed size");
    if (usize != expected) {
        throw IoError("binary_compressed: uncompressed size is " + std::to_string(usize) +
                      " B but " + std::to_string(l.n) + " points x " +
                      std::to_string(l.packed_step) + " B = " + std::to_string(expected) + " B");
    }
    if (std::uint64_t{csize} + 8 > available) {
        throw IoError("truncated binary_compressed body: compressed size " + std::to_string(csize) +
                      " B, " + std::to_string(available - 8) + " B present");
    }
    if (l.n > 0 && csize == 0) {
        throw IoError("binary_compressed: compressed size is 0 B for " + std::to_string(l.n) +
                      " points");
    }
    std::vector<std::uint8_t> soa(usize);
    lzf_decompress({reinterpret_cast<const std::uint8_t*>(bytes.data() + h.body_offset + 8), csize},
                   soa);
    // Structure of arrays (all x, then all y, ...) back to one record per point; `_` stays zero.
    auto& data = blob.cloud.data;
    reserve_points(blob, l.n);
    data.assign(l.n * l.point_step, 0);
    std::size_t block = 0;
    for (const Field& f : l.fields) {
        if (f.name == "_") {
            continue;
        }
        const std::size_t fs = type_size(f.datatype) * f.count;
        const std::uint8_t* src = soa.data() + block;
        for (std::uint64_t i = 0; i < l.n; ++i) {
            std::memcpy(data.data() + i * l.point_step + f.offset, src + i * fs, fs);
        }
        block += fs * l.n;
    }
}

/// Fields sorted by offset, with `_` padding (U 1, COUNT gap) filling every gap, as PCL writes.
std::vector<Field> output_fields(const Blob& blob, bool drop_padding) {
    std::vector<Field> fields = blob.cloud.fields;
    std::stable_sort(fields.begin(), fields.end(),
                     [](const Field& a, const Field& b) { return a.offset < b.offset; });
    std::vector<Field> out;
    std::uint32_t at = 0;
    const auto pad = [&](std::uint32_t to) {
        if (to > at && !drop_padding) {
            Field p;
            p.name = "_";
            p.offset = at;
            p.datatype = Field::UINT8;
            p.count = to - at;
            out.push_back(p);
        }
    };
    for (Field f : fields) {
        if (f.offset < at) {
            throw IoError("field '" + f.name + "' overlaps the field before it");
        }
        pad(f.offset);
        at = f.offset + static_cast<std::uint32_t>(type_size(f.datatype) * f.count);
        if (drop_padding && f.name == "_") {
            continue;
        }
        // Packed colour is declared U 4: same bits, no float NaN canonicalisation anywhere.
        if ((f.name == "rgb" || f.name == "rgba") && f.datatype == Field::FLOAT32) {
            f.datatype = Field::UINT32;
        }
        out.push_back(f);
    }
    pad(blob.cloud.point_step);
    return out;
}

std::string header_text(const Blob& blob, const std::vector<Field>& fields, const char* data) {
    std::string s = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS";
    for (const auto& f : fields) {
        s += " " + f.name;
    }
    s += "\nSIZE";
    for (const auto& f : fields) {
        s += " " + std::to_string(type_size(f.datatype));
    }
    s += "\nTYPE";
    for (const auto& f : fields) {
        s += ' ';
        s += type_letter(f.datatype);
    }
    s += "\nCOUNT";
    for (const auto& f : fields) {
        s += " " + std::to_string(f.count);
    }
    s += "\nWIDTH " + std::to_string(blob.cloud.width) + "\nHEIGHT " +
         std::to_string(blob.cloud.height) + "\nVIEWPOINT";
    for (float v : blob.viewpoint) {
        s += " " + format_number(v);
    }
    s += "\nPOINTS " + std::to_string(blob.size()) + "\nDATA " + data + "\n";
    return s;
}

void write_ascii(const Blob& blob, const std::vector<Field>& fields, ByteSink& sink) {
    std::string buf;
    buf.reserve(1 << 20);
    const std::size_t n = blob.size();
    const std::uint8_t* data = blob.cloud.data.data();
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* p = data + i * blob.cloud.point_step;
        bool first = true;
        for (const Field& f : fields) {
            const std::size_t es = type_size(f.datatype);
            for (std::uint32_t c = 0; c < f.count; ++c) {
                if (!first) {
                    buf += ' ';
                }
                first = false;
                detail::format_value(p + f.offset + c * es, f.datatype, buf);
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

void write_compressed(const Blob& blob, const std::vector<Field>& fields, ByteSink& sink) {
    const std::size_t n = blob.size();
    std::size_t packed = 0;
    for (const auto& f : fields) {
        packed += type_size(f.datatype) * f.count;
    }
    const std::uint64_t usize = std::uint64_t{packed} * n;
    if (usize > 0xffffffffu) {
        throw IoError("binary_compressed holds at most 4294967295 B, this cloud needs " +
                      std::to_string(usize) + " B; write binary instead");
    }
    std::vector<std::uint8_t> soa(usize);
    std::size_t block = 0;
    for (const Field& f : fields) {
        const std::size_t fs = type_size(f.datatype) * f.count;
        for (std::size_t i = 0; i < n; ++i) {
            std::memcpy(soa.data() + block + i * fs,
                        blob.cloud.data.data() + i * blob.cloud.point_step + f.offset, fs);
        }
        block += fs * n;
    }
    const std::vector<std::uint8_t> lz = lzf_compress(soa);
    const auto csize = static_cast<std::uint32_t>(lz.size());
    const auto usize32 = static_cast<std::uint32_t>(usize);
    sink.write(&csize, 4);
    sink.write(&usize32, 4);
    sink.write(lz.data(), lz.size());
}

}  // namespace

namespace {

/// The cloud's shell from a validated header: every value but the data.
void set_shell(const Header& h, const Layout& l, Blob& blob) {
    blob.viewpoint = h.viewpoint;
    blob.cloud.fields = l.fields;
    blob.cloud.point_step = static_cast<std::uint32_t>(l.point_step);
    blob.cloud.width = static_cast<std::uint32_t>(l.width);
    blob.cloud.height = static_cast<std::uint32_t>(l.height);
    blob.cloud.row_step = static_cast<std::uint32_t>(l.point_step * l.width);
    blob.cloud.is_bigendian = false;
}

}  // namespace

std::optional<PcdStart> start_binary_pcd(std::string_view prefix) {
    try {
        const Header h = parse_header(prefix);
        if (h.data != DataKind::kBinary) {
            return std::nullopt;
        }
        PcdStart s;
        const Layout l = validate(h, s.result.notes);
        if (l.point_step != 0 &&
            l.n > (std::numeric_limits<std::uint64_t>::max() - h.body_offset) / l.point_step) {
            return std::nullopt;
        }
        set_shell(h, l, s.result.blob);
        s.result.format = "pcd binary";
        s.body_offset = h.body_offset;
        s.body_bytes = l.n * l.point_step;
        return s;
    } catch (const Error&) {
        return std::nullopt;
    }
}

ReadResult parse_pcd(std::string_view bytes) {
    ReadResult r;
    const Header h = parse_header(bytes);
    const Layout l = validate(h, r.notes);
    Blob& blob = r.blob;
    set_shell(h, l, blob);
    switch (h.data) {
        case DataKind::kAscii:
            read_ascii(bytes, h, l, blob);
            r.format = "pcd ascii";
            break;
        case DataKind::kBinary:
            read_binary(bytes, h, l, blob, r.notes);
            r.format = "pcd binary";
            break;
        case DataKind::kCompressed:
            read_compressed(bytes, h, l, blob);
            r.format = "pcd binary_compressed";
            break;
    }
    update_is_dense(blob);
    return r;
}

void write_pcd(const Blob& blob, PcdEncoding encoding, ByteSink& sink) {
    check_layout(blob);
    const bool compressed = encoding == PcdEncoding::kBinaryCompressed;
    const std::vector<Field> fields = output_fields(blob, compressed);
    switch (encoding) {
        case PcdEncoding::kAscii:
            sink.write(header_text(blob, fields, "ascii"));
            write_ascii(blob, fields, sink);
            break;
        case PcdEncoding::kBinary:
            sink.write(header_text(blob, fields, "binary"));
            sink.write(blob.cloud.data.data(), blob.size() * blob.cloud.point_step);
            break;
        case PcdEncoding::kBinaryCompressed:
            sink.write(header_text(blob, fields, "binary_compressed"));
            write_compressed(blob, fields, sink);
            break;
    }
}

}  // namespace pc::io
