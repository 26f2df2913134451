// Numbers and lists of numbers typed into a parameter file: one parser for a finite number and
// one for a list "a, b, c" or a range "start : stop : count", each failing with one line that
// names the entry and what was typed.
#pragma once

#include <string>
#include <vector>

namespace sealfe::numerics
{
/// The finite number `text` (surrounding blanks allowed); std::runtime_error
/// "<entry> is not a finite number (got '<text>')" otherwise.
double parse_finite_number(const std::string &text, const std::string &entry);

/// A list "a, b, c" or a range "start : stop : count" (count equally spaced values, both ends
/// included), sorted ascending, without repeats; an empty text gives an empty list.
/// std::runtime_error naming `entry` for anything else.
std::vector<double> parse_number_list(const std::string &text, const std::string &entry);

/// The shortest text that reads back as exactly `value` ("0.0355", "1e-06"): how a default held
/// in a class's member initialiser is declared as a prm default without writing it twice.
std::string to_prm_string(double value);

} // namespace sealfe::numerics
