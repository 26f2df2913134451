// VTU piece writer: deal.II's patches (one Lagrange cell per patch) as an UnstructuredGrid with
// raw appended binary arrays compressed by LZ4, the format VTK and ParaView read natively
// (vtkLZ4DataCompressor). deal.II 9.4's write_vtu base64-encodes every array, which made the
// field output a third of a 1e6-dof solve (doc/performance.md, "Field output").
#pragma once

#include <deal.II/base/data_out_base.h>
#include <deal.II/numerics/data_component_interpretation.h>

#include <ostream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace sealfe
{
namespace output
{
/// The point data of a piece: a name per data set of the patches, and the pairs of data sets
/// that form one 2D vector (first, name).
struct VtuFields
{
  /// From DataOutInterface's data set names and nonscalar ranges; throws for a range that is not
  /// a named vector of two components (tensors and 1- or 3-component vectors are not written).
  static VtuFields
  from(const std::vector<std::string> &names,
       const std::vector<
           std::tuple<unsigned int, unsigned int, std::string,
                      dealii::DataComponentInterpretation::DataComponentInterpretation>> &ranges);

  std::vector<std::string> names;
  std::vector<std::pair<unsigned int, std::string>> vectors;
};

/// The arrays of one VTU piece as the file holds them, filled cell by cell from patches (2D, one
/// subdivision n for all: (n + 1)^2 points each, coordinates from the patch data when the patch
/// is curved, else bilinear between its vertices): Float32 points and point data, 2D vectors
/// padded to 3 components, points and vectors turned by `rotation` (rad, counter-clockwise about
/// z: a field computed in a turned frame is drawn in the frame of the picture). A caller that
/// makes its patches one at a time (the film output's polar rows) fills the piece from one reused
/// patch instead of holding one per cell (doc/performance.md "Field output").
class VtuPieceArrays
{
public:
  VtuPieceArrays(const VtuFields &fields, std::size_t n_cells, unsigned int n_subdivisions,
                 double rotation = 0);
  /// Takes `patch` as cell number `cell` (< n_cells) of the piece.
  void set_cell(std::size_t cell, const dealii::DataOutBase::Patch<2, 2> &patch);
  /// Whether every cell has been set (write_vtu_piece refuses a piece that is not: a cell left
  /// out would be drawn as zeros at the origin).
  bool complete() const { return n_filled == cells; }

  std::size_t n_cells() const { return cells; }
  std::size_t n_points() const { return cells * points_per_cell; }
  unsigned int n_subdivisions() const { return order; }
  /// Points (x, y, 0 each) and, per point array (vectors first, then scalars, in data-set
  /// order: the order of the .pvtu record), its name, components and values.
  const std::vector<float> &points() const { return point_coordinates; }
  struct PointArray
  {
    std::string name;
    unsigned int components, first_set;
    std::vector<float> values;
  };
  const std::vector<PointArray> &point_arrays() const { return arrays; }

private:
  std::size_t cells;
  unsigned int order, points_per_cell, n_sets;
  double cos_r, sin_r;
  std::vector<float> point_coordinates;
  std::vector<PointArray> arrays;
  std::vector<bool> filled; ///< by cell
  std::size_t n_filled = 0;
};

/// Writes `piece` as one VTU piece of VTK_LAGRANGE_QUADRILATERAL cells of order n, and each of
/// `cell_data` as an Int32 cell array of one value per cell.
void write_vtu_piece(std::ostream &out, const VtuPieceArrays &piece,
                     const std::vector<std::pair<std::string, std::vector<int>>> &cell_data);

/// Writes `patches` (all of one subdivision n) through VtuPieceArrays: see there.
void write_vtu_piece(std::ostream &out,
                     const std::vector<dealii::DataOutBase::Patch<2, 2>> &patches,
                     const VtuFields &fields,
                     const std::vector<std::pair<std::string, std::vector<int>>> &cell_data,
                     double rotation = 0);

/// The .pvtu record of pieces written by write_vtu_piece with the same `fields` and cell arrays
/// named `cell_data_names`: VTK's reader matches the arrays of the record and of the pieces by
/// position and type, so both are listed from one place (array_layouts in vtu_piece.cc).
void write_pvtu_record(std::ostream &out, const VtuFields &fields,
                       const std::vector<std::string> &cell_data_names,
                       const std::vector<std::string> &pieces);
} // namespace output
} // namespace sealfe
