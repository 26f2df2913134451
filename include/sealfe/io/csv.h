// The one CSV convention of every sealfe table (doc/csv.md): a single header line of
// `name [unit]` fields, then data rows of shortest round-trip numbers; no comment lines, so that a
// plain `pandas.read_csv(file)` gives numeric columns with the units in their names.
#pragma once

#include <string>
#include <vector>

namespace sealfe::csv
{
/// The unit of a dimensionless column (ratios, flags 0/1, counts, indices).
inline const std::string dimensionless = "-";

/// One column: a snake_case name and its SI unit (`dimensionless` for pure numbers, empty for a
/// text column, whose header is the bare name).
struct Column
{
  std::string name, unit;
};

/// "name [unit]", or "name" for a text column.
std::string header_field(const Column &column);

/// The header line (no newline).
std::string header(const std::vector<Column> &columns);

/// The shortest text that reads back to the same double (std::to_chars): exact values in the
/// file, the same file whatever the rank count, no precision chosen per writer.
std::string number(double value);

/// `text` made safe as one field: commas become ';', quotes '\'', line breaks spaces.
std::string text_field(const std::string &text);

/// A table built row by row and written in the convention above.
class Writer
{
public:
  /// One field of a row: a number (written by number()), an integer, or text.
  struct Field
  {
    Field(double v) : text(number(v)) {}
    Field(int v) : text(std::to_string(v)) {}
    Field(unsigned int v) : text(std::to_string(v)) {}
    Field(bool v) : text(v ? "1" : "0") {}
    Field(const std::string &v) : text(text_field(v)) {}
    Field(const char *v) : text(text_field(v)) {}
    std::string text;
  };

  explicit Writer(std::vector<Column> columns);

  /// Appends one row; throws std::logic_error unless it has one field per column.
  void add_row(const std::vector<Field> &fields);

  /// The header and the rows, each line ending in '\n'.
  std::string text() const;

  /// Writes text() to directory/name atomically (output::write_file_atomically).
  void write(const std::string &directory, const std::string &name) const;

private:
  std::vector<Column> columns;
  std::string rows;
};
} // namespace sealfe::csv
