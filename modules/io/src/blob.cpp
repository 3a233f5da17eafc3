#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>

#include <pc/core/error.h>
#include <pc/io/blob.h>

namespace pc::io {

using Field = pcl::PCLPointField;

std::size_t type_size(std::uint8_t datatype) {
    switch (datatype) {
        case Field::INT8:
        case Field::UINT8:
            return 1;
        case Field::INT16:
        case Field::UINT16:
            return 2;
        case Field::INT32:
        case Field::UINT32:
        case Field::FLOAT32:
            return 4;
        case Field::FLOAT64:
        case Field::INT64:
        case Field::UINT64:
            return 8;
        default:
            return 0;
    }
}

char type_letter(std::uint8_t datatype) {
    switch (datatype) {
        case Field::INT8:
        case Field::INT16:
        case Field::INT32:
        case Field::INT64:
            return 'I';
        case Field::UINT8:
        case Field::UINT16:
        case Field::UINT32:
        case Field::UINT64:
            return 'U';
        case Field::FLOAT32:
        case Field::FLOAT64:
            return 'F';
        default:
            return '?';
    }
}

std::uint8_t datatype_of(char letter, std::size_t size) {
    if (letter == 'F') {
        return size == 4 ? Field::FLOAT32 : size == 8 ? Field::FLOAT64 : 0;
    }
    const bool is_signed = letter == 'I';
    if (!is_signed && letter != 'U') {
        return 0;
    }
    switch (size) {
        case 1:
            return is_signed ? Field::INT8 : Field::UINT8;
        case 2:
            return is_signed ? Field::INT16 : Field::UINT16;
        case 4:
            return is_signed ? Field::INT32 : Field::UINT32;
        case 8:
            return is_signed ? Field::INT64 : Field::UINT64;
        default:
            return 0;
    }
}

const Field* find_field(const Blob& blob, std::string_view name) {
    for (const auto& f : blob.cloud.fields) {
        if (f.name == name) {
            return &f;
        }
    }
    return nullptr;
}

namespace {
template <class T>
double load(const std::uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
}
}  // namespace

double value_as_double(const std::uint8_t* p, std::uint8_t datatype) {
    switch (datatype) {
        case Field::INT8:
            return load<std::int8_t>(p);
        case Field::UINT8:
            return load<std::uint8_t>(p);
        case Field::INT16:
            return load<std::int16_t>(p);
        case Field::UINT16:
            return load<std::uint16_t>(p);
        case Field::INT32:
            return load<std::int32_t>(p);
        case Field::UINT32:
            return load<std::uint32_t>(p);
        case Field::FLOAT32:
            return load<float>(p);
        case Field::FLOAT64:
            return load<double>(p);
        case Field::INT64:
            return load<std::int64_t>(p);
        case Field::UINT64:
            return load<std::uint64_t>(p);
        default:
            return std::nan("");
    }
}

std::string field_names(const Blob& blob) {
    std::string names;
    for (const auto& f : blob.cloud.fields) {
        names += (names.empty() ? "" : " ") + f.name;
    }
    return names;
}

Blob empty_like(const Blob& blob) {
    Blob out;
    out.viewpoint = blob.viewpoint;
    out.cloud.header = blob.cloud.header;
    out.cloud.fields = blob.cloud.fields;
    out.cloud.point_step = blob.cloud.point_step;
    out.cloud.is_bigendian = blob.cloud.is_bigendian;
    out.cloud.width = 0;
    out.cloud.height = 1;
    out.cloud.row_step = 0;
    out.cloud.is_dense = true;
    return out;
}

void reserve_points(Blob& blob, std::size_t points) {
    blob.cloud.data.reserve(points * (std::size_t{blob.cloud.point_step} + 4));
}

namespace {

/// The first `kept` points become the cloud (unorganised: height 1).
void set_point_count(Blob& blob, std::size_t kept) {
    const std::size_t step = blob.cloud.point_step;
    blob.cloud.data.resize(kept * step);
    blob.cloud.width = static_cast<std::uint32_t>(kept);
    blob.cloud.height = 1;
    blob.cloud.row_step = static_cast<std::uint32_t>(kept * step);
}

}  // namespace

void keep_points(Blob& blob, std::span<const std::uint32_t> indices) {
    const std::size_t step = blob.cloud.point_step;
    const std::size_t n = blob.size();
    std::uint8_t* data = blob.cloud.data.data();
    for (std::size_t j = 0; j < indices.size(); ++j) {
        const std::uint32_t i = indices[j];
        if (i >= n || (j > 0 && i <= indices[j - 1])) {
            throw Error("keep_points: indices must ascend and be < " + std::to_string(n) +
                        ", got " + std::to_string(i) + " at position " + std::to_string(j));
        }
        if (i != j) {  // i > j: the row moves towards the front over rows already kept
            std::memmove(data + j * step, data + std::size_t{i} * step, step);
        }
    }
    set_point_count(blob, indices.size());
}

Blob copy_points(const Blob& blob, std::span<const std::uint32_t> indices) {
    Blob out = empty_like(blob);
    const std::size_t step = blob.cloud.point_step;
    const std::size_t n = blob.size();
    out.cloud.data.resize(indices.size() * step);
    for (std::size_t j = 0; j < indices.size(); ++j) {
        if (indices[j] >= n) {
            throw Error("copy_points: indices must be < " + std::to_string(n) + ", got " +
                        std::to_string(indices[j]));
        }
        std::memcpy(out.cloud.data.data() + j * step,
                    blob.cloud.data.data() + std::size_t{indices[j]} * step, step);
    }
    out.cloud.width = static_cast<std::uint32_t>(indices.size());
    out.cloud.row_step = static_cast<std::uint32_t>(indices.size() * step);
    update_is_dense(out);
    return out;
}

bool append_points(Blob& to, const Blob& from) {
    const auto same = [](const pcl::PCLPointField& a, const pcl::PCLPointField& b) {
        return a.name == b.name && a.offset == b.offset && a.datatype == b.datatype &&
               a.count == b.count;
    };
    const std::size_t step = to.cloud.point_step;
    if (from.cloud.point_step != step ||
        !std::equal(to.cloud.fields.begin(), to.cloud.fields.end(), from.cloud.fields.begin(),
                    from.cloud.fields.end(), same)) {
        return false;
    }
    const std::size_t n = to.size() + from.size();
    to.cloud.data.resize(to.size() * step);
    to.cloud.data.insert(to.cloud.data.end(), from.cloud.data.begin(),
                         from.cloud.data.begin() + static_cast<std::ptrdiff_t>(from.size() * step));
    to.cloud.width = static_cast<std::uint32_t>(n);
    to.cloud.height = 1;
    to.cloud.row_step = static_cast<std::uint32_t>(n * step);
    to.cloud.is_dense = to.cloud.is_dense && from.cloud.is_dense;
    return true;
}

void keep_flagged(Blob& blob, std::span<const std::uint8_t> flags, bool keep_set) {
    const std::size_t step = blob.cloud.point_step;
    const std::size_t n = blob.size();
    if (flags.size() != n) {
        throw Error("keep_flagged: flags must be one per point (" + std::to_string(n) + "), got " +
                    std::to_string(flags.size()));
    }
    std::uint8_t* data = blob.cloud.data.data();
    std::size_t j = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if ((flags[i] != 0) == keep_set) {
            if (i != j) {  // i > j: the row moves towards the front over rows already kept
                std::memmove(data + j * step, data + i * step, step);
            }
            ++j;
        }
    }
    set_point_count(blob, j);
}

