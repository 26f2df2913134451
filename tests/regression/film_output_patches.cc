// The field output on the built-in annulus fills its patches from the radial rows (one FEValues
// evaluation per row, the other cells of the row turned: PolarCellValues) instead of deal.II's
// DataOut::build_patches. Both routes must write the same VTU: the same points, cells and every
// point array, read back through VTK, to the round-off of the Float32 arrays. The case has every
// field: a tilted, wavy film with rough faces (Patir & Cheng flow factors in the flux and the
// expected gap, a rougher rotor for a shear flow factor, GW/CEB contact pressure) and JFO
// cavitation with a cavity, whose void fraction enters the flux. A wrong rotation of the points
// moves a point by a fraction of the radius and changes h at it by O(1); a wrong rotation of the
// gradients changes the pressure-driven part of the flux (~3 % of it here). So that the
// comparison is of the fast path and not of FEValues with itself, the test also checks that
// PolarCellValues takes every cell of this mesh from its row (none refused: polar_patches falls
// back to FEValues only for refused cells).
#include "../surface_feature_seals.h"
#include <sealfe/film/film_output.h>
#include <sealfe/film/reynolds_solver.h>

#include <sealfe/film/annulus_mesh.h>
#include <sealfe/film/polar_cell_values.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q.h>

#include <gtest/gtest.h>

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace sealfe;

namespace
{
vtkSmartPointer<vtkXMLUnstructuredGridReader> read_piece(const fs::path &dir)
{
  auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
  reader->SetFileName((dir / "solution_0000.0.vtu").c_str());
  reader->Update();
  return reader;
}

/// Largest |a - b| over the components of two arrays of equal shape, and max |a|.
std::pair<double, double> difference(vtkDataArray *a, vtkDataArray *b)
{
  double diff = 0, scale = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      diff = std::max(diff, std::abs(a->GetComponent(i, c) - b->GetComponent(i, c)));
      scale = std::max(scale, std::abs(a->GetComponent(i, c)));
    }
  return {diff, scale};
}

/// Cells of the mesh of `s` (built the way the solver builds it) that PolarCellValues, with
/// polar_patches' lattice, takes from their row; `turned`: those at a nonzero angle, `rows`:
/// FEValues evaluations.
struct RowCount
{
  unsigned int taken = 0, refused = 0, turned = 0, rows = 0;
};
RowCount count_rows(const FilmSettings &s)
{
  using namespace dealii;
  parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
  s.mesh.create(tria, s.geometry.inner_radius, s.geometry.outer_radius);
  const FE_Q<2> fe(s.polynomial_degree);
  const MappingQ<2> mapping(s.polynomial_degree);
  PolarCellValues polar(mapping, fe, QIterated<2>(QTrapezoid<1>(), s.polynomial_degree));
  RowCount count;
  for (const auto &cell : tria.active_cell_iterators())
    if (cell->is_locally_owned())
      ++(polar.reinit(cell) ? count.taken : count.refused);
  count.turned = polar.n_turned();
  count.rows = polar.n_rows();
  return count;
}

