#include <sealfe/io/csv.h>
#include <sealfe/io/output.h>

#include <charconv>
#include <stdexcept>
#include <utility>

namespace sealfe::csv
{
std::string header_field(const Column &column)
{
  return column.unit.empty() ? column.name : column.name + " [" + column.unit + "]";
}

std::string header(const std::vector<Column> &columns)
{
  std::string h;
  for (std::size_t i = 0; i < columns.size(); ++i)
    h += (i ? "," : "") + header_field(columns[i]);
  return h;
}

std::string number(const double value)
{
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::string text_field(const std::string &text)
{
  std::string s;
  for (const char c : text)
    s += (c == ',' ? ';' : (c == '"' ? '\'' : ((c == '\n' || c == '\r') ? ' ' : c)));
  return s;
}

Writer::Writer(std::vector<Column> columns_) : columns(std::move(columns_)) {}

void Writer::add_row(const std::vector<Field> &fields)
{
  if (fields.size() != columns.size())
    throw std::logic_error("csv::Writer: a row of " + std::to_string(fields.size()) +
                           " fields for " + std::to_string(columns.size()) + " columns");
  for (std::size_t i = 0; i < fields.size(); ++i)
    rows += (i ? "," : "") + fields[i].text;
  rows += "\n";
}

std::string Writer::text() const
{
  return header(columns) + "\n" + rows;
}

void Writer::write(const std::string &directory, const std::string &name) const
{
  output::write_file_atomically(directory, name, text());
}
} // namespace sealfe::csv
