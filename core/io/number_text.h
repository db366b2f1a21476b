// Strict reading of numbers typed by a user (dynamesh-cli, the viewer's command line and its
// saved settings): the whole text must be one finite number in plain decimal notation, and
// whole numbers must fit the range asked for. Nothing wraps ("4294967297" is not 1), nothing
// is partially read ("12abc"), and "inf", "nan" and the empty string are refused. And the one way
// numbers are written into messages and saved settings.
#pragma once

#include <optional>
#include <string>

#include "core/geometry/vector_types.h"

namespace dynamesh {

// The largest whole number read: beyond 2^53 (~9.007e15) doubles skip whole numbers, and no
// option needs that much.
inline constexpr long long kLargestWholeNumber = 9'000'000'000'000'000LL;

std::optional<double> parse_finite_number(const std::string& text);
std::optional<long long> parse_whole_number(const std::string& text, long long min, long long max);

// A command-line option's value read as above, or std::invalid_argument with the one line both
// programs (dynamesh-cli run, the viewer) print for it:
//   "--k expects a number, got 'x'"
//   "--steps expects a whole number, got '1.5'"
//   "--steps expects a whole number in [1, 10000000], got '0'"
double option_number(const std::string& option, const std::string& text);
long long option_whole_number(const std::string& option, const std::string& text, long long min,
                              long long max);

// `x` with `digits` significant digits, in the shortest of fixed and scientific notation (the
// stream's default): messages stay short for any magnitude, where std::to_string's fixed
// notation printed a 300-digit number for 1e300.
std::string format_significant(double x, int digits);

// "(0.5, -1, 2)" with 6 significant digits: where a message says a point is.
std::string format_point(const Vec3& p);
std::string format_point(const Vec2& p);

}  // namespace dynamesh
