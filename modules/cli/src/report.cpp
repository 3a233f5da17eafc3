#include <algorithm>
#include <charconv>
#include <new>
#include <sstream>

#include <pc/cli/report.h>
#include <pc/core/error.h>
#include <pc/io/read.h>

namespace pc::cli {

namespace {

using nlohmann::ordered_json;

/// An option's text as JSON: numbers as numbers, true/false as booleans, "off" and "" as null.
ordered_json parameter_value(const std::string& text) {
    if (text == "true" || text == "false") {
        return text == "true";
    }
    if (text.empty() || text == "off") {
        return nullptr;
    }
    double v = 0;
    const char* end = text.data() + text.size();
    const auto r = std::from_chars(text.data(), end, v);
    if (r.ec == std::errc{} && r.ptr == end) {
        return v;
    }
    return text;
}

constexpr std::size_t kShortList = 8;

bool scalar(const ordered_json& v) { return !v.is_object() && !v.is_array(); }

/// Appends the table cells of `v` under `key` (see format_rows).
void flatten(const std::string& key,
             const ordered_json& v,
             bool markdown,
             std::vector<std::pair<std::string, ordered_json>>& out) {
    if (scalar(v)) {
        out.emplace_back(key, v);
        return;
    }
    const std::string prefix = key.empty() ? "" : key + ".";
    if (v.is_object()) {
        for (const auto& [k, x] : v.items()) {
            if (!(markdown && key.empty() &&
                  (k == "parameters" || k == "tool" || k == "version"))) {
                flatten(prefix + k, x, markdown, out);
            }
        }
        return;
    }
    bool strings = true, numbers = true, named = true;
    for (const auto& x : v) {
        strings = strings && x.is_string();
        numbers = numbers && x.is_number();
        named = named && x.is_object() && !x.empty() && x.begin()->is_string();
    }
    if (strings) {  // warnings: one cell
        std::string joined;
        for (const auto& x : v) {
            joined += (joined.empty() ? "" : "; ") + x.get<std::string>();
        }
        out.emplace_back(key, joined);
    } else if (numbers && v.size() <= kShortList) {
        for (std::size_t i = 0; i < v.size(); ++i) {
            out.emplace_back(prefix + std::to_string(i), v[i]);
        }
    } else if (named) {
        for (const auto& x : v) {
            ordered_json rest = x;
            const std::string name = x.begin()->get<std::string>();
            rest.erase(x.begin().key());
            flatten(prefix + name, rest, markdown, out);
        }
    }
}

std::string cell_text(const ordered_json& v) {
    if (v.is_null()) {
        return "";
    }
    if (v.is_string()) {
        return v.get<std::string>();
    }
    if (v.is_number_float()) {
        return format_number(v.get<double>());
    }
    return v.dump();
}

std::string markdown_cell(std::string s) {
    for (std::size_t at = 0; (at = s.find('|', at)) != std::string::npos; at += 2) {
        s.replace(at, 1, "\\|");
    }
    return s;
}

std::string table(const std::vector<Row>& rows, bool markdown) {
    std::vector<std::string> columns;
    std::vector<std::vector<std::pair<std::string, ordered_json>>> cells(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r) {
        flatten("", rows[r], markdown, cells[r]);
        for (const auto& [key, value] : cells[r]) {
            if (std::find(columns.begin(), columns.end(), key) == columns.end()) {
                columns.push_back(key);
            }
        }
    }
    std::ostringstream out;
    const std::string sep = markdown ? " | " : ",";
    const auto line = [&](const std::vector<std::string>& values) {
        out << (markdown ? "| " : "");
        for (std::size_t c = 0; c < values.size(); ++c) {
            out << (c ? sep : "") << (markdown ? markdown_cell(values[c]) : csv_cell(values[c]));
        }
        out << (markdown ? " |\n" : "\n");
    };
    line(columns);
    if (markdown) {
        out << '|';
        for (std::size_t c = 0; c < columns.size(); ++c) {
            out << " --- |";
        }
        out << '\n';
    }
    for (const auto& row : cells) {
        std::vector<std::string> values(columns.size());
        for (const auto& [key, value] : row) {
            const auto at = std::find(columns.begin(), columns.end(), key) - columns.begin();
            values[static_cast<std::size_t>(at)] = cell_text(value);
        }
        line(values);
    }
    return out.str();
}

}  // namespace

constexpr const char* kFormatFlags[] = {"jsonl", "csv", "markdown", "text", "plain"};

Report::Report(Tool& tool, std::string plain_key) : plain_key_(std::move(plain_key)) {
    tool.flag("jsonl", &jsonl_, "JSON Lines: one report object a line");
    tool.flag("csv", &csv_, "CSV: one row an input (nested keys as a.b columns)");
    tool.flag("markdown", &markdown_, "a markdown table, one row an input");
    tool.flag("text", &text_,
              "'key value' lines (nested keys as a.b), a blank line between inputs");
    if (!plain_key_.empty()) {
        tool.flag("plain", &plain_, "print only the " + plain_key_ + " (one line an input)");
    }
}

RowFormat Report::format() const {
    if (jsonl_ + csv_ + markdown_ + text_ + plain_ > 1) {
        throw InvalidArgument("--jsonl, --csv, --markdown, --text and --plain exclude each other");
    }
    return jsonl_      ? RowFormat::kJsonLines
           : csv_      ? RowFormat::kCsv
           : markdown_ ? RowFormat::kMarkdown
           : text_     ? RowFormat::kText
           : plain_    ? RowFormat::kPlain
                       : RowFormat::kJson;
}

Row report_header(const Streams& io) {
    ordered_json parameters = ordered_json::object();
    for (const auto& [name, text] : io.parameters()) {
        if (std::find(std::begin(kFormatFlags), std::end(kFormatFlags), name) ==
            std::end(kFormatFlags)) {
            parameters[name] = parameter_value(text);
        }
    }
    return {{"tool", io.tool()}, {"version", version()}, {"parameters", parameters}};
}

std::string format_rows(const std::vector<Row>& rows,
                        RowFormat format,
                        const std::string& plain_key) {
    std::string out;
    switch (format) {
        case RowFormat::kJson:
            return (rows.size() == 1 ? rows[0] : ordered_json(rows)).dump(1) + "\n";
        case RowFormat::kJsonLines:
            for (const auto& r : rows) {
                out += r.dump() + "\n";
            }
            return out;
        case RowFormat::kCsv:
            return table(rows, false);
        case RowFormat::kMarkdown:
            return table(rows, true);
        case RowFormat::kText:
            for (std::size_t r = 0; r < rows.size(); ++r) {
                std::vector<std::pair<std::string, ordered_json>> cells;
                flatten("", rows[r], false, cells);
                out += r ? "\n" : "";
                for (const auto& [key, value] : cells) {
                    out += key + " " + cell_text(value) + "\n";
                }
            }
            return out;
        case RowFormat::kPlain:
            for (const auto& r : rows) {
                out += (r.contains(plain_key) ? cell_text(r[plain_key]) : "") + "\n";
            }
            return out;
    }
    return out;
}

void Report::each(Streams& io,
                  const std::vector<std::string>& inputs,
                  const std::function<Row(const std::string& path)>& measure) const {
    const RowFormat fmt = format();
    const Row header = report_header(io);
    std::vector<Row> rows;
    std::size_t failed = 0;
    for (const std::string& path : inputs) {
        Row row{{"input", io::display_name(path)}};
        row.update(header);
        try {
            Row body = measure(path);
            std::vector<std::string> warnings;
            if (body.contains("warnings")) {
                warnings = body["warnings"].get<std::vector<std::string>>();
                body.erase("warnings");
            }
            row.update(body);
            row["warnings"] = warnings;
            for (const auto& w : warnings) {
                io.warn(inputs.size() > 1 ? row["input"].get<std::string>() + ": " + w : w);
            }
        } catch (const InvalidArgument&) {
            throw;
        } catch (const std::exception& e) {
            // Readers name the file; a step's error may not.
            const std::string what =
                naming_input(row["input"].get<std::string>(),
                             dynamic_cast<const std::bad_alloc*>(&e) ? "out of memory" : e.what());
            io.fail(what);
            row.erase("parameters");
            row["error"] = what;
            ++failed;
        }
        rows.push_back(std::move(row));
    }
    if (failed < rows.size()) {  // when every input failed, no report: only the error lines
        io.write_text(format_rows(rows, fmt, plain_key_));
    }
}

}  // namespace pc::cli
