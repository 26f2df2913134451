// CoefficientTable: film coefficients interpolated from a table of finite-element results over a
// grid of operating points (level 1 of doc/reynolds.md, Levels), read from the CSV that `sealfe
// table` writes.
#pragma once

#include <sealfe/film/film_coefficients.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace sealfe
{
/// The operating quantities that identify a row of a coefficient table (SI units). The first
/// seven can be swept by `sealfe table`; all are written to every row, so that a reader can check
/// that a query belongs to the table.
struct OperatingPoint
{
  double rotor_speed = 0;         // rad/s
  double stator_speed = 0;        // rad/s
  double clearance = 0;           // m, C0
  double coning = 0;              // rad, beta
  double tilt = 0;                // rad, gamma (at tilt_angle)
  double pressure_difference = 0; // Pa, po - pi
  double viscosity = 0;           // Pa s
  double tilt_angle = 0;          // rad, psi
  double inner_pressure = 0;      // Pa
  double inner_radius = 0;        // m
  double outer_radius = 0;        // m

  static OperatingPoint of(const FilmThickness &film, const OperatingConditions &conditions);
  /// The film and conditions of this point: `film` and `conditions` with the quantities above
  /// replaced (everything else, e.g. waviness, kept).
  void apply(FilmThickness &film, OperatingConditions &conditions) const;

  /// Names (CSV column names) and units of the fields above, in this order.
  static const std::vector<std::pair<std::string, std::string>> &columns();
  double get(const std::string &name) const;
  void set(const std::string &name, const double value);
};

/// The CSV layout shared by the writer (`sealfe table`) and the reader: one header line of
/// "name [unit]" fields, then one row per operating point:
///   index [-], role, <OperatingPoint columns>, <load columns>, K_<i>_<j> (9), D_<i>_<j> (9),
///   [err_K_<i>_<j>, err_D_<i>_<j> (18) when estimated], dofs [-], status
/// with i, j in (z, tx, ty) for q = (z, tilt_x, tilt_y), row-major. role is "grid" (a node of the
/// tensor-product grid) or "check" (a held-out point inside a grid cell, not used by the
/// interpolation, only to report its error). status is "ok" or "failed: <message>" (numbers "nan").
namespace coefficient_table_format
{
/// name, unit of every numeric output column (loads, K, D, [errors], dofs) in order.
std::vector<std::pair<std::string, std::string>> output_columns(bool with_errors);
/// "K_z_tx" etc. for K (stiffness = true) or D, row i and column j of q = (z, tx, ty).
std::string coefficient_name(bool stiffness, unsigned int i, unsigned int j);
/// The complete header line (no newline).
std::string header(bool with_errors);
/// A status text that cannot break the CSV (commas, quotes and newlines replaced).
std::string sanitize(const std::string &message);
} // namespace coefficient_table_format

/// A grid of operating points with their coefficients and loads, and interpolation between them.
/// The axes are the OperatingPoint columns that take more than one value among the grid rows; the
/// grid rows must form the full tensor product of the axis values (any spacing, any order).
///
///   CoefficientTable table("sealfe-output/coefficients.csv");
///   FilmCoefficients k = table.coefficients(film, conditions);        // level 1
///   auto model = table.film_model(film, conditions);                  // seal_dynamics FilmModel
///
/// Interpolation: multilinear (error O(h^2)) or tensor-product cubic Lagrange on the 4 nearest
/// nodes of every axis (error O(h^4); fewer nodes on an axis lower the degree to nodes - 1).
class CoefficientTable
{
public:
  enum class Interpolation
  {
    linear,
    cubic
  };

  /// Reads the CSV file; throws std::runtime_error naming the file and line on any problem.
  explicit CoefficientTable(const std::string &csv_file,
                            Interpolation interpolation = Interpolation::cubic);
  /// The same from the text of a CSV file (`name` is used in messages).
  static CoefficientTable from_text(const std::string &csv_text, const std::string &name,
                                    Interpolation interpolation = Interpolation::cubic);

  Interpolation interpolation() const { return method; }
  void set_interpolation(const Interpolation i) { method = i; }

  /// Swept quantities (OperatingPoint column names) and their sorted grid values.
  const std::vector<std::string> &axes() const { return axis_names; }
  const std::vector<double> &axis_values(const unsigned int axis) const { return axis_nodes[axis]; }
  unsigned int n_grid_points() const { return grid_rows.size(); }
  unsigned int n_check_points() const { return check_rows.size(); }
  unsigned int n_failed_points() const { return failed; }
  bool has_column(const std::string &name) const { return column_index.count(name) > 0; }
  /// The values of the quantities the table did not sweep (swept ones: their first row's).
  const OperatingPoint &constant_point() const { return constants; }

  /// One numeric column (e.g. "K_tx_ty", "force_z") interpolated at `point`. Throws
  /// std::runtime_error if the point lies outside the grid, differs from the table in a quantity
  /// that was not swept, or needs a node whose solve failed.
  double value(const std::string &column, const OperatingPoint &point) const;

  /// K and D at `point` (level = 1). The film's K and D depend on the ring speeds only through
  /// the mean speed (omega1 + omega2)/2 (the Couette velocity of the Reynolds equation), so if
  /// the stator speed was not swept, a query with another stator speed is answered at the rotor
  /// speed giving the same mean speed (two rotating rings, FMRR, from an FMS table).
  FilmCoefficients coefficients(const OperatingPoint &point) const;
  FilmCoefficients coefficients(const FilmThickness &film,
                                const OperatingConditions &conditions) const;

  /// Level-1 film model for the dynamics module (seal_dynamics.h FilmModel): coefficients of
  /// `film`, `conditions` at the given ring speeds. Holds a copy of the table.
  std::function<FilmCoefficients(double, double)>
  film_model(const FilmThickness &film, const OperatingConditions &conditions) const;

  /// Interpolation error of K and D at a point with known (e.g. freshly computed) coefficients:
  /// max_ij |K~_ij - K_ij| / max_ij |K_ij| on the matrices made dimensionally uniform by
  /// diag(1, 1/ro, 1/ro) K diag(1, 1/ro, 1/ro) (tilt times ro is a displacement, a moment over ro
  /// a force); the same for D.
  struct Error
  {
    OperatingPoint point;
    double stiffness = 0;
    double damping = 0;
    /// |interpolated - reference| / scale for every result column. The scale is the largest
    /// magnitude over the grid rows of the column, or for quantities that can vanish by symmetry
    /// of the group they belong to: a K or D entry is measured against the largest entry of its
    /// (dimensionally uniform) matrix, a moment against max(|moments|, |F_z| ro), a leakage
    /// against both leakages.
    std::map<std::string, double> columns;
  };
  static Error compare(const FilmCoefficients &interpolated, const FilmCoefficients &reference,
                       double outer_radius);
  /// The error at every held-out ("check") row of the file that succeeded.
  std::vector<Error> held_out_errors() const;

private:
  CoefficientTable() = default;
  void parse(const std::string &text, const std::string &name);
  void build_grid();
  /// Indices of the grid node (one per axis) -> row in grid_rows.
  unsigned int grid_row(const std::vector<unsigned int> &node) const;
  /// Interpolation weights along one axis at x: node indices and weights.
  void axis_weights(unsigned int axis, double x, std::vector<unsigned int> &nodes,
                    std::vector<double> &weights) const;
  /// Axis coordinates of a point (checks range and non-swept quantities).
  std::vector<double> locate(const OperatingPoint &point) const;
  double interpolate(unsigned int column, const std::vector<double> &x) const;

  std::string source;
  Interpolation method = Interpolation::cubic;
  std::vector<std::string> column_names;
  std::map<std::string, unsigned int> column_index;
  struct Row
  {
    unsigned int line = 0;
    std::vector<double> values; // one per column (status and role excluded: NaN there)
    std::string status;
    bool ok = true;
  };
  std::vector<Row> grid_rows, check_rows;
  unsigned int failed = 0;
  std::vector<std::string> axis_names;
  std::vector<std::vector<double>> axis_nodes;
  std::vector<unsigned int> node_to_row; // lexicographic node index (first axis fastest) -> row
  OperatingPoint constants;              // values of the non-swept quantities
  std::map<std::string, double> column_scale; // per column, see Error::columns
};

} // namespace sealfe
