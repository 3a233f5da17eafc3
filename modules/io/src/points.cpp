#include <algorithm>
#include <cmath>
#include <cstring>

#include <pc/core/error.h>
#include <pc/io/points.h>

namespace pc::io {

using Field = pcl::PCLPointField;

namespace {
bool is_real(std::uint8_t t) { return t == Field::FLOAT32 || t == Field::FLOAT64; }
/// Writes `v` as a T at `dst` (any alignment).
template <class T>
void store(std::uint8_t* dst, double v) {
    const auto x = static_cast<T>(v);
    std::memcpy(dst, &x, sizeof x);
}

/// Writes an integer value (exact in double: all PCD integer types up to 2^53) as `datatype`.
void store_integer(double v, std::uint8_t datatype, std::uint8_t* dst) {
    switch (datatype) {
        case Field::INT8:
            return store<std::int8_t>(dst, v);
        case Field::UINT8:
            return store<std::uint8_t>(dst, v);
        case Field::INT16:
            return store<std::int16_t>(dst, v);
        case Field::UINT16:
            return store<std::uint16_t>(dst, v);
        case Field::INT32:
            return store<std::int32_t>(dst, v);
        case Field::UINT32:
            return store<std::uint32_t>(dst, v);
        case Field::INT64:
            return store<std::int64_t>(dst, v);
        default:
            return store<std::uint64_t>(dst, v);
    }
}

bool is_packed_colour(const Field& f) {
    return (f.name == "rgb" || f.name == "rgba") && type_size(f.datatype) == 4 && f.count == 1;
}
}  // namespace

Cloud xyz(const Blob& blob) {
    const Field* axes[3] = {find_field(blob, "x"), find_field(blob, "y"), find_field(blob, "z")};
    if (!axes[0] || !axes[1] || !axes[2]) {
        throw IoError("cloud has no x y z fields");
    }
    const std::size_t n = blob.size();
    Cloud cloud;
    cloud.resize(n);
    cloud.width = static_cast<std::uint32_t>(n);
    cloud.height = 1;
    const std::uint8_t* data = blob.cloud.data.data();
    const std::size_t step = blob.cloud.point_step;
    const bool fast = axes[0]->datatype == Field::FLOAT32 && axes[1]->datatype == Field::FLOAT32 &&
                      axes[2]->datatype == Field::FLOAT32;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* p = data + i * step;
        auto& q = cloud[i];
        if (fast) {
            std::memcpy(&q.x, p + axes[0]->offset, 4);
            std::memcpy(&q.y, p + axes[1]->offset, 4);
            std::memcpy(&q.z, p + axes[2]->offset, 4);
        } else {
            q.x = static_cast<float>(value_as_double(p + axes[0]->offset, axes[0]->datatype));
            q.y = static_cast<float>(value_as_double(p + axes[1]->offset, axes[1]->datatype));
            q.z = static_cast<float>(value_as_double(p + axes[2]->offset, axes[2]->datatype));
        }
    }
    cloud.is_dense = false;
    return cloud;
}

XyzPoints::XyzPoints(const Blob& blob) {
    const Field* axes[3] = {find_field(blob, "x"), find_field(blob, "y"), find_field(blob, "z")};
    const bool floats = axes[0] && axes[1] && axes[2] && axes[0]->datatype == Field::FLOAT32 &&
                        axes[1]->datatype == Field::FLOAT32 && axes[2]->datatype == Field::FLOAT32;
    if (!floats) {
        copy_ = xyz(blob);
        view_ = XyzView(copy_);
        return;
    }
    view_.base = blob.cloud.data.data();
    view_.stride = blob.cloud.point_step;
    view_.size = blob.size();
    for (int a = 0; a < 3; ++a) {
        view_.offset[a] = axes[a]->offset;
    }
}

XyzSortable::XyzSortable(Blob& blob) {
    const Field* axes[3] = {find_field(blob, "x"), find_field(blob, "y"), find_field(blob, "z")};
    bool consecutive = true;
    for (int a = 0; a < 3; ++a) {
        consecutive = consecutive && axes[a] != nullptr && axes[a]->datatype == Field::FLOAT32 &&
                      axes[a]->count == 1 &&
                      axes[a]->offset == axes[0]->offset + 4 * static_cast<std::uint32_t>(a);
    }
    if (consecutive) {
        records_ =
            XyzRecords(blob.cloud.data.data(), blob.cloud.point_step, blob.size(), axes[0]->offset);
        if (records_.aligned()) {
            return;
        }
    }
    copy_ = xyz(blob);
    records_ = XyzRecords(copy_);
}

