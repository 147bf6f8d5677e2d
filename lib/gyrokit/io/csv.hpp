#pragma once
// CSV (RFC 4180) fields and lines, written and read in one place: tables, screening result
// files and bearing tables all go through these.

#include <string>
#include <vector>

namespace gyrokit {

// A field as written: quoted only where it holds a comma, a quote or a line break; quotes doubled.
std::string csv_field(const std::string& s);
// A record: the fields joined by commas, with '\n'.
std::string csv_line(const std::vector<std::string>& cells);
// A record read back: quoted fields unquoted; an unterminated quote throws gyrokit::Error.
std::vector<std::string> parse_csv_line(const std::string& line);

}  // namespace gyrokit
