#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <set>

#include <pc/core/error.h>
#include <pc/io/ply.h>

#include "parse_util.h"

namespace pc::io {

namespace {

using detail::checked_mul;
using detail::quote;
using Field = pcl::PCLPointField;

using detail::kMaxHeaderBytes;

enum class PlyFormat { kAscii, kBinaryLe, kBinaryBe };

struct Property {
    std::string name;
    std::uint8_t type = 0;        // PCLPointField datatype of the value (or of list items)
    std::uint8_t count_type = 0;  // list length type, 0 for a scalar property
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> props;
};

struct Header {
    PlyFormat format = PlyFormat::kAscii;
    std::vector<Element> elements;
    std::size_t body_offset = 0;
    std::size_t end_line = 0;
};

std::uint8_t ply_type(std::string_view t) {
    static const std::pair<std::string_view, std::uint8_t> kTypes[] = {
        {"char", Field::INT8},      {"int8", Field::INT8},       {"uchar", Field::UINT8},
        {"uint8", Field::UINT8},    {"short", Field::INT16},     {"int16", Field::INT16},
        {"ushort", Field::UINT16},  {"uint16", Field::UINT16},   {"int", Field::INT32},
        {"int32", Field::INT32},    {"uint", Field::UINT32},     {"uint32", Field::UINT32},
        {"float", Field::FLOAT32},  {"float32", Field::FLOAT32}, {"double", Field::FLOAT64},
        {"float64", Field::FLOAT64}};
    for (const auto& [name, type] : kTypes) {
        if (name == t) {
            return type;
        }
    }
    return 0;
}

const char* ply_type_name(std::uint8_t datatype) {
    switch (datatype) {
        case Field::INT8:
            return "char";
        case Field::UINT8:
            return "uchar";
        case Field::INT16:
            return "short";
        case Field::UINT16:
            return "ushort";
        case Field::INT32:
            return "int";
        case Field::UINT32:
            return "uint";
        case Field::FLOAT32:
            return "float";
        case Field::FLOAT64:
            return "double";
        default:
            return nullptr;
    }
}

Header parse_header(std::string_view bytes) {
    Header h;
    detail::LineCursor cur{bytes};
    std::string_view line;
    cur.next(line);  // "ply", checked by the caller's format detection
    bool have_format = false;
    while (true) {
        if (cur.pos > kMaxHeaderBytes) {
            throw IoError("PLY header is longer than " + std::to_string(kMaxHeaderBytes) +
                          " B without end_header");
        }
        if (!cur.next(line)) {
            throw IoError("PLY header has no end_header line");
        }
        const std::size_t ln = cur.line_number;
        const auto fail = [ln](const std::string& what) {
            throw IoError("PLY header line " + std::to_string(ln) + ": " + what);
        };
        detail::Tokens toks{line};
        std::vector<std::string_view> t;
        for (std::string_view tok; toks.next(tok);) {
            t.push_back(tok);
        }
        if (t.empty() || t[0] == "comment" || t[0] == "obj_info") {
            continue;
        }
        if (t[0] == "format") {
            if (t.size() != 3 || t[2] != "1.0") {
                fail("format line must be 'format <kind> 1.0'");
            }
            if (t[1] == "ascii") {
                h.format = PlyFormat::kAscii;
            } else if (t[1] == "binary_little_endian") {
                h.format = PlyFormat::kBinaryLe;
            } else if (t[1] == "binary_big_endian") {
                h.format = PlyFormat::kBinaryBe;
            } else {
                fail("unknown format " + quote(t[1]));
            }
            have_format = true;
        } else if (t[0] == "element") {
            std::uint64_t count = 0;
            if (t.size() != 3 || !detail::parse_u64(t[2], count)) {
                fail("element line must be 'element <name> <non-negative count>'");
            }
            h.elements.push_back({std::string(t[1]), count, {}});
        } else if (t[0] == "property") {
            if (h.elements.empty()) {
                fail("property before any element");
            }
            Property p;
            if (t.size() == 5 && t[1] == "list") {
                p.count_type = ply_type(t[2]);
                p.type = ply_type(t[3]);
                p.name = t[4];
                if (p.count_type == 0 || p.type == 0 || p.count_type == Field::FLOAT32 ||
                    p.count_type == Field::FLOAT64) {
                    fail("bad list property types " + quote(t[2]) + " " + quote(t[3]));
                }
            } else if (t.size() == 3) {
                p.type = ply_type(t[1]);
                p.name = t[2];
                if (p.type == 0) {
                    fail("unknown property type " + quote(t[1]));
                }
            } else {
                fail("property line must be 'property <type> <name>'");
            }
            h.elements.back().props.push_back(p);
        } else if (t[0] == "end_header") {
            if (!have_format) {
                throw IoError("PLY header has no format line");
            }
            h.body_offset = cur.pos;
            h.end_line = ln;
            return h;
        } else {
            fail("unknown PLY keyword " + quote(t[0]));
        }
    }
}

/// How one vertex property lands in the output point.
struct Target {
    std::size_t dst_offset = 0;  // byte offset in the output point
    int colour_byte = -1;        // >= 0: byte of the packed rgb(a) word (b=0, g=1, r=2, a=3)
};

struct VertexLayout {
    std::vector<Field> fields;
    std::vector<Target> targets;  // one per vertex property
    std::size_t point_step = 0;
    std::size_t row_bytes = 0;                       // binary bytes of one vertex row
    std::optional<std::array<std::size_t, 3>> f_dc;  // offsets of f_dc_0..2, for derived rgb
    std::array<std::uint8_t, 3> f_dc_type{};         // their datatypes (F4 or F8)
    std::size_t rgb_from_dc = 0;                     // offset of the derived rgb field
};

void add_field(VertexLayout& v, const std::string& name, std::uint8_t type) {
    Field f;
    f.name = name;
    f.offset = static_cast<std::uint32_t>(v.point_step);
    f.datatype = type;
    f.count = 1;
    v.fields.push_back(f);
    v.point_step += type_size(type);
}

VertexLayout vertex_layout(const Element& e) {
    VertexLayout v;
    std::set<std::string> names;
    const auto find = [&](std::initializer_list<const char*> alts) -> const Property* {
        for (const char* a : alts) {
            for (const auto& p : e.props) {
                if (p.name == a) {
                    return &p;
                }
            }
        }
        return nullptr;
    };
    for (const auto& p : e.props) {
        if (p.count_type != 0) {
            throw IoError("PLY vertex property '" + p.name +
                          "' is a list; lists are not supported "
                          "on vertices");
        }
        if (!names.insert(p.name).second) {
            throw IoError("PLY vertex property '" + p.name + "' appears twice");
        }
        v.row_bytes += type_size(p.type);
    }
    for (const char* axis : {"x", "y", "z"}) {
        if (names.count(axis) == 0) {
            throw IoError(std::string("PLY vertex element has no '") + axis + "' property");
        }
    }
    const Property* red = find({"red", "diffuse_red"});
    const Property* green = find({"green", "diffuse_green"});
    const Property* blue = find({"blue", "diffuse_blue"});
    const Property* alpha = find({"alpha", "diffuse_alpha"});
    const bool packed = red && green && blue && red->type == Field::UINT8 &&
                        green->type == Field::UINT8 && blue->type == Field::UINT8;
    const bool packed_alpha = packed && alpha && alpha->type == Field::UINT8;
    std::size_t colour_offset = 0;
    for (const auto& p : e.props) {
        Target t;
        const bool is_colour =
            packed && (&p == red || &p == green || &p == blue || (packed_alpha && &p == alpha));
        if (is_colour) {
            if (colour_offset == 0 && find_if(v.fields.begin(), v.fields.end(), [](auto& f) {
                                          return f.name == "rgb" || f.name == "rgba";
                                      }) == v.fields.end()) {
                colour_offset = v.point_step;
                add_field(v, packed_alpha ? "rgba" : "rgb", Field::UINT32);
            }
            t.dst_offset = colour_offset;
            t.colour_byte = &p == blue ? 0 : &p == green ? 1 : &p == red ? 2 : 3;
        } else {
            std::string name = p.name;
            if (name == "nx" || name == "ny" || name == "nz") {
                name = std::string("normal_") + name.back();
            } else if (name.rfind("scalar_", 0) == 0 && name.size() > 7) {
                name.erase(0, 7);  // CloudCompare's scalar fields: scalar_label is label
            }
            if (name != p.name && names.count(name) != 0) {
                name = p.name;  // both nx and normal_x exist: keep the file's names
            }
            t.dst_offset = v.point_step;
            add_field(v, name, p.type);
        }
        v.targets.push_back(t);
    }
    // 3D Gaussian splatting: colour = 0.5 + C0 * f_dc (SH degree 0), when no colour is stored.
    if (!packed && names.count("f_dc_0") && names.count("f_dc_1") && names.count("f_dc_2") &&
        names.count("rgb") == 0) {
        std::array<std::size_t, 3> off{};
        for (int c = 0; c < 3; ++c) {
            for (std::size_t i = 0; i < e.props.size(); ++i) {
                if (e.props[i].name == "f_dc_" + std::to_string(c)) {
                    off[c] = v.targets[i].dst_offset;
                    v.f_dc_type[c] = e.props[i].type;
                    if (e.props[i].type != Field::FLOAT32 && e.props[i].type != Field::FLOAT64) {
                        return v;  // not the 3DGS layout; keep the fields only
                    }
                }
            }
        }
        v.f_dc = off;
        v.rgb_from_dc = v.point_step;
        add_field(v, "rgb", Field::UINT32);
    }
    return v;
}

/// Copies one scalar of `size` bytes, swapping bytes for big-endian files.
inline void copy_value(std::uint8_t* dst, const std::uint8_t* src, std::size_t size, bool swap) {
    if (!swap) {
        std::memcpy(dst, src, size);
    } else {
        for (std::size_t k = 0; k < size; ++k) {
            dst[k] = src[size - 1 - k];
        }
    }
}

std::uint64_t read_uint(const std::uint8_t* p, std::uint8_t type, bool swap) {
    std::uint8_t buf[8];
    const std::size_t s = type_size(type);
    copy_value(buf, p, s, swap);
    const double v = value_as_double(buf, type);
    return v < 0 ? ~std::uint64_t{0} : static_cast<std::uint64_t>(v);
}

/// Skips a non-vertex element in a binary body; returns the new position.
std::size_t skip_binary(const Element& e, std::string_view bytes, std::size_t pos, bool swap) {
    std::size_t fixed = 0;
    bool has_list = false;
    for (const auto& p : e.props) {
        has_list |= p.count_type != 0;
        fixed += p.count_type ? 0 : type_size(p.type);
    }
    const std::size_t available = bytes.size() - pos;
    if (!has_list) {
        const std::uint64_t need = checked_mul(e.count, fixed, "PLY element size");
        if (need > available) {
            throw IoError("truncated PLY body: element '" + e.name + "' needs " +
                          std::to_string(need) + " B, " + std::to_string(available) + " B present");
        }
        return pos + need;
    }
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    for (std::uint64_t r = 0; r < e.count; ++r) {
        for (const auto& p : e.props) {
            const std::size_t cs = p.count_type ? type_size(p.count_type) : 0;
            std::uint64_t len = 1;
            if (p.count_type) {
                if (pos + cs > bytes.size()) {
                    throw IoError("truncated PLY body in element '" + e.name + "' row " +
                                  std::to_string(r));
                }
                len = read_uint(data + pos, p.count_type, swap);
                pos += cs;
            }
            const std::uint64_t need = checked_mul(len, type_size(p.type), "PLY list size");
            if (need > bytes.size() - pos) {
                throw IoError("truncated PLY body in element '" + e.name + "' row " +
                              std::to_string(r));
            }
            pos += need;
        }
    }
    return pos;
}

void fill_rgb_from_dc(const VertexLayout& v, Blob& blob) {
    const std::size_t n = blob.size();
    for (std::size_t i = 0; i < n; ++i) {
        std::uint8_t* p = blob.cloud.data.data() + i * v.point_step;
        std::uint32_t word = 0;
        for (int c = 0; c < 3; ++c) {
            const double dc = value_as_double(p + (*v.f_dc)[c], v.f_dc_type[c]);
            const double lin = 0.5 + 0.28209479177387814 * dc;
            const double colour = std::isfinite(lin) ? std::clamp(lin, 0.0, 1.0) : 0.0;
            const auto byte = static_cast<std::uint32_t>(std::lround(colour * 255.0));
            word |= byte << (8 * (2 - c));  // r in bits 16..23, g 8..15, b 0..7
        }
        std::memcpy(p + v.rgb_from_dc, &word, 4);
    }
}

}  // namespace

namespace {

/// The body of a binary PLY: the vertex rows into `out` (point_step bytes each), other elements
/// skipped; every byte of the body must belong to an element.
void read_binary_body(const Header& h,
                      const Element& ve,
                      const VertexLayout& v,
                      std::string_view bytes,
                      std::uint8_t* out,
                      bool swap) {
    const std::uint64_t n = ve.count;
    std::size_t pos = h.body_offset;
    const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
    for (const Element& e : h.elements) {
        if (&e != &ve) {
            pos = skip_binary(e, bytes, pos, swap);
            continue;
        }
        // parse_ply() bounded the rows by the bytes after the header; the elements before the
        // vertices take some of them
        if (checked_mul(n, v.row_bytes, "PLY vertex data") > bytes.size() - pos) {
            throw IoError("truncated PLY body: " + std::to_string(n) + " vertices x " +
                          std::to_string(v.row_bytes) + " B, " +
                          std::to_string(bytes.size() - pos) +
                          " B present after the elements before them");
        }
        for (std::uint64_t i = 0; i < n; ++i) {
            std::uint8_t* dst = out + i * v.point_step;
            for (std::size_t k = 0; k < e.props.size(); ++k) {
                const std::size_t s = type_size(e.props[k].type);
                const Target& t = v.targets[k];
                if (t.colour_byte >= 0) {
                    dst[t.dst_offset + t.colour_byte] = data[pos];
                } else {
                    copy_value(dst + t.dst_offset, data + pos, s, swap);
                }
                pos += s;
            }
        }
    }
    if (pos != bytes.size()) {
        throw IoError(std::to_string(bytes.size() - pos) +
                      " B after the last PLY element: the element counts do not match the "
                      "body (vertex count " +
                      std::to_string(n) + ")");
    }
}

/// The body of an ASCII PLY: one line a row, the vertex rows parsed into `out`, other elements
/// skipped; nothing but blank lines after the last element.
void read_ascii_body(const Header& h,
                     const Element& ve,
                     const VertexLayout& v,
                     std::string_view bytes,
                     std::uint8_t* out) {
    const std::uint64_t n = ve.count;
    detail::LineCursor cur{bytes, h.body_offset, h.end_line};
    std::string_view line;
    const auto next_row = [&](const Element& e, std::uint64_t row) {
        while (cur.next(line)) {
            detail::Tokens toks{line};
            std::string_view tok;
            if (toks.next(tok)) {
                return;
            }
        }
        throw IoError("truncated PLY body: element '" + e.name + "' has " + std::to_string(row) +
                      " rows, header declares " + std::to_string(e.count));
    };
    for (const Element& e : h.elements) {
        for (std::uint64_t row = 0; row < e.count; ++row) {
            next_row(e, row);
            if (&e != &ve) {
                continue;  // faces and other elements are skipped
            }
            detail::Tokens toks{line};
            std::string_view tok;
            std::uint8_t* dst = out + row * v.point_step;
            std::size_t k = 0;
            for (; toks.next(tok); ++k) {
                if (k == e.props.size()) {
                    break;
                }
                const Property& p = e.props[k];
                const Target& t = v.targets[k];
                std::uint8_t tmp[8];
                std::uint8_t* target = t.colour_byte >= 0 ? tmp : dst + t.dst_offset;
                if (!detail::parse_value(tok, p.type, target)) {
                    throw IoError("line " + std::to_string(cur.line_number) + ": " + quote(tok) +
                                  " is not a valid " + ply_type_name(p.type) + " for property '" +
                                  p.name + "'");
                }
                if (t.colour_byte >= 0) {
                    dst[t.dst_offset + t.colour_byte] = tmp[0];
                }
            }
            if (k != e.props.size()) {
                std::size_t found = k;
                while (toks.next(tok)) {
                    ++found;
                }
                throw IoError("line " + std::to_string(cur.line_number) + ": expected " +
                              std::to_string(e.props.size()) + " values, found " +
                              std::to_string(found + (k == e.props.size() ? 1 : 0)));
            }
        }
    }
    while (cur.next(line)) {
        detail::Tokens toks{line};
        std::string_view tok;
        if (toks.next(tok)) {
            throw IoError("line " + std::to_string(cur.line_number) +
                          ": extra data after the last PLY element (vertex count " +
                          std::to_string(n) + ")");
        }
    }
}

}  // namespace

ReadResult parse_ply(std::string_view bytes) {
    ReadResult r;
    const Header h = parse_header(bytes);
    const auto vit = std::find_if(h.elements.begin(), h.elements.end(),
                                  [](const Element& e) { return e.name == "vertex"; });
    if (vit == h.elements.end()) {
        throw IoError("PLY has no vertex element");
    }
    const Element& ve = *vit;
    const VertexLayout v = vertex_layout(ve);
    if (ve.count > 0xffffffffu) {
        throw IoError("PLY vertex count " + std::to_string(ve.count) + " exceeds 4294967295");
    }
    const std::uint64_t n = ve.count;
    const std::uint64_t available = bytes.size() - h.body_offset;
    Blob& blob = r.blob;
    const bool binary = h.format != PlyFormat::kAscii;
    const bool swap = h.format == PlyFormat::kBinaryBe;
    // Bound the allocation by the bytes present before making it.
    const std::uint64_t min_row = binary ? v.row_bytes : 2 * ve.props.size();
    const std::uint64_t min_need = checked_mul(n, min_row, "PLY vertex data");
    if (min_need > available + (binary ? 0 : 1)) {
        throw IoError("truncated PLY body: header declares " + std::to_string(n) + " vertices x " +
                      std::to_string(min_row) + " B, " + std::to_string(available) + " B present");
    }
    blob.cloud.fields = v.fields;
    blob.cloud.point_step = static_cast<std::uint32_t>(v.point_step);
    blob.cloud.width = static_cast<std::uint32_t>(n);
    blob.cloud.height = 1;
    blob.cloud.row_step = static_cast<std::uint32_t>(n * v.point_step);
    reserve_points(blob, n);
    blob.cloud.data.assign(n * v.point_step, 0);
    std::uint8_t* out = blob.cloud.data.data();

    if (binary) {
        r.format = swap ? "ply binary_big_endian" : "ply binary_little_endian";
        read_binary_body(h, ve, v, bytes, out, swap);
    } else {
        r.format = "ply ascii";
        read_ascii_body(h, ve, v, bytes, out);
    }
    if (v.f_dc) {
        fill_rgb_from_dc(v, blob);
        r.notes.push_back("3D Gaussian splatting PLY: rgb derived from f_dc_0..2");
    }
    update_is_dense(blob);
    return r;
}

void write_ply(const Blob& blob, bool binary, ByteSink& sink, bool scalar_prefix) {
    check_layout(blob);
    struct Out {
        std::string name;
        std::size_t offset;
        std::uint8_t type;
    };
    std::vector<Out> props;
    for (const auto& f : blob.cloud.fields) {
        if (f.name == "_") {
            continue;
        }
        const std::size_t es = type_size(f.datatype);
        if ((f.name == "rgb" || f.name == "rgba") && es == 4 && f.count == 1) {
            props.push_back({"red", f.offset + 2, Field::UINT8});
            props.push_back({"green", f.offset + 1, Field::UINT8});
            props.push_back({"blue", f.offset + 0, Field::UINT8});
            if (f.name == "rgba") {
                props.push_back({"alpha", f.offset + 3, Field::UINT8});
            }
            continue;
        }
        if (ply_type_name(f.datatype) == nullptr) {
            throw IoError("field '" + f.name + "' is " + type_letter(f.datatype) +
                          std::to_string(es) + ", which PLY cannot hold; write PCD instead");
        }
        std::string name = f.name;
        if (name == "normal_x" || name == "normal_y" || name == "normal_z") {
            name = std::string("n") + name.back();
        } else if (scalar_prefix && name != "x" && name != "y" && name != "z" &&
                   name != "intensity") {
            name = "scalar_" + name;  // what CloudCompare loads as a scalar field by itself
        }
        for (std::uint32_t c = 0; c < f.count; ++c) {
            props.push_back({f.count == 1 ? name : name + "_" + std::to_string(c),
                             f.offset + c * es, f.datatype});
        }
    }
    std::string head = "ply\nformat ";
    head += binary ? "binary_little_endian" : "ascii";
    head +=
        " 1.0\ncomment written by pctools\nelement vertex " + std::to_string(blob.size()) + "\n";
    for (const auto& p : props) {
        head += std::string("property ") + ply_type_name(p.type) + " " + p.name + "\n";
    }
    head += "end_header\n";
    sink.write(head);
    const std::size_t n = blob.size();
    std::string buf;
    buf.reserve(1 << 20);
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* src = blob.cloud.data.data() + i * blob.cloud.point_step;
        for (std::size_t k = 0; k < props.size(); ++k) {
            if (binary) {
                buf.append(reinterpret_cast<const char*>(src + props[k].offset),
                           type_size(props[k].type));
            } else {
                if (k > 0) {
                    buf += ' ';
                }
                detail::format_value(src + props[k].offset, props[k].type, buf);
            }
        }
        if (!binary) {
            buf += '\n';
        }
        if (buf.size() > (1 << 20) - 4096) {
            sink.write(buf);
            buf.clear();
        }
    }
    sink.write(buf);
}

}  // namespace pc::io
