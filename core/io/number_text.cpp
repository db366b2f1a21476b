#include "core/io/number_text.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dynamesh {

std::optional<double> parse_finite_number(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) return {};
  return value;
}

std::optional<long long> parse_whole_number(const std::string& text, long long min, long long max) {
  const std::optional<double> value = parse_finite_number(text);
  if (!value || *value != std::floor(*value) ||
      std::abs(*value) > static_cast<double>(kLargestWholeNumber))
    return {};
  const auto n = static_cast<long long>(*value);
  if (n < min || n > max) return {};
  return n;
}

double option_number(const std::string& option, const std::string& text) {
  const std::optional<double> value = parse_finite_number(text);
  if (!value) throw std::invalid_argument(option + " expects a number, got '" + text + "'");
  return *value;
}

long long option_whole_number(const std::string& option, const std::string& text, long long min,
                              long long max) {
  if (const std::optional<long long> n = parse_whole_number(text, min, max)) return *n;
  // Refused: say whether it is no whole number at all or one out of the range.
  const std::optional<double> value = parse_finite_number(text);
  if (!value || *value != std::floor(*value))
    throw std::invalid_argument(option + " expects a whole number, got '" + text + "'");
  throw std::invalid_argument(option + " expects a whole number in [" + std::to_string(min) + ", " +
                              std::to_string(max) + "], got '" + text + "'");
}

std::string format_significant(double x, int digits) {
  std::ostringstream out;
  out.precision(digits);
  out << x;
  return out.str();
}

std::string format_point(const Vec3& p) {
  return '(' + format_significant(p.x(), 6) + ", " + format_significant(p.y(), 6) + ", " +
         format_significant(p.z(), 6) + ')';
}

std::string format_point(const Vec2& p) {
  return '(' + format_significant(p.x(), 6) + ", " + format_significant(p.y(), 6) + ')';
}

}  // namespace dynamesh
