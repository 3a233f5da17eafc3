#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <pc/io/blob.h>

namespace pc::filters {

/// One limit in PDAL's filters.range syntax: `name[lo:hi]`, `(` `)` for open ends, an empty bound
/// for none (`opacity[0.1:]`), `!` before the bracket to keep what lies outside
/// (`label![0:0]`).
struct Range {
    std::string field;
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    bool lo_open = false, hi_open = false;  ///< `(` / `)`: the bound itself is outside
    bool negate = false;                    ///< `!`: keep the values outside [lo, hi]
};

/// Parses one limit or several separated by commas ("z[0:],label![0:0]"); throws
/// pc::InvalidArgument saying what was expected.
[[nodiscard]] std::vector<Range> parse_ranges(const std::string& text);

/// Parameters of range_filter(): PDAL's rule, limits on one field are ORed, on different fields
/// ANDed.
struct RangeFilterParams {
    std::vector<Range> ranges;
    void validate() const;
};

/// The indices of the points that pass, ascending. Fields must exist and have one element, as
/// any numeric type (packed rgb/rgba refused: use the colour filter); for F 4 fields the bounds
/// are rounded to float first, so `opacity(0.1:]` leaves out a value stored as 0.1f. A non-finite
/// value is outside every range (so a negated range keeps it; PDAL lets NaN pass every range).
/// Throws pc::IoError for a missing field, naming the fields there are.
[[nodiscard]] std::vector<std::uint32_t> range_filter(const io::Blob& blob,
                                                      const RangeFilterParams& params);

}  // namespace pc::filters
