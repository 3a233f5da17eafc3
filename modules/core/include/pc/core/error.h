#pragma once

#include <stdexcept>
#include <string>

namespace pc {

/// Base of every error the library throws. Messages follow `<unit>: <what> must <rule>, got
/// <value>`.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A caller gave a bad value (a Params field, an option). The CLI maps it to exit code 2.
class InvalidArgument : public Error {
public:
    using Error::Error;
};

/// Input cannot be opened, parsed or written. The CLI maps it to exit code 1.
class IoError : public Error {
public:
    using Error::Error;
};

/// Shortest text that reads back to the same double ("0.05", not "0.050000000000000003").
[[nodiscard]] std::string format_number(double value);

/// A measured value for people to read: `digits` significant digits ("0.0923", not
/// "0.09228739930133324"; "1235" for 1234.5). Values the user gave are shown with format_number.
[[nodiscard]] std::string format_rounded(double value, int digits = 3);

/// `text` as one CSV cell (RFC 4180): quoted, with quotes doubled, when it holds a comma, a quote
/// or a line break; as it is otherwise.
[[nodiscard]] std::string csv_cell(const std::string& text);

}  // namespace pc