void set_field(Blob& blob, const std::string& name, std::span<const std::uint32_t> values) {
    const std::size_t n = blob.size();
    if (values.size() != n) {
        throw Error("set_field: values must be one per point (" + std::to_string(n) + "), got " +
                    std::to_string(values.size()));
    }
    auto& cloud = blob.cloud;
    const Field* existing = find_field(blob, name);
    if (existing != nullptr && existing->datatype == Field::UINT32 && existing->count == 1) {
        const std::size_t offset = existing->offset;
        for (std::size_t i = 0; i < n; ++i) {
            std::memcpy(&cloud.data[i * cloud.point_step + offset], &values[i], 4);
        }
        return;
    }
    // Append a U 4 field at the end of each point (after dropping an old field of that name).
    std::erase_if(cloud.fields, [&](const Field& f) { return f.name == name; });
    const std::size_t old_step = cloud.point_step;
    const std::size_t new_step = old_step + 4;
    Field f;
    f.name = name;
    f.offset = static_cast<std::uint32_t>(old_step);
    f.datatype = Field::UINT32;
    f.count = 1;
    cloud.fields.push_back(f);
    // The points grow into the room the readers reserved (reserve_points): no second copy.
    cloud.data.resize(n * new_step);
    // Back to front: each row moves to a higher offset, past every row not yet moved.
    std::uint8_t* data = cloud.data.data();
    for (std::size_t i = n; i-- > 0;) {
        std::memmove(data + i * new_step, data + i * old_step, old_step);
        std::memcpy(data + i * new_step + old_step, &values[i], 4);
    }
    cloud.point_step = static_cast<std::uint32_t>(new_step);
    cloud.row_step = static_cast<std::uint32_t>(new_step * cloud.width);
}

