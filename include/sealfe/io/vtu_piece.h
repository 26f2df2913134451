// VTU piece writer: deal.II's patches (one Lagrange cell per patch) as an UnstructuredGrid with
// raw appended binary arrays compressed by LZ4, the format VTK and ParaView read natively
// (vtkLZ4DataCompressor). deal.II 9.4's write_vtu base64-encodes every array, which made the
// field output a third of a 1e6-dof solve (doc/performance.md, "Field output").
#pragma once

#include <deal.II/base/data_out_base.h>

#include <ostream>
#include <string>
#include <tuple>
#include <vector>

namespace sealfe
{
namespace output
{
/// The point data of a piece: a name per data set of the patches, and the ranges of data sets
/// that form one vector (first, last, name), as DataOutInterface describes them.
struct VtuFields
{
  std::vector<std::string> names;
  std::vector<std::tuple<unsigned int, unsigned int, std::string>> vectors;
};

/// Writes `patches` (2D, any subdivision n: (n + 1)^2 points each, coordinates from the patch
/// data when the patch is curved) as one VTU piece of VTK_LAGRANGE_QUADRILATERAL cells of order
/// n, Float32 points and point data (2D vectors padded to 3 components), and each of
/// `cell_data` as an Int32 cell array of one value per patch. The points and the vectors are
/// turned by `rotation` (rad, counter-clockwise about z): a field computed in a turned frame is
/// drawn in the frame of the picture.
void write_vtu_piece(std::ostream &out,
                     const std::vector<dealii::DataOutBase::Patch<2, 2>> &patches,
                     const VtuFields &fields,
                     const std::vector<std::pair<std::string, std::vector<int>>> &cell_data,
                     double rotation = 0);
} // namespace output
} // namespace sealfe