std::vector<Rgb> colours(const Blob& blob) {
    const std::size_t n = blob.size();
    const std::size_t step = blob.cloud.point_step;
    const std::uint8_t* data = blob.cloud.data.data();
    std::vector<Rgb> out(n);
    for (const char* packed : {"rgb", "rgba"}) {
        const Field* f = find_field(blob, packed);
        if (f != nullptr && is_packed_colour(*f)) {
            for (std::size_t i = 0; i < n; ++i) {
                std::uint32_t w;
                std::memcpy(&w, data + i * step + f->offset, 4);
                out[i] = {static_cast<float>((w >> 16) & 0xff) / 255.0f,
                          static_cast<float>((w >> 8) & 0xff) / 255.0f,
                          static_cast<float>(w & 0xff) / 255.0f};
            }
            return out;
        }
    }
    for (const auto& trio : {std::array<const char*, 3>{"red", "green", "blue"},
                             std::array<const char*, 3>{"r", "g", "b"}}) {
        const Field* f[3] = {find_field(blob, trio[0]), find_field(blob, trio[1]),
                             find_field(blob, trio[2])};
        if (!f[0] || !f[1] || !f[2]) {
            continue;
        }
        for (std::size_t i = 0; i < n; ++i) {
            float c[3];
            for (int k = 0; k < 3; ++k) {
                const double v = value_as_double(data + i * step + f[k]->offset, f[k]->datatype);
                c[k] = static_cast<float>(is_real(f[k]->datatype) ? v : v / 255.0);
            }
            out[i] = {c[0], c[1], c[2]};
        }
        return out;
    }
    throw IoError("cloud has no colour (looked for rgb, rgba, red green blue, r g b)");
}

std::vector<std::uint32_t> labels(const Blob& blob, const std::string& name) {
    const Field* f = find_field(blob, name);
    if (f == nullptr) {
        throw IoError("cloud has no '" + name + "' field" +
                      (name == "label" ? " (label its clusters first: pc_dbscan, then "
                                         "pc_recursive_split; or pc_fruitcount --cloud)"
                                       : ""));
    }
    if (is_real(f->datatype) || f->count != 1) {
        throw IoError("field '" + name + "' must be an integer with COUNT 1, got " +
                      type_letter(f->datatype) + std::to_string(type_size(f->datatype)) +
                      " COUNT " + std::to_string(f->count));
    }
    const std::size_t n = blob.size();
    std::vector<std::uint32_t> out(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double v =
            value_as_double(&blob.cloud.data[i * blob.cloud.point_step + f->offset], f->datatype);
        if (v < 0 || v > 4294967295.0) {
            throw IoError("field '" + name + "' of point " + std::to_string(i) + " is " +
                          format_number(v) + ", outside 0..4294967295");
        }
        out[i] = static_cast<std::uint32_t>(v);
    }
    return out;
}

namespace {

/// For sorted (group, value) votes (group_of(vote) reads the group; equal votes are equal
/// entries): calls found(group, vote) once a group with its most frequent vote, ties to the
/// first (the smallest value).
template <class Vote, class GroupOf, class Found>
void for_each_mode(const std::vector<Vote>& votes, GroupOf group_of, Found found) {
    for (std::size_t r = 0; r < votes.size();) {
        const std::uint32_t g = group_of(votes[r]);
        std::size_t best = 0, best_at = r;
        while (r < votes.size() && group_of(votes[r]) == g) {
            std::size_t run = r;
            while (run < votes.size() && votes[run] == votes[r]) {
                ++run;
            }
            if (run - r > best) {  // ascending values: ties keep the smallest
                best = run - r;
                best_at = r;
            }
            r = run;
        }
        found(g, votes[best_at]);
    }
}

}  // namespace

