#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <pcl/PCLPointCloud2.h>

namespace pc::io {

/// A cloud exactly as read: every field (padding `_` and COUNT > 1 included) in a PCLPointCloud2,
/// plus the PCD VIEWPOINT (tx ty tz qw qx qy qz) so that it survives a pipe.
struct Blob {
    pcl::PCLPointCloud2 cloud;
    std::array<float, 7> viewpoint{0, 0, 0, 1, 0, 0, 0};

    [[nodiscard]] std::size_t size() const {
        return std::size_t{cloud.width} * std::size_t{cloud.height};
    }
};

/// Bytes of one element of a PCLPointField datatype; 0 for an unknown datatype.
[[nodiscard]] std::size_t type_size(std::uint8_t datatype);
/// 'I', 'U' or 'F' for a known datatype, '?' otherwise.
[[nodiscard]] char type_letter(std::uint8_t datatype);
/// The datatype for a PCD TYPE letter and SIZE (I/U: 1,2,4,8; F: 4,8); 0 when the pair is invalid.
[[nodiscard]] std::uint8_t datatype_of(char letter, std::size_t size);

/// The field called `name`, or nullptr.
[[nodiscard]] const pcl::PCLPointField* find_field(const Blob& blob, std::string_view name);

/// The names of the cloud's fields, space-separated ("x y z rgb label"): for pc_info and for
/// messages about a field that is not there.
[[nodiscard]] std::string field_names(const Blob& blob);

/// Reads one element of a field as double (any datatype). `p` points at the element.
[[nodiscard]] double value_as_double(const std::uint8_t* p, std::uint8_t datatype);

/// An empty cloud (width 0, height 1) with the same fields, point_step and viewpoint as `blob`.
[[nodiscard]] Blob empty_like(const Blob& blob);

/// Makes room in `blob.cloud.data` for `points` points of point_step bytes plus one U 4 field
/// each, so that set_field() can append a label without a second copy of the cloud. The readers
/// call it; room that is never written is never touched and costs address space, not memory.
void reserve_points(Blob& blob, std::size_t points);

/// Keeps the points at `indices` (strictly ascending, each < size()), in place: the data is
/// compacted, not copied. The result is unorganised (height 1). Throws pc::Error on a bad index.
void keep_points(Blob& blob, std::span<const std::uint32_t> indices);

/// A new cloud of the points at `indices` (any order, repeats allowed, each < size()), with every
/// field: a subset copied out, the source untouched. Throws pc::Error on a bad index.
[[nodiscard]] Blob copy_points(const Blob& blob, std::span<const std::uint32_t> indices);

/// Appends the points of `from` after those of `to` where both have the same fields (name,
/// offset, datatype, count) and point_step; returns false and leaves `to` as it was otherwise.
/// The result is unorganised (height 1).
bool append_points(Blob& to, const Blob& from);

/// Keeps the points whose flag is set (`keep_set`) or clear (not `keep_set`), one flag per point,
/// in place as keep_points(), with no list of indices (4 bytes a kept point). Throws pc::Error
/// when the flags are not one per point.
void keep_flagged(Blob& blob, std::span<const std::uint8_t> flags, bool keep_set);

/// Sets a `U 4` field `name` from `values` (one per point), in place. An existing U 4 field of
/// that name is overwritten where it sits, so repeated runs of a tool do not stack copies;
/// otherwise the field is appended to each point (dropping an old field of that name from the
/// field list) and the data grows within its capacity when there is room (see reserve_points).
void set_field(Blob& blob, const std::string& name, std::span<const std::uint32_t> values);

/// Removes field `name` (when present) from every point, in place: each point's other bytes move
/// down over it, and the fields after it with them. No copy of the cloud.
void remove_field(Blob& blob, const std::string& name);

/// Recomputes cloud.is_dense as PCL does: true iff every F4/F8 element of every point is finite.
void update_is_dense(Blob& blob);

/// Checks point_step, row_step, data size and field bounds; throws pc::IoError when inconsistent.
void check_layout(const Blob& blob);

}  // namespace pc::io
