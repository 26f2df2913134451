// TableResume: `Resume = true` of `sealfe table` — the finished rows of the previous run in the
// output directory are taken over (after checking it was run with the same parameters), so that
// an interrupted table computes only the points it had not finished.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace sealfe
{
namespace table
{
/// Every entry of `prm` with its value as "Subsection/Entry": value, as recorded in summary.json
/// ("parameters"), except those that cannot change a row: Output directory and Table/Resume.
nlohmann::json recorded_parameters(const dealii::ParameterHandler &prm);

/// Whether two recorded values mean the same: equal after removing blanks, or lists (',' or ':'
/// separated) of the same numbers however written (1e-6 and 0.000001).
bool same_value(const std::string &a, const std::string &b);

/// The finished rows of the previous table in `directory` (the published output directory).
struct PreviousTable
{
  std::map<unsigned int, std::string> rows; ///< point index -> CSV row, as written (no newline)
  bool found = false;                       ///< false: no previous run (everything is computed)
  bool complete = false;                    ///< the previous run had finished every point
};

/// Reads directory/summary.json and the table it names. Throws std::runtime_error with one line
/// if the previous run is not a table, was run with a different value of any recorded parameter
/// (named, with both values), has other columns than `header`, or has a row that does not belong
/// to the plan (`row_prefix[i]`: index, role and operating-point columns of point i, with the
/// trailing comma). No summary.json: found = false.
PreviousTable read_previous(const std::string &directory, const std::string &file,
                            const nlohmann::json &parameters, const std::string &header,
                            const std::vector<std::string> &row_prefix);
} // namespace table
} // namespace sealfe
