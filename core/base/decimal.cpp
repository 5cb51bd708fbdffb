#include "core/base/decimal.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <system_error>

namespace sl {
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

// Skips decimal digits from `i`; returns how many there were.
size_t skipDigits(std::string_view text, size_t& i) {
  const size_t start = i;
  while (i < text.size() && isDigit(text[i])) ++i;
  return i - start;
}

// The grammar of the header: [+-] digits [. digits] [(e|E) [+-] digits], at least one digit
// before the exponent. std::from_chars alone would also take "inf" and "nan".
bool isDecimal(std::string_view text) {
  size_t i = 0;
  if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
  size_t digits = skipDigits(text, i);
  if (i < text.size() && text[i] == '.') {
    ++i;
    digits += skipDigits(text, i);
  }
  if (digits == 0) return false;
  if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
    ++i;
    if (i < text.size() && (text[i] == '+' || text[i] == '-')) ++i;
    if (skipDigits(text, i) == 0) return false;
  }
  return i == text.size();
}

// std::from_chars takes no leading '+'.
std::string_view withoutPlus(std::string_view text) {
  return !text.empty() && text[0] == '+' ? text.substr(1) : text;
}

}  // namespace

std::optional<double> parseDecimal(std::string_view text) {
  if (!isDecimal(text)) return std::nullopt;
  const std::string_view digits = withoutPlus(text);
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value,
                                            std::chars_format::general);
  if (error != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::optional<long long> parseWholeNumber(std::string_view text) {
  const std::string_view digits = withoutPlus(text);
  if (digits.empty() || digits == "-") return std::nullopt;
  for (size_t i = digits[0] == '-' ? 1 : 0; i < digits.size(); ++i)
    if (!isDigit(digits[i])) return std::nullopt;
  if (digits.size() != text.size() && digits[0] == '-') return std::nullopt;  // "+-5"
  long long value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  return value;
}

std::string fixedDecimals(double value, int digits) {
  const int length = std::snprintf(nullptr, 0, "%.*f", digits, value);
  std::string text(size_t(std::max(length, 0)), '\0');
  std::snprintf(text.data(), text.size() + 1, "%.*f", digits, value);
  return text;
}

}  // namespace sl