void remove_field(Blob& blob, const std::string& name) {
    auto& cloud = blob.cloud;
    const auto it = std::find_if(cloud.fields.begin(), cloud.fields.end(),
                                 [&](const Field& f) { return f.name == name; });
    if (it == cloud.fields.end()) {
        return;
    }
    const std::size_t at = it->offset;
    const std::size_t width = type_size(it->datatype) * std::max<std::uint32_t>(it->count, 1);
    cloud.fields.erase(it);
    const std::size_t n = blob.size(), old_step = cloud.point_step, new_step = old_step - width;
    // Front to back: each row moves to a lower offset, over rows already moved.
    std::uint8_t* data = cloud.data.data();
    for (std::size_t i = 0; i < n; ++i) {
        std::memmove(data + i * new_step, data + i * old_step, at);
        std::memmove(data + i * new_step + at, data + i * old_step + at + width,
                     old_step - at - width);
    }
    cloud.data.resize(n * new_step);
    for (Field& f : cloud.fields) {
        if (f.offset > at) {
            f.offset -= static_cast<std::uint32_t>(width);
        }
    }
    cloud.point_step = static_cast<std::uint32_t>(new_step);
    cloud.row_step = static_cast<std::uint32_t>(new_step * cloud.width);
}

void update_is_dense(Blob& blob) {
    // Every F4 / F8 element, point by point in one pass over the data: an element is not
    // finite when its exponent bits are all ones (Inf or NaN).
    struct Element {
        std::size_t offset;
        bool wide;
    };
    std::vector<Element> elements;
    for (const auto& f : blob.cloud.fields) {
        if (f.datatype == Field::FLOAT32 || f.datatype == Field::FLOAT64) {
            const std::size_t es = type_size(f.datatype);
            for (std::size_t c = 0; c < f.count; ++c) {
                elements.push_back({f.offset + c * es, f.datatype == Field::FLOAT64});
            }
        }
    }
    const std::size_t n = blob.size();
    const std::size_t step = blob.cloud.point_step;
    const std::uint8_t* data = blob.cloud.data.data();
    constexpr std::size_t kChunk = 4096;
    for (std::size_t begin = 0; begin < n; begin += kChunk) {
        bool bad = false;
        for (std::size_t i = begin; i < std::min(n, begin + kChunk); ++i) {
            for (const Element& e : elements) {
                const std::uint8_t* p = data + i * step + e.offset;
                if (e.wide) {
                    std::uint64_t bits;
                    std::memcpy(&bits, p, 8);
                    bad |= (bits & 0x7ff0000000000000ull) == 0x7ff0000000000000ull;
                } else {
                    std::uint32_t bits;
                    std::memcpy(&bits, p, 4);
                    bad |= (bits & 0x7f800000u) == 0x7f800000u;
                }
            }
        }
        if (bad) {
            blob.cloud.is_dense = false;
            return;
        }
    }
    blob.cloud.is_dense = true;
}

void check_layout(const Blob& blob) {
    const auto& c = blob.cloud;
    const std::size_t need = blob.size() * std::size_t{c.point_step};
    if (c.data.size() < need) {
        throw IoError("cloud data holds " + std::to_string(c.data.size()) + " B, " +
                      std::to_string(blob.size()) + " points x " + std::to_string(c.point_step) +
                      " B need " + std::to_string(need));
    }
    for (const auto& f : c.fields) {
        const std::size_t es = type_size(f.datatype);
        if (es == 0) {
            throw IoError("field '" + f.name + "' has unknown datatype " +
                          std::to_string(int{f.datatype}));
        }
        if (f.count == 0 || f.offset + es * f.count > c.point_step) {
            throw IoError("field '" + f.name + "' does not fit in point_step " +
                          std::to_string(c.point_step));
        }
    }
}

}  // namespace pc::io
