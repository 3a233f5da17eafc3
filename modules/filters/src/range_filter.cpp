#include <algorithm>
#include <charconv>
#include <cmath>

#include <pc/core/error.h>
#include <pc/filters/range_filter.h>

namespace pc::filters {

namespace {

double bound(const std::string& limit, const std::string& text, double none) {
    if (text.empty()) {
        return none;
    }
    double v = 0;
    const char* b = text.data();
    const char* e = b + text.size();
    b += (*b == '+');
    const auto r = std::from_chars(b, e, v);
    if (r.ec != std::errc{} || r.ptr != e || std::isnan(v)) {
        throw InvalidArgument("range '" + limit + "': '" + text + "' is not a number");
    }
    return v;
}

Range parse_one(const std::string& limit) {
    const std::string expected =
        "range '" + limit +
        "': expected FIELD[LO:HI] ('(' ')' for open ends, an empty bound for none, '!' before "
        "the bracket to keep what lies outside), e.g. opacity[0.1:] or label![0:0]";
    const std::size_t open = limit.find_first_of("[(");
    const std::size_t colon = limit.find(':', open == std::string::npos ? 0 : open);
    if (open == std::string::npos || colon == std::string::npos || limit.size() < open + 3) {
        throw InvalidArgument(expected);
    }
    const char close = limit.back();
    if (close != ']' && close != ')') {
        throw InvalidArgument(expected);
    }
    Range r;
    r.field = limit.substr(0, open);
    if (!r.field.empty() && r.field.back() == '!') {
        r.negate = true;
        r.field.pop_back();
    }
    if (r.field.empty()) {
        throw InvalidArgument(expected);
    }
    r.lo_open = limit[open] == '(';
    r.hi_open = close == ')';
    r.lo = bound(limit, limit.substr(open + 1, colon - open - 1), r.lo);
    r.hi = bound(limit, limit.substr(colon + 1, limit.size() - colon - 2), r.hi);
    if (r.lo > r.hi) {
        throw InvalidArgument("range '" + limit + "': the lower bound is above the upper");
    }
    return r;
}

/// Whether `v` lies in `r`; for an F 4 field (`as_float`) the bounds are rounded to float first,
/// as the field holds its values: opacity(0.1:] leaves out the points stored as 0.1f.
bool inside(double v, const Range& r, bool as_float) {
    if (!std::isfinite(v)) {
        return false;
    }
    // Rounded here, not in a copy of the Range: GCC 12.2's -O2 vectorizer dropped the rounding
    // of a copied Range's two bounds (right at -O1 and with -fno-tree-vectorize).
    const double lo = as_float ? static_cast<double>(static_cast<float>(r.lo)) : r.lo;
    const double hi = as_float ? static_cast<double>(static_cast<float>(r.hi)) : r.hi;
    const bool above_lo = r.lo_open ? v > lo : v >= lo;
    const bool below_hi = r.hi_open ? v < hi : v <= hi;
    return above_lo && below_hi;
}

}  // namespace

std::vector<Range> parse_ranges(const std::string& text) {
    std::vector<Range> out;
    std::size_t start = 0;
    int depth = 0;
    for (std::size_t i = 0; i <= text.size(); ++i) {
        const char c = i < text.size() ? text[i] : ',';
        depth += (c == '[' || c == '(') - (c == ']' || c == ')');
        if (c == ',' && depth == 0) {
            std::string limit = text.substr(start, i - start);
            limit.erase(0, limit.find_first_not_of(" \t"));
            limit.erase(limit.find_last_not_of(" \t") + 1);
            if (!limit.empty()) {
                out.push_back(parse_one(limit));
            }
            start = i + 1;
        }
    }
    if (out.empty()) {
        throw InvalidArgument("no range given: expected FIELD[LO:HI], e.g. opacity[0.1:]");
    }
    return out;
}

void RangeFilterParams::validate() const {
    if (ranges.empty()) {
        throw InvalidArgument("range_filter: ranges must not be empty");
    }
}

std::vector<std::uint32_t> range_filter(const io::Blob& blob, const RangeFilterParams& params) {
    params.validate();
    // Limits grouped by field, in the order each field first appears.
    struct Group {
        const pcl::PCLPointField* field;
        std::vector<Range> ranges;
    };
    std::vector<Group> groups;
    for (const Range& r : params.ranges) {
        const pcl::PCLPointField* f = io::find_field(blob, r.field);
        if (f == nullptr) {
            throw IoError("no field '" + r.field + "' (the cloud has: " + io::field_names(blob) +
                          ")");
        }
        if ((f->name == "rgb" || f->name == "rgba") && io::type_size(f->datatype) == 4) {
            throw InvalidArgument("'" + f->name +
                                  "' is a packed colour: filter colours with pc_colorfilter");
        }
        if (f->count != 1) {
            throw InvalidArgument("'" + f->name + "' has " + std::to_string(f->count) +
                                  " elements a point; ranges take fields of one");
        }
        auto it = std::find_if(groups.begin(), groups.end(),
                               [&](const Group& g) { return g.field == f; });
        if (it == groups.end()) {
            groups.push_back({f, {}});
            it = groups.end() - 1;
        }
        it->ranges.push_back(r);
    }
    std::vector<std::uint32_t> kept;
    const std::size_t n = blob.size();
    const std::uint8_t* data = blob.cloud.data.data();
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint8_t* p = data + i * blob.cloud.point_step;
        bool pass = true;
        for (const Group& g : groups) {
            const double v = io::value_as_double(p + g.field->offset, g.field->datatype);
            const bool as_float = g.field->datatype == pcl::PCLPointField::FLOAT32;
            bool any = false;
            for (const Range& r : g.ranges) {
                any = any || (inside(v, r, as_float) != r.negate);
            }
            pass = pass && any;
        }
        if (pass) {
            kept.push_back(static_cast<std::uint32_t>(i));
        }
    }
    return kept;
}

}  // namespace pc::filters
