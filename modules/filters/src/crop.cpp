#include <pc/core/error.h>
#include <pc/filters/crop.h>

namespace pc::filters {

void CropParams::validate() const {
    for (int a = 0; a < 3; ++a) {
        if (!(min[a] <= max[a])) {
            throw InvalidArgument("crop: min must be <= max on every axis, got " +
                                  format_number(min[a]) + " > " + format_number(max[a]) +
                                  " on axis " + "xyz"[a]);
        }
    }
}

CropResult crop(const XyzView& cloud, const CropParams& params) {
    params.validate();
    CropResult r;
    for (std::uint32_t i = 0; i < cloud.size; ++i) {
        const pcl::PointXYZ p = cloud[i];
        const double v[3] = {p.x, p.y, p.z};
        bool inside = is_finite(p);
        for (int a = 0; a < 3 && inside; ++a) {
            inside = v[a] >= params.min[a] && v[a] <= params.max[a];
        }
        if (inside != params.invert) {
            r.kept.push_back(i);
        }
    }
    return r;
}

}  // namespace pc::filters
