// The VTU writer (output::write_vtu_piece, write_pvtu_record), read back through VTK: points,
// point data and cell data equal deal.II's patches, the Lagrange cells' node order is VTK's,
// checked by VTK's own interpolation inside each cell against the deal.II mapping and an exactly
// represented field, and pieces (one of them empty) with their .pvtu record read as the whole.
#include <sealfe/io/vtu_piece.h>

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace dealii;

namespace
{
/// The output point itself as a 2D vector field (a vector data set whose value VTK must return
/// where the point is).
class PositionField : public DataPostprocessorVector<2>
{
public:
  PositionField() : DataPostprocessorVector<2>("position", update_quadrature_points) {}
  void evaluate_scalar_field(const DataPostprocessorInputs::Scalar<2> &in,
                             std::vector<Vector<double>> &out) const override
  {
    for (unsigned int q = 0; q < in.evaluation_points.size(); ++q)
      for (unsigned int d = 0; d < 2; ++d)
        out[q](d) = in.evaluation_points[q][d];
  }
};

class ExposedDataOut : public DataOut<2>
{
public:
  sealfe::output::VtuFields fields() const
  {
    return sealfe::output::VtuFields::from(get_dataset_names(), get_nonscalar_data_ranges());
  }
};

double linear_field(const Point<2> &x)
{
  return 2 + 3 * x[0] - 5 * x[1];
}

/// Writes p = 2 + 3x - 5y (represented exactly: p o F is in Q_k for the meshes below) and the
/// position field on `tria` with FE_Q(k) and MappingQ(k), reads the piece back and checks it.
void check(const Triangulation<2> &tria, const unsigned int k, const std::string &name)
{
  const FE_Q<2> fe(k);
  const MappingQ<2> mapping(k);
  DoFHandler<2> dofs(tria);
  dofs.distribute_dofs(fe);
  Vector<double> p(dofs.n_dofs());
  VectorTools::interpolate(mapping, dofs, ScalarFunctionFromFunctionObject<2>(&linear_field), p);
  ExposedDataOut data_out;
  data_out.attach_dof_handler(dofs);
  data_out.add_data_vector(p, "pressure");
  const PositionField position;
  data_out.add_data_vector(p, position);
  data_out.build_patches(mapping, k, DataOut<2>::curved_inner_cells);
  const auto &patches = data_out.get_patches();
  std::vector<int> ids(patches.size());
  for (std::size_t c = 0; c < ids.size(); ++c)
    ids[c] = int(c) % 7;

  const fs::path file = fs::temp_directory_path() / ("sealfe_vtu_piece_" + name + ".vtu");
  {
    std::ofstream out(file, std::ios::binary);
    sealfe::output::write_vtu_piece(out, patches, data_out.fields(), {{"cell_id", ids}});
  }
  auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  reader->SetFileName(file.c_str());
  reader->Update();
  vtkUnstructuredGrid *grid = reader->GetOutput();
  ASSERT_EQ(std::size_t(grid->GetNumberOfCells()), tria.n_active_cells());
  ASSERT_EQ(std::size_t(grid->GetNumberOfPoints()), tria.n_active_cells() * (k + 1) * (k + 1));
  vtkDataArray *pressure = grid->GetPointData()->GetArray("pressure");
  vtkDataArray *vector = grid->GetPointData()->GetArray("position");
  vtkDataArray *cell_id = grid->GetCellData()->GetArray("cell_id");
  ASSERT_TRUE(pressure && vector && cell_id);
  ASSERT_EQ(vector->GetNumberOfComponents(), 3);

  // Float32 arrays: a relative rounding of 6e-8 of the values (|x| <= 1, |p| <= 10 here)
  const double float_tolerance = 1e-6;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    double x[3];
    grid->GetPoint(i, x);
    EXPECT_NEAR(pressure->GetTuple1(i), linear_field(Point<2>(x[0], x[1])), 10 * float_tolerance);
    const double *v = vector->GetTuple3(i);
    EXPECT_NEAR(v[0], x[0], float_tolerance);
    EXPECT_NEAR(v[1], x[1], float_tolerance);
    EXPECT_EQ(v[2], 0.0);
  }
  // Inside every cell, VTK's Lagrange interpolation of its nodes at the parametric point (0.3,
  // 0.7) is the deal.II cell's point at the unit point (0.3, 0.7), and the pressure there is exact:
  // a wrong node order moves it by a fraction of the cell size
  const Point<2> unit(0.3, 0.7);
  double max_position_error = 0, max_pressure_error = 0;
  vtkIdType c = 0;
  for (const auto &cell : tria.active_cell_iterators())
  {
    EXPECT_EQ(cell_id->GetTuple1(c), double(c % 7));
    vtkCell *vtk_cell = grid->GetCell(c);
    const double pcoords[3] = {unit[0], unit[1], 0};
    double x[3];
    std::vector<double> weights(vtk_cell->GetNumberOfPoints());
    int sub_id = 0;
    vtk_cell->EvaluateLocation(sub_id, pcoords, x, weights.data());
    const Point<2> expected = mapping.transform_unit_to_real_cell(cell, unit);
    max_position_error =
        std::max(max_position_error, std::hypot(x[0] - expected[0], x[1] - expected[1]));
    double p_vtk = 0;
    for (vtkIdType n = 0; n < vtk_cell->GetNumberOfPoints(); ++n)
      p_vtk += weights[n] * pressure->GetTuple1(vtk_cell->GetPointId(n));
    max_pressure_error = std::max(max_pressure_error, std::abs(p_vtk - linear_field(expected)));
    ++c;
  }
  EXPECT_LT(max_position_error, float_tolerance);
  EXPECT_LT(max_pressure_error, 10 * float_tolerance);

