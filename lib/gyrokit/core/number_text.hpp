// Numbers as a user writes them on a command line or in a list: one decimal
// spelling for every front end, so that "0x10", " 5", "1e-310" or "inf" mean the
// same (nothing) everywhere.
#pragma once

#include <optional>
#include <string>

namespace gyrokit {

// A finite decimal number spelled out completely ("2.5", "-1e-3"): no hexadecimal,
// no leading space or '+', no inf or nan, and no subnormal value (below
// 2.2250738585072014e-308 in magnitude: its precision is lost); nullopt otherwise.
std::optional<double> decimal_number(const std::string& text);

// The same, or InputError "OPTION 'TEXT': allowed: ALLOWED" (a subnormal value named as such).
double parse_decimal(const std::string& text, const std::string& option, const std::string& allowed);

}  // namespace gyrokit
