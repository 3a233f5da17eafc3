#include <cmath>
#include <filesystem>
#include <limits>

#include <pc/charts/panel.h>
#include <pc/core/error.h>

namespace pc::charts {

namespace {

const char* kind_name(Panel::Kind k) {
    return k == Panel::Kind::kHistogram ? "histogram" : k == Panel::Kind::kBox ? "box" : "bars";
}

/// The cells of one CSV line (RFC 4180 quoting); pc::IoError for an unclosed quote.
std::vector<std::string> cells(const std::string& line, std::size_t number) {
    std::vector<std::string> out(1);
    bool quote = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quote) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
                out.back() += '"';
                ++i;
            } else if (c == '"') {
                quote = false;
            } else {
                out.back() += c;
            }
        } else if (c == '"') {
            quote = true;
        } else if (c == ',') {
            out.emplace_back();
        } else if (c != '\r') {
            out.back() += c;
        }
    }
    if (quote) {
        throw IoError("line " + std::to_string(number) + ": a quote is not closed");
    }
    return out;
}

}  // namespace

std::string panels_csv(const std::vector<Panel>& panels) {
    std::string out = "panel,kind,xlabel,name,value\n";
    for (const Panel& p : panels) {
        const std::string head =
            csv_cell(p.title) + "," + kind_name(p.kind) + "," + csv_cell(p.xlabel);
        for (std::size_t k = 0; k < p.values.size(); ++k) {
            for (std::size_t j = 0; j < p.values[k].size(); ++j) {
                const std::size_t n = p.kind == Panel::Kind::kBars ? j : k;
                const double v = p.values[k][j];
                out += head + "," + csv_cell(n < p.names.size() ? p.names[n] : "") + "," +
                       (std::isfinite(v) ? format_number(v) : "") + "\n";
            }
        }
    }
    return out;
}

std::vector<Panel> parse_panels(const std::string& csv) {
    std::vector<Panel> panels;
    std::size_t start = 0, number = 0;
    while (start < csv.size()) {
        std::size_t end = csv.find('\n', start);
        end = end == std::string::npos ? csv.size() : end;
        const std::string line = csv.substr(start, end - start);
        start = end + 1;
        ++number;
        if (line.empty() || line == "\r" || number == 1) {
            if (number == 1 && line.rfind("panel,kind,xlabel,name,value", 0) != 0) {
                throw IoError("line 1: expected the header panel,kind,xlabel,name,value");
            }
            continue;
        }
        const std::vector<std::string> c = cells(line, number);
        if (c.size() != 5) {
            throw IoError("line " + std::to_string(number) + ": expected 5 cells, found " +
                          std::to_string(c.size()));
        }
        Panel::Kind kind;
        if (c[1] == "histogram") {
            kind = Panel::Kind::kHistogram;
        } else if (c[1] == "box") {
            kind = Panel::Kind::kBox;
        } else if (c[1] == "bars") {
            kind = Panel::Kind::kBars;
        } else {
            throw IoError("line " + std::to_string(number) +
                          ": kind must be histogram, box or bars, got '" + c[1] + "'");
        }
        double v = std::numeric_limits<double>::quiet_NaN();
        if (!c[4].empty()) {
            std::size_t used = 0;
            try {
                v = std::stod(c[4], &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != c[4].size()) {
                throw IoError("line " + std::to_string(number) + ": '" + c[4] +
                              "' is not a number");
            }
        }
        if (panels.empty() || panels.back().title != c[0] || panels.back().kind != kind) {
            panels.push_back({kind, c[0], c[2], {}, {}});
        }
        Panel& p = panels.back();
        if (kind == Panel::Kind::kBox) {
            std::size_t k = 0;
            while (k < p.names.size() && p.names[k] != c[3]) {
                ++k;
            }
            if (k == p.names.size()) {
                p.names.push_back(c[3]);
                p.values.emplace_back();
            }
            p.values[k].push_back(v);
        } else {
            if (p.values.empty()) {
                p.values.emplace_back();
            }
            p.values[0].push_back(v);
            if (kind == Panel::Kind::kBars) {
                p.names.push_back(c[3]);
            }
        }
    }
    return panels;
}

std::string csv_path(const std::string& png_path) {
    return std::filesystem::path(png_path).replace_extension(".csv").string();
}

}  // namespace pc::charts
