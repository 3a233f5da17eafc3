#pragma once
// Blobs with known content for the I/O tests.

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <pc/io/blob.h>

namespace pc::test {

struct FieldSpec {
    std::string name;
    std::uint8_t datatype;
    std::uint32_t count = 1;
};

/// A blob with `fields` laid out back to back and `n` points (width n, height 1), filled by
/// fill(point, field index, element) -> double, stored in the field's type.
template <class Fill>
io::Blob make_blob(const std::vector<FieldSpec>& fields,
                   std::size_t width,
                   std::size_t height,
                   Fill fill) {
    io::Blob b;
    std::size_t step = 0;
    for (const auto& s : fields) {
        pcl::PCLPointField f;
        f.name = s.name;
        f.offset = static_cast<std::uint32_t>(step);
        f.datatype = s.datatype;
        f.count = s.count;
        b.cloud.fields.push_back(f);
        step += io::type_size(s.datatype) * s.count;
    }
    b.cloud.width = static_cast<std::uint32_t>(width);
    b.cloud.height = static_cast<std::uint32_t>(height);
    b.cloud.point_step = static_cast<std::uint32_t>(step);
    b.cloud.row_step = static_cast<std::uint32_t>(step * width);
    const std::size_t n = width * height;
    b.cloud.data.assign(n * step, 0);
    for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t k = 0; k < fields.size(); ++k) {
            const auto& f = b.cloud.fields[k];
            const std::size_t es = io::type_size(f.datatype);
            for (std::uint32_t c = 0; c < f.count; ++c) {
                std::uint8_t* p = &b.cloud.data[i * step + f.offset + c * es];
                const double v = fill(i, k, c);
                switch (f.datatype) {
                    case pcl::PCLPointField::INT8: {
                        auto x = static_cast<std::int8_t>(v);
                        std::memcpy(p, &x, 1);
                        break;
                    }
                    case pcl::PCLPointField::UINT8: {
                        auto x = static_cast<std::uint8_t>(v);
                        std::memcpy(p, &x, 1);
                        break;
                    }
                    case pcl::PCLPointField::INT16: {
                        auto x = static_cast<std::int16_t>(v);
                        std::memcpy(p, &x, 2);
                        break;
                    }
                    case pcl::PCLPointField::UINT16: {
                        auto x = static_cast<std::uint16_t>(v);
                        std::memcpy(p, &x, 2);
                        break;
                    }
                    case pcl::PCLPointField::INT32: {
                        auto x = static_cast<std::int32_t>(v);
                        std::memcpy(p, &x, 4);
                        break;
                    }
                    case pcl::PCLPointField::UINT32: {
                        auto x = static_cast<std::uint32_t>(v);
                        std::memcpy(p, &x, 4);
                        break;
                    }
                    case pcl::PCLPointField::INT64: {
                        auto x = static_cast<std::int64_t>(v);
                        std::memcpy(p, &x, 8);
                        break;
                    }
                    case pcl::PCLPointField::UINT64: {
                        auto x = static_cast<std::uint64_t>(v);
                        std::memcpy(p, &x, 8);
                        break;
                    }
                    case pcl::PCLPointField::FLOAT32: {
                        auto x = static_cast<float>(v);
                        std::memcpy(p, &x, 4);
                        break;
                    }
                    default:
                        std::memcpy(p, &v, 8);
                        break;
                }
            }
        }
    }
    io::update_is_dense(b);
    return b;
}

/// x y z F 4 points with values from a seeded generator.
inline io::Blob random_xyz(std::size_t n, unsigned seed = 1) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-10, 10);
    return make_blob({{"x", pcl::PCLPointField::FLOAT32},
                      {"y", pcl::PCLPointField::FLOAT32},
                      {"z", pcl::PCLPointField::FLOAT32}},
                     n, 1, [&](std::size_t, std::size_t, std::uint32_t) { return u(rng); });
}

/// Stores the raw 32-bit pattern `bits` into element 0 of field `k` of point `i`.
inline void set_bits(io::Blob& b, std::size_t i, std::size_t k, std::uint32_t bits) {
    std::memcpy(&b.cloud.data[i * b.cloud.point_step + b.cloud.fields[k].offset], &bits, 4);
}

}  // namespace pc::test