/// Tilted, wavy, rough faces with asperity contact and a JFO cavity.
FilmSettings every_field_settings(const unsigned int degree)
{
  FilmSettings s;
  s.cavitation.model = Cavitation::jfo;
  s.geometry.coning = 0;
  s.geometry.wave_amplitude = 0.4e-6;
  s.geometry.wave_number = 3;
  s.geometry.tilt = 0.2 * s.geometry.clearance / s.geometry.outer_radius;
  s.geometry.tilt_angle = 0.3;
  s.conditions.inner_pressure = 1e5;
  s.conditions.outer_pressure = 1e5;
  s.flow_factors = FlowFactors(FlowFactors::Model::patir_cheng, 0.2e-6, 3.0, 0.8);
  AsperityContactParameters contact;
  contact.composite_roughness = 0.2e-6;
  s.contact = AsperityContact(AsperityContact::Model::gw_ceb, contact);
  s.polynomial_degree = degree;
  s.mesh.radial_cells = 4;
  s.mesh.circumferential_cells = 48;
  s.estimate_error = false;
  s.linear_solver = FilmSettings::LinearSolver::direct;
  return s;
}
/// Writes the fields of `s` by both routes (the radial rows, and DataOut::build_patches) into
/// `root` and expects the same cells, points and arrays. Every array is Float32: the two routes
/// compute the same doubles up to the round-off of the rotation (~1e-12 relative,
/// tests/validation/polar_cell_values.cc), so their floats differ by at most one unit in the last
/// place, 2^-23 |x| <= 2^-23 max |x|; twice that. Returns the number of point arrays. `n_cells`:
/// the mesh's cells (0: the built-in grid's N_r N_theta).
int expect_both_routes_equal(ReynoldsSolver &s, const fs::path &root, const std::string &tag,
                             std::size_t n_cells = 0)
{
  const fs::path polar = root / ("polar" + tag), generic = root / ("generic" + tag);
  for (const fs::path &dir : {polar, generic})
  {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  write_film_output(s, polar.string());
  s.polar_rows = false; // the same solution through DataOut::build_patches
  write_film_output(s, generic.string());
  s.polar_rows = true;

  const auto reader_a = read_piece(polar), reader_b = read_piece(generic);
  vtkUnstructuredGrid *a = reader_a->GetOutput(), *b = reader_b->GetOutput();
  const unsigned int degree = s.settings.polynomial_degree;
  if (n_cells == 0) // the built-in grid
    n_cells = s.mesh().radial_cells * s.mesh().circumferential_cells;
  EXPECT_EQ(std::size_t(a->GetNumberOfCells()), n_cells) << tag;
  EXPECT_EQ(a->GetNumberOfCells(), b->GetNumberOfCells()) << tag;
  EXPECT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints()) << tag;
  EXPECT_EQ(std::size_t(a->GetNumberOfPoints()), n_cells * (degree + 1) * (degree + 1)) << tag;
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints())
    return 0;

  const double float_tolerance = 2 * std::ldexp(1.0, -23);
  const auto [point_diff, point_scale] =
      difference(a->GetPoints()->GetData(), b->GetPoints()->GetData());
  EXPECT_LE(point_diff, float_tolerance * point_scale) << tag;

  vtkPointData *pa = a->GetPointData(), *pb = b->GetPointData();
  EXPECT_EQ(pa->GetNumberOfArrays(), pb->GetNumberOfArrays()) << tag;
  for (int k = 0; k < pa->GetNumberOfArrays(); ++k)
  {
    const std::string name = pa->GetArrayName(k);
    vtkDataArray *x = pa->GetArray(name.c_str()), *y = pb->GetArray(name.c_str());
    EXPECT_TRUE(x && y) << name;
    if (!(x && y))
      continue;
    EXPECT_EQ(x->GetNumberOfComponents(), y->GetNumberOfComponents()) << name;
    EXPECT_EQ(x->GetNumberOfTuples(), y->GetNumberOfTuples()) << name;
    const auto [diff, scale] = difference(x, y);
    EXPECT_LE(diff, float_tolerance * scale) << name << ", " << tag;
    std::cout << tag << ", " << name << ": max |difference| " << diff << " of max |value| " << scale
              << "\n";
  }
  vtkDataArray *rank_a = a->GetCellData()->GetArray("rank"),
               *rank_b = b->GetCellData()->GetArray("rank");
  EXPECT_TRUE(rank_a && rank_b) << tag;
  if (rank_a && rank_b)
  {
    EXPECT_EQ(difference(rank_a, rank_b).first, 0.0) << tag;
  }
  return pa->GetNumberOfArrays();
}
} // namespace