Blob aggregate(const Blob& blob,
               const std::vector<std::uint32_t>& group,
               std::uint32_t group_count) {
    const std::size_t n = blob.size();
    if (group.size() != n) {
        throw Error("aggregate: group must have one entry per point");
    }
    Blob out = empty_like(blob);
    const std::size_t step = blob.cloud.point_step;
    out.cloud.width = group_count;
    out.cloud.row_step = static_cast<std::uint32_t>(group_count * step);
    out.cloud.data.assign(std::size_t{group_count} * step, 0);
    std::vector<std::uint32_t> members(group_count, 0);
    for (std::uint32_t g : group) {
        if (g != kNoGroup) {
            ++members[g];
        }
    }
    const std::uint8_t* src = blob.cloud.data.data();
    std::uint8_t* dst = out.cloud.data.data();
    // One accumulator a group, reused for every real element and colour channel in turn (one
    // per channel at once was 32 bytes a group: with a voxel a point, more than the cloud).
    std::vector<double> sum;
    const auto add_up = [&](auto value_of) {
        sum.assign(group_count, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
            if (group[i] != kNoGroup) {
                sum[group[i]] += value_of(src + i * step);
            }
        }
    };
    for (const Field& f : blob.cloud.fields) {
        if (f.name == "_") {
            continue;
        }
        const std::size_t es = type_size(f.datatype);
        if (is_packed_colour(f)) {
            for (int c = 0; c < 4; ++c) {
                add_up([&](const std::uint8_t* p) {
                    std::uint32_t w;
                    std::memcpy(&w, p + f.offset, 4);
                    return static_cast<double>((w >> (8 * c)) & 0xff);
                });
                for (std::uint32_t g = 0; g < group_count; ++g) {
                    std::uint32_t w;
                    std::memcpy(&w, dst + g * step + f.offset, 4);
                    w |= static_cast<std::uint32_t>(std::lround(sum[g] / members[g])) << (8 * c);
                    std::memcpy(dst + g * step + f.offset, &w, 4);
                }
            }
            continue;
        }
        for (std::uint32_t e = 0; e < f.count; ++e) {
            const std::size_t off = f.offset + e * es;
            if (is_real(f.datatype)) {
                add_up([&](const std::uint8_t* p) { return value_as_double(p + off, f.datatype); });
                for (std::uint32_t g = 0; g < group_count; ++g) {
                    const double mean = sum[g] / members[g];
                    if (f.datatype == Field::FLOAT32) {
                        const auto v = static_cast<float>(mean);
                        std::memcpy(dst + g * step + off, &v, 4);
                    } else {
                        std::memcpy(dst + g * step + off, &mean, 8);
                    }
                }
                continue;
            }
            // Integer fields (labels, ids, classes): the most frequent value, ties to the smallest.
            // Sort (group, value) pairs and scan the runs; values of up to 4 bytes ride in one
            // word with their group (8 bytes a point, not 16).
            if (es <= 4) {
                std::vector<std::uint64_t> votes;
                votes.reserve(n);
                const bool is_signed = type_letter(f.datatype) == 'I';
                for (std::size_t i = 0; i < n; ++i) {
                    if (group[i] != kNoGroup) {
                        // value_as_double is exact for these types; signed values are offset
                        // so that the word orders as the value does.
                        const double v = value_as_double(src + i * step + off, f.datatype);
                        const auto ordered = static_cast<std::uint32_t>(
                            is_signed ? static_cast<std::int64_t>(v) + (std::int64_t{1} << 31)
                                      : static_cast<std::int64_t>(v));
                        votes.push_back((std::uint64_t{group[i]} << 32) | ordered);
                    }
                }
                std::sort(votes.begin(), votes.end());
                for_each_mode(
                    votes, [&](std::uint64_t w) { return static_cast<std::uint32_t>(w >> 32); },
                    [&](std::uint32_t g, std::uint64_t w) {
                        const auto ordered = static_cast<std::uint32_t>(w);
                        const double v =
                            is_signed ? static_cast<double>(static_cast<std::int64_t>(ordered) -
                                                            (std::int64_t{1} << 31))
                                      : static_cast<double>(ordered);
                        store_integer(v, f.datatype, dst + g * step + off);
                    });
                continue;
            }
            std::vector<std::pair<std::uint32_t, double>> votes;
            votes.reserve(n);
            for (std::size_t i = 0; i < n; ++i) {
                if (group[i] != kNoGroup) {
                    votes.emplace_back(group[i], value_as_double(src + i * step + off, f.datatype));
                }
            }
            std::sort(votes.begin(), votes.end());
            for_each_mode(
                votes, [](const auto& v) { return v.first; },
                [&](std::uint32_t g, const auto& v) {
                    store_integer(v.second, f.datatype, dst + g * step + off);
                });
        }
    }
    update_is_dense(out);
    return out;
}

}  // namespace pc::io
