#include <cmath>
#include <limits>

#include <pc/core/stats.h>
#include <pc/io/info.h>

namespace pc::io {

std::string colour_fields(const Blob& blob) {
    for (const char* packed : {"rgb", "rgba"}) {
        if (find_field(blob, packed) != nullptr) {
            return packed;
        }
    }
    for (const auto& trio : {std::array<const char*, 3>{"red", "green", "blue"},
                             std::array<const char*, 3>{"r", "g", "b"}}) {
        if (find_field(blob, trio[0]) && find_field(blob, trio[1]) && find_field(blob, trio[2])) {
            return std::string(trio[0]) + " " + trio[1] + " " + trio[2];
        }
    }
    return "";
}

CloudInfo describe(const Blob& blob, bool percentiles) {
    CloudInfo info;
    const auto& c = blob.cloud;
    info.points = blob.size();
    info.width = c.width;
    info.height = c.height;
    info.organised = c.height > 1;
    info.is_dense = c.is_dense;
    info.viewpoint = blob.viewpoint;
    info.colour = colour_fields(blob);
    const std::size_t n = blob.size();
    const std::uint8_t* data = c.data.data();
    std::vector<double> values;  // one element's values, for its percentiles
    for (const auto& f : c.fields) {
        FieldInfo fi;
        fi.name = f.name;
        fi.type = type_letter(f.datatype);
        fi.size = type_size(f.datatype);
        fi.count = f.count;
        fi.packed_colour = (f.name == "rgb" || f.name == "rgba") && fi.size == 4;
        if (f.name != "_" && !fi.packed_colour) {
            for (std::uint32_t e = 0; e < f.count; ++e) {
                ElementStats s;
                s.min = std::numeric_limits<double>::infinity();
                s.max = -s.min;
                double sum = 0, mean = 0, m2 = 0;  // Welford for m2: no cancellation on offsets
                const std::uint8_t* p = data + f.offset + e * fi.size;
                if (percentiles) {
                    values.resize(n);
                }
                for (std::size_t i = 0; i < n; ++i, p += c.point_step) {
                    const double v = value_as_double(p, f.datatype);
                    if (percentiles) {
                        values[i] = v;
                    }
                    if (std::isfinite(v)) {
                        s.min = std::min(s.min, v);
                        s.max = std::max(s.max, v);
                        ++s.finite;
                        sum += v;
                        const double d = v - mean;
                        mean += d / static_cast<double>(s.finite);
                        m2 += d * (v - mean);
                    }
                }
                if (s.finite == 0) {
                    s.min = s.max = std::nan("");
                }
                s.mean = s.finite ? sum / static_cast<double>(s.finite) : std::nan("");
                s.stddev = s.finite ? std::sqrt(m2 / static_cast<double>(s.finite)) : std::nan("");
                if (percentiles && s.finite) {
                    s.p10 = percentile_of_finite(values, 10);
                    s.median = percentile_of_finite(values, 50);
                    s.p90 = percentile_of_finite(values, 90);
                }
                fi.stats.push_back(s);
            }
        }
        info.fields.push_back(std::move(fi));
    }
    const pcl::PCLPointField* axes[3] = {find_field(blob, "x"), find_field(blob, "y"),
                                         find_field(blob, "z")};
    info.has_xyz = axes[0] && axes[1] && axes[2];
    if (info.has_xyz) {
        info.bbox_min.fill(std::numeric_limits<double>::infinity());
        info.bbox_max.fill(-std::numeric_limits<double>::infinity());
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint8_t* p = data + i * c.point_step;
            double v[3];
            bool finite = true;
            for (int a = 0; a < 3; ++a) {
                v[a] = value_as_double(p + axes[a]->offset, axes[a]->datatype);
                finite = finite && std::isfinite(v[a]);
            }
            if (!finite) {
                ++info.non_finite_points;
                continue;
            }
            for (int a = 0; a < 3; ++a) {
                info.bbox_min[a] = std::min(info.bbox_min[a], v[a]);
                info.bbox_max[a] = std::max(info.bbox_max[a], v[a]);
            }
        }
        if (info.non_finite_points == n) {
            info.bbox_min.fill(std::nan(""));
            info.bbox_max.fill(std::nan(""));
        }
    }
    return info;
}

}  // namespace pc::io
