// Strict reading of numbers typed by a user (dynamesh-cli, the viewer's command line and its
// saved settings): the whole text must be one finite number in plain decimal notation, and
// whole numbers must fit the range asked for. Nothing wraps ("4294967297" is not 1), nothing
// is partially read ("12abc"), and "inf", "nan" and the empty string are refused.
#pragma once

#include <optional>
#include <string>

namespace dynamesh {

std::optional<double> parse_finite_number(const std::string& text);
std::optional<long long> parse_whole_number(const std::string& text, long long min,
                                            long long max);

}  // namespace dynamesh
