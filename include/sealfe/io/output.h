// Output: the output directory and the summary.json / used_parameters.prm files of a run,
// written atomically (a failed run never leaves a half-written or stale-looking result).
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <string>

namespace sealfe
{
namespace output
{
/// Create `directory` (and parents) if needed; throws std::runtime_error if impossible.
void make_directory(const std::string &directory);

/// Write `text` to `directory/name` through a temporary file and a rename.
void write_file_atomically(const std::string &directory, const std::string &name,
                           const std::string &text);

/// Remove a previous summary.json so that a failing run cannot be mistaken for a good one
/// (called only after the inputs were validated and the run is about to overwrite results).
void write_summary(const std::string &directory, const nlohmann::json &summary);

/// used_parameters.prm: every entry, with the values used, in ParameterHandler syntax.
void write_used_parameters(const std::string &directory, const dealii::ParameterHandler &prm);
} // namespace output
} // namespace sealfe
