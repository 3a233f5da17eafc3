#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace pc {

/// The narrow view algorithms take: positions only, one per input point, in input order.
/// Non-finite points stay in place (as NaN/Inf) so that indices match the full cloud.
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// Indices into a cloud, ascending unless a function says otherwise.
using Indices = std::vector<std::uint32_t>;

/// True when x, y and z are all finite.
[[nodiscard]] inline bool is_finite(const pcl::PointXYZ& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

/// Read-only x y z of `size` points laid out with a fixed byte stride, without a copy: a pcl
/// cloud's points, or the F 4 x y z fields of a PCD blob where they are (io::xyz_points).
struct XyzView {
    const std::uint8_t* base = nullptr;
    std::size_t stride = 0;  ///< bytes from one point to the next
    std::size_t size = 0;
    std::uint32_t offset[3] = {0, 4, 8};  ///< byte offsets of x, y, z (float) in a point
    /// When set, point i is the laid-out point index[i] (`size` entries): a subset of the points,
    /// or a reordering, still without a copy of their coordinates.
    const std::uint32_t* index = nullptr;

    XyzView() = default;
    explicit XyzView(const Cloud& cloud)
        : base(reinterpret_cast<const std::uint8_t*>(cloud.points.data())),
          stride(sizeof(pcl::PointXYZ)),
          size(cloud.size()) {}

    /// The points idx[0], idx[1], ... of this view (idx must outlive the result).
    /// Not of a view that is itself a subset (std::logic_error): compose the indices instead.
    [[nodiscard]] XyzView subset(std::span<const std::uint32_t> idx) const {
        if (index != nullptr) {
            throw std::logic_error("XyzView::subset of a subset");
        }
        XyzView v = *this;
        v.size = idx.size();
        v.index = idx.data();
        return v;
    }

    /// The bytes of point i's record (its x y z at `offset`).
    [[nodiscard]] const std::uint8_t* record(std::size_t i) const {
        return base + (index != nullptr ? index[i] : i) * stride;
    }

    [[nodiscard]] pcl::PointXYZ operator[](std::size_t i) const {
        const std::uint8_t* p = record(i);
        pcl::PointXYZ q;
        std::memcpy(&q.x, p + offset[0], sizeof(float));
        std::memcpy(&q.y, p + offset[1], sizeof(float));
        std::memcpy(&q.z, p + offset[2], sizeof(float));
        return q;
    }
};

/// The points of a cloud's own memory, which an algorithm taking `XyzRecords&` may reorder while
/// it runs (search::Grid's in-place build): `size` records of `stride` bytes at `base`, each with
/// x, y, z as consecutive floats at byte `offset` (stride and offset multiples of 4, base
/// 4-aligned). Records are moved whole. Functions that only read take an XyzView (view()).
struct XyzRecords {
    std::uint8_t* base = nullptr;
    std::size_t stride = 0;
    std::size_t size = 0;
    std::uint32_t offset = 0;  ///< byte offset of x (y at + 4, z at + 8)

    XyzRecords() = default;
    XyzRecords(std::uint8_t* at,
               std::size_t record_bytes,
               std::size_t count,
               std::uint32_t x_offset)
        : base(at), stride(record_bytes), size(count), offset(x_offset) {}
    /// The points of a pcl cloud (16-byte records, x at 0).
    explicit XyzRecords(Cloud& cloud)
        : base(reinterpret_cast<std::uint8_t*>(cloud.points.data())),
          stride(sizeof(pcl::PointXYZ)),
          size(cloud.size()) {}

    /// Whether x y z can be read as floats in place: stride and offset multiples of 4, x y z
    /// inside a record, base 4-aligned.
    [[nodiscard]] bool aligned() const {
        return stride % 4 == 0 && offset % 4 == 0 && offset + 12 <= stride &&
               reinterpret_cast<std::uintptr_t>(base) % alignof(float) == 0;
    }

    [[nodiscard]] XyzView view() const {
        XyzView v;
        v.base = base;
        v.stride = stride;
        v.size = size;
        v.offset[0] = offset;
        v.offset[1] = offset + 4;
        v.offset[2] = offset + 8;
        return v;
    }
};

}  // namespace pc
