#include <sealfe/numerics/number_lists.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace sealfe::numerics
{
double parse_finite_number(const std::string &text, const std::string &entry)
{
  const std::string s = dealii::Utilities::trim(text);
  char *end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end != s.c_str() + s.size() || !std::isfinite(v))
    throw std::runtime_error(entry + " is not a finite number (got '" + text + "')");
  return v;
}

std::vector<double> parse_number_list(const std::string &text, const std::string &entry)
{
  const auto fail = [&](const std::string &why)
  {
    throw std::runtime_error(entry + " " + why + " (got '" + text +
                             "'); use a list 'a, b, c' or a range 'start : stop : count'");
  };
  const auto number = [&](const std::string &s)
  {
    try
    {
      return parse_finite_number(s, "");
    }
    catch (const std::runtime_error &)
    {
      fail("has '" + dealii::Utilities::trim(s) + "', which is not a finite number");
    }
    return 0.0;
  };

  std::vector<double> values;
  if (dealii::Utilities::trim(text).empty())
    return values;
  if (text.find(':') != std::string::npos)
  {
    // split_string_list drops a trailing empty item: count the separators instead.
    if (std::count(text.begin(), text.end(), ':') != 2)
      fail("is not a range start : stop : count");
    const std::vector<std::string> parts = dealii::Utilities::split_string_list(text, ':');
    if (parts.size() != 3)
      fail("is not a range start : stop : count");
    const double start = number(parts[0]), stop = number(parts[1]), count = number(parts[2]);
    if (count < 1 || count != std::floor(count))
      fail("needs a whole count of at least 1");
    if (count > 100000)
      fail("has a count of " + to_prm_string(count) +
           ", more than the 100000 points a list may have");
    if (count == 1 && start != stop)
      fail("has count 1 but start != stop");
    const unsigned int n = static_cast<unsigned int>(count);
    for (unsigned int i = 0; i < n; ++i)
      values.push_back(n == 1 ? start : start + (stop - start) * i / (n - 1));
  }
  else
  {
    const auto n_items = std::count(text.begin(), text.end(), ',') + 1;
    const std::vector<std::string> items = dealii::Utilities::split_string_list(text, ',');
    if (static_cast<long>(items.size()) != n_items)
      fail("has an empty item");
    for (const std::string &item : items)
      values.push_back(number(item));
  }
  std::sort(values.begin(), values.end());
  for (unsigned int i = 1; i < values.size(); ++i)
    if (values[i] == values[i - 1])
      fail("repeats the value " + to_prm_string(values[i]));
  return values;
}

std::string to_prm_string(const double value)
{
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  std::string text = error == std::errc() ? std::string(buffer, end) : std::to_string(value);
  // "4e+05" -> "4e5", "1e-06" -> "1e-6": the way people type exponents in a prm file
  const auto e = text.find('e');
  if (e != std::string::npos)
  {
    std::string exponent = text.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent.erase(0, exponent.find_first_not_of("+-"));
    exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
    text = text.substr(0, e + 1) + (negative ? "-" : "") + exponent;
  }
  return text;
}

} // namespace sealfe::numerics