  // The same patches as three pieces (the first half, none, the second half: a rank may own no
  // cell) and their .pvtu record: VTK's parallel reader gives the single piece back, every array
  // in place (the record lists the arrays by position and type, so a record out of step with its
  // pieces would drop or garble one)
  const std::size_t half = patches.size() / 2;
  const std::vector<std::vector<DataOutBase::Patch<2, 2>>> parts = {
      {patches.begin(), patches.begin() + half}, {}, {patches.begin() + half, patches.end()}};
  std::vector<std::string> piece_names;
  for (std::size_t part = 0; part < parts.size(); ++part)
  {
    piece_names.push_back("sealfe_vtu_piece_" + name + "_part" + std::to_string(part) + ".vtu");
    std::ofstream out(fs::temp_directory_path() / piece_names.back(), std::ios::binary);
    sealfe::output::write_vtu_piece(out, parts[part], data_out.fields(),
                                    {{"cell_id", std::vector<int>(parts[part].size(), int(part))}});
  }
  const fs::path record = fs::temp_directory_path() / ("sealfe_vtu_piece_" + name + ".pvtu");
  {
    std::ofstream out(record);
    sealfe::output::write_pvtu_record(out, data_out.fields(), {"cell_id"}, piece_names);
  }
  auto parallel_reader = vtkSmartPointer<vtkXMLPUnstructuredGridReader>::New();
  parallel_reader->SetFileName(record.c_str());
  parallel_reader->Update();
  vtkUnstructuredGrid *whole = parallel_reader->GetOutput();
  ASSERT_EQ(whole->GetNumberOfPoints(), grid->GetNumberOfPoints());
  ASSERT_EQ(whole->GetNumberOfCells(), grid->GetNumberOfCells());
  for (const char *array : {"pressure", "position"})
  {
    vtkDataArray *a = whole->GetPointData()->GetArray(array),
                 *b = grid->GetPointData()->GetArray(array);
    ASSERT_TRUE(a != nullptr) << array;
    ASSERT_EQ(a->GetNumberOfComponents(), b->GetNumberOfComponents());
    for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
      for (int c = 0; c < b->GetNumberOfComponents(); ++c)
        ASSERT_EQ(a->GetComponent(i, c), b->GetComponent(i, c)) << array << " " << i;
  }
  vtkDataArray *part = whole->GetCellData()->GetArray("cell_id");
  ASSERT_TRUE(part != nullptr);
  EXPECT_EQ(part->GetTuple1(0), 0.0);
  EXPECT_EQ(part->GetTuple1(whole->GetNumberOfCells() - 1), 2.0);
  fs::remove(file);
  fs::remove(record);
  for (const auto &piece : piece_names)
    fs::remove(fs::temp_directory_path() / piece);
}
} // namespace

// Degree 2 on a curved annulus (MappingQ(2)'s support points are the equidistant output
// lattice, so VTK's quadratic cell is the deal.II cell); 8 x 4^6 = 32 768 cells: the point array
// (3.5 MB) spans four 1 MiB compression blocks, the last one partial.
TEST(VtuPiece, QuadraticCellsOnAnAnnulusReadBackThroughVtk)
{
  Triangulation<2> tria;
  GridGenerator::hyper_shell(tria, Point<2>(), 0.5, 1.0, 8);
  tria.refine_global(6);
  check(tria, 2, "annulus");
}

// Degrees 1 and 3 on a distorted straight-sided mesh (bilinear cells, represented exactly by a
// lattice of any order).
TEST(VtuPiece, LinearAndCubicCellsOnADistortedMesh)
{
  for (const unsigned int k : {1u, 3u})
  {
    Triangulation<2> tria;
    GridGenerator::subdivided_hyper_rectangle(tria, {5, 3}, Point<2>(0, 0), Point<2>(1, 0.6));
    GridTools::distort_random(0.2, tria, true, 42);
    check(tria, k, "distorted_" + std::to_string(k));
  }
}
