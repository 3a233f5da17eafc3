#pragma once
// Reports of one row per input (pc_info, pc_count, pc_fruitcount): each row says which input,
// which tool and version, and every parameter as used, so that a batch's rows can be matched to
// their inputs and reproduced. See docs/architecture.md, "Reports".

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <pc/cli/tool.h>

namespace pc::cli {

using Row = nlohmann::ordered_json;

enum class RowFormat {
    kJson,       ///< one input: its object; several: an array of them
    kJsonLines,  ///< one object a line
    kCsv,        ///< a header, then one line a row (nested keys joined by '.')
    kMarkdown,   ///< a table with the CSV's columns, parameters left out
    kText,       ///< `column value` lines, a blank line between rows
    kPlain,      ///< one value a line (`--plain`: the count)
};

/// The text of `rows` in `format`. Table formats (CSV, markdown, text) flatten nested objects
/// into `a.b` columns, short lists of numbers into `a.0 a.1 ...`, lists of strings into one cell
/// joined by "; ", lists of objects that start with a string (the chain's `steps`, pc_info's
/// `fields`) into `a.<that string>.<key>`; other lists (clusters) stay in the JSON formats only.
/// Columns are the union over the rows, in order of first appearance. kPlain writes
/// `plain_key`'s value (empty for a row without it).
[[nodiscard]] std::string format_rows(const std::vector<Row>& rows,
                                      RowFormat format,
                                      const std::string& plain_key = "count");

/// `v` as JSON: the number, or null when it is not finite (JSON has no NaN or infinity).
[[nodiscard]] inline Row json_number(double v) { return std::isfinite(v) ? Row(v) : Row(nullptr); }

/// What every report starts with: `tool`, `version`, `parameters` (every option of the tool as
/// used, its report-format flags left out: numbers as numbers, switches as booleans, "off" as
/// null).
[[nodiscard]] Row report_header(const Streams& io);

/// A report of one row per input, and the flags that choose its format: --jsonl, --csv,
/// --markdown, --text (JSON without any), and --plain when the tool has a plain value.
class Report {
public:
    /// Binds the format flags to `tool`; `plain_key` (pc_count's "count") adds --plain.
    explicit Report(Tool& tool, std::string plain_key = "");
    /// The format chosen; throws pc::InvalidArgument when two flags were given.
    [[nodiscard]] RowFormat format() const;

    /// Runs `measure` on each input and writes one row for each: `input`, `tool`, `version`,
    /// `parameters` (every option of the tool as used, the format flags left out), then what
    /// `measure` returned, then `warnings` (printed on stderr too, prefixed with the input when
    /// there are several). An input that fails (unreadable, malformed) gets a row with `error`
    /// instead and its one line on stderr; the others go on and the run exits 1. When every
    /// input fails, nothing is written. Usage errors (pc::InvalidArgument) stop the run.
    void each(Streams& io,
              const std::vector<std::string>& inputs,
              const std::function<Row(const std::string& path)>& measure) const;

private:
    std::string plain_key_;
    bool jsonl_ = false, csv_ = false, markdown_ = false, text_ = false, plain_ = false;
};

}  // namespace pc::cli
