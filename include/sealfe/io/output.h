// Output: the output directory and the summary.json / used_parameters.prm files of a run,
// written atomically (a failed run never leaves a half-written or stale-looking result).
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>
#include <utility>

namespace sealfe
{
namespace output
{
/// Create `directory` (and parents) if needed; throws std::runtime_error if impossible.
void make_directory(const std::string &directory);

/// Write `text` to `directory/name` through a temporary file and a rename.
void write_file_atomically(const std::string &directory, const std::string &name,
                           const std::string &text);

/// summary.json (written atomically; check_finite first, as nlohmann::json writes nan as null).
void write_summary(const std::string &directory, const nlohmann::json &summary);

/// used_parameters.prm: every entry, with the values used, in ParameterHandler syntax.
void write_used_parameters(const std::string &directory, const dealii::ParameterHandler &prm);

/// The files of one run, written into a hidden staging directory inside the output directory and
/// published by renames once the run succeeded and its results were checked (summary.json last):
/// the output directory holds one complete run or the previous one, never a mixture marked
/// complete. Creating the staging directory first also checks that the output directory can be
/// written before any work is done.
class StagedOutput
{
public:
  /// Creates `directory` if needed and `directory/.sealfe-partial-<tag>`; throws with the reason
  /// if either cannot be created (a file in the way, no permission, an empty name).
  StagedOutput(const std::string &directory, const std::string &tag);
  /// Unless published: removes the staging directory, and the output directory if this run
  /// created it and it is still empty.
  ~StagedOutput();
  StagedOutput(const StagedOutput &) = delete;
  StagedOutput &operator=(const StagedOutput &) = delete;

  /// Where the run writes its files.
  const std::string &path() const { return staging; }

  /// Moves every staged file into the output directory: the previous summary.json is removed
  /// first, then the files are renamed, used_parameters.prm and summary.json last. SIGINT and
  /// SIGTERM are held meanwhile (interrupt::HoldSignals).
  void publish();

private:
  std::string directory, staging;
  bool created_directory = false, published = false;
};

/// `text` with the staging directory of the run in progress replaced by its output directory:
/// for messages and summary entries that name files (they are read after publication).
std::string published_name(const std::string &text);

/// Thrown by a run that stopped part-way but has results worth keeping (the rows of a transient
/// up to where the integrator gave up, the finished points of a table): the driver publishes the
/// staged files with `summary` (which says `"complete": false` and why), then reports the error
/// and exits non-zero.
class IncompleteRun : public std::runtime_error
{
public:
  IncompleteRun(const std::string &message, nlohmann::json summary)
      : std::runtime_error(message), summary(std::move(summary))
  {
  }
  nlohmann::json summary;
};

/// Throws std::runtime_error naming the first non-finite number in `summary` and where it is
/// (e.g. "force_z = nan"): nlohmann::json would write it as null, a silent wrong answer.
void check_finite(const nlohmann::json &summary);

/// Throws std::runtime_error naming the first nan or inf in a data row of a CSV file (a row whose
/// fields include a "failed..." status is a reported failure and exempt, so is an error-estimate
/// column "err_..." (nan: no estimate); an empty field is a documented missing value).
void check_finite_csv(const std::string &file);
} // namespace output
} // namespace sealfe