TEST(FilmOutputPatches, PolarRowsWriteWhatBuildPatchesWrites)
{
  // the pid: other worktrees run this test at the same time
  const fs::path root =
      fs::temp_directory_path() / ("sealfe_film_output_patches_" + std::to_string(getpid()));
  for (const unsigned int degree : {1u, 2u, 3u})
  {
    const FilmSettings settings = every_field_settings(degree);
    ReynoldsSolver s(settings, MPI_COMM_WORLD);
    const FilmLoads loads = s.run();
    ASSERT_GT(loads.cavitated_fraction, 0.02) << "degree " << degree; // the case has a cavity
    const std::size_t n_cells = s.mesh().radial_cells * s.mesh().circumferential_cells;
    // the fast path runs: every cell taken from its row, all but one per row turned (a row whose
    // key straddles a rounding step may have a second first cell: at most 2 per radial row)
    const RowCount rows = count_rows(settings);
    EXPECT_EQ(rows.refused, 0u) << "degree " << degree;
    EXPECT_EQ(std::size_t(rows.taken), n_cells) << "degree " << degree;
    EXPECT_LE(rows.rows, 2 * s.mesh().radial_cells) << "degree " << degree;
    EXPECT_GE(std::size_t(rows.turned), n_cells - rows.rows) << "degree " << degree;

    // every field the model has: pressure, h, flux, the four Patir & Cheng quantities, contact
    // pressure, liquid fraction, cavitated
    const int n_arrays = expect_both_routes_equal(s, root, "degree " + std::to_string(degree));
    EXPECT_EQ(n_arrays, 10) << "degree " << degree;

    // the void fraction is present and enters the flux: a cavity in the liquid fraction
    const fs::path polar = root / ("polardegree " + std::to_string(degree));
    const auto reader = read_piece(polar);
    vtkDataArray *liquid = reader->GetOutput()->GetPointData()->GetArray("liquid_fraction");
    ASSERT_TRUE(liquid);
    double min_liquid = 1;
    for (vtkIdType i = 0; i < liquid->GetNumberOfTuples(); ++i)
      min_liquid = std::min(min_liquid, liquid->GetTuple1(i));
    EXPECT_LT(min_liquid, 0.99) << "degree " << degree;
  }
  fs::remove_all(root);
}

// Rayleigh pads with the mesh aligned to their steps: the cells of a radial row have unequal
// angular widths (groove, pocket, land), each width a row of its own. The face is flat and the
// film piecewise constant (land, pocket, groove), so every cell, aligned to the steps, must show
// one film thickness at all its points: its own side of a step at the vertices on it
// (film_output.cc takes the film a hair inside the cell), never the neighbour's. Before that,
// the vertex's side followed the round-off of its coordinates, which the two routes compute
// differently: their film thickness differed there by the groove depth.
TEST(FilmOutputPatches, EveryCellShowsItsOwnSideOfAStep)
{
  const fs::path root =
      fs::temp_directory_path() / ("sealfe_film_output_patches_steps_" + std::to_string(getpid()));
  test::RayleighPadSeal pads;
  pads.pads = 4;
  pads.cells_per_pad = 10;
  pads.radial_cells = 3;
  for (const unsigned int degree : {1u, 2u})
  {
    pads.degree = degree;
    ReynoldsSolver s(pads.settings(), MPI_COMM_WORLD);
    s.run();
    // pressure, h, flux (no roughness, contact or cavitation model)
    const std::string tag = "pads degree " + std::to_string(degree);
    EXPECT_EQ(expect_both_routes_equal(s, root, tag), 3);

    // one film thickness per cell (patches: the (k + 1)^2 points of each cell in turn), and all
    // three films present
    const auto reader = read_piece(root / ("polar" + tag));
    vtkDataArray *h = reader->GetOutput()->GetPointData()->GetArray("film_thickness");
    ASSERT_TRUE(h);
    const vtkIdType per_cell = (degree + 1) * (degree + 1);
    double largest_spread = 0;
    std::set<float> films;
    for (vtkIdType c = 0; c * per_cell < h->GetNumberOfTuples(); ++c)
    {
      double lo = h->GetTuple1(c * per_cell), hi = lo;
      for (vtkIdType i = 1; i < per_cell; ++i)
      {
        lo = std::min(lo, h->GetTuple1(c * per_cell + i));
        hi = std::max(hi, h->GetTuple1(c * per_cell + i));
      }
      largest_spread = std::max(largest_spread, hi - lo);
      films.insert(float(lo));
    }
    EXPECT_EQ(largest_spread, 0.0) << tag;
    EXPECT_EQ(films.size(), 3u) << tag;
  }
  fs::remove_all(root);
}
