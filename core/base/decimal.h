// core/base/decimal.h — strict decimal numbers, the one way the command line reads a number
// (registry/cli.cpp: sizes, counts, --threshold; core/technique/technique.cpp: --param values).
//
// Accepted: an optional sign, decimal digits with an optional decimal point, and an optional
// exponent ("42", "-0.5", ".5", "2.", "1e-3"). Refused: hexadecimal ("0x10", "0x0.8"), inf and
// nan, leading or trailing spaces, anything after the number ("0.5abc"), and values outside
// the range of a double. std::stod accepts all of those, which is why it is not used.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace sl {

// The value of `text`, or std::nullopt when it is not a finite decimal number as above.
std::optional<double> parseDecimal(std::string_view text);

// `value` with exactly `digits` decimals ("%.*f": 2.345 -> "2.35" at 2), the one way figures,
// tables and reports print a fixed-point number.
std::string fixedDecimals(double value, int digits);

// The value of `text` when it is an optional sign and decimal digits only (no point, no
// exponent) and fits a long long; std::nullopt otherwise.
std::optional<long long> parseWholeNumber(std::string_view text);

}  // namespace sl
