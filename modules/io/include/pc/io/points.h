#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <pc/core/cloud.h>
#include <pc/io/blob.h>

namespace pc::io {

/// The x, y, z of every point as float (F 8 and integer coordinates are converted), in order.
/// Throws pc::IoError when x, y or z is missing.
[[nodiscard]] Cloud xyz(const Blob& blob);

/// The x, y, z of every point for algorithms that take an XyzView: the blob's own floats where
/// they are when x, y and z are F 4 (no copy: 16 bytes per point saved against xyz()), a converted
/// copy otherwise. The blob must outlive this object. Throws pc::IoError as xyz() does.
class XyzPoints {
public:
    explicit XyzPoints(const Blob& blob);
    XyzPoints(const XyzPoints&) = delete;
    XyzPoints& operator=(const XyzPoints&) = delete;
    [[nodiscard]] const XyzView& view() const { return view_; }

private:
    Cloud copy_;
    XyzView view_;
};

/// The blob's points for algorithms that may reorder them while they run (those taking
/// XyzRecords&: dbscan, knn_outlier): the blob's own records when x, y, z are consecutive
/// 4-aligned F 4 fields (as PCL and these tools write them), otherwise a converted copy (a pcl
/// cloud, 16 bytes a point) owned by this object. The blob must outlive it and not be resized
/// meanwhile. Throws pc::IoError as xyz() does.
class XyzSortable {
public:
    explicit XyzSortable(Blob& blob);
    XyzSortable(const XyzSortable&) = delete;
    XyzSortable& operator=(const XyzSortable&) = delete;
    [[nodiscard]] XyzRecords& records() { return records_; }

private:
    Cloud copy_;
    XyzRecords records_;
};

/// A colour with channels in [0, 1].
struct Rgb {
    float r = 0, g = 0, b = 0;
};

/// The colour of every point, from packed `rgb`/`rgba` (U 4 or F 4 bits, 0x..RRGGBB) or from
/// separate `red green blue` / `r g b` fields (integer types are divided by 255, reals are taken
/// as 0..1). Throws pc::IoError naming the fields looked for when the cloud has no colour.
[[nodiscard]] std::vector<Rgb> colours(const Blob& blob);

/// The values of integer field `name` (any I/U type, one per point). Throws pc::IoError when the
/// field is missing, not an integer, has COUNT > 1, or holds a value outside 0..4294967295.
[[nodiscard]] std::vector<std::uint32_t> labels(const Blob& blob,
                                                const std::string& name = "label");

/// Marker for points that belong to no group in aggregate().
inline constexpr std::uint32_t kNoGroup = 0xffffffffu;

/// One point per group (groups 0..group_count-1, in that order): real fields averaged (in double),
/// packed `rgb`/`rgba` averaged per channel and rounded, integer fields take the most frequent
/// value (ties: the smallest). Points with group kNoGroup are left out. `_` padding is zeroed.
[[nodiscard]] Blob aggregate(const Blob& blob,
                             const std::vector<std::uint32_t>& group,
                             std::uint32_t group_count);

}  // namespace pc::io
