// Validation of the generated gmsh mesh with lines on the dimple circles (film/feature_mesh.h,
// `Mesh size` > 0) against geometry and the discrete conservation law:
//  - every dimple circle is closed by mesh faces (their angles add up to 2 pi), the film seen at
//    the quadrature points is the polygonal film of the mesh exactly, and the polygon misses the
//    circle by the circular segments R^2/2 (phi - sin phi): O(h^2), 4 times less per refinement
//    because refinement puts the new vertices on the circles;
//  - JFO on the fitted mesh (coarse levels: the unrefined generated mesh, then meshes generated
//    at 2 h, 4 h) conserves mass to 1e-8.
#include "../surface_feature_seals.h"

#include <sealfe/film/film_summary.h>
#include <sealfe/film/nested_transfer.h>
#include <sealfe/film/surface_features.h>

#include <deal.II/base/function_lib.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_nothing.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include <unistd.h>

using namespace sealfe;
using namespace sealfe::test;

namespace
{
std::string temporary_mesh(const std::string &name)
{
  return (std::filesystem::temp_directory_path() /
          ("sealfe-" + name + "-" + std::to_string(::getpid()) + ".msh"))
      .string();
}

struct DimpleArea
{
  double quadrature = 0; // int [depth > 0] over the mesh at the Gauss points
  double polygon = 0;    // N pi R^2 minus the circular segments cut off by the circle faces
  double circle = 0;     // N pi R^2
  double angle = 0;      // sum of the angles subtended by the circle faces
  double largest_angle = 0;
  double off_circle = 0; // largest |distance to the centre - R| of a circle face's vertices
  double cells = 0;
};

DimpleArea dimple_area(const DimpledSeal &seal, const unsigned int gauss_points)
{
  const FilmSettings s = seal.settings();
  AnnulusMesh mesh = s.mesh;
  const SurfaceFeatures &f = *s.geometry.features;
  mesh.alignment = f.mesh_alignment();
  dealii::parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
  mesh.create(tria, seal.ri, seal.ro);
  const double R = f.dimple_radius;
  const auto centres = f.dimple_centres();
  DimpleArea a;
  a.circle = centres.size() * M_PI * R * R;
  a.polygon = a.circle;
  a.cells = tria.n_global_active_cells();
  dealii::MappingQ<2> mapping(1);
  dealii::FE_Q<2> fe(1);
  dealii::FEValues<2> values(mapping, fe, dealii::QGauss<2>(gauss_points),
                             dealii::update_quadrature_points | dealii::update_JxW_values);
  for (const auto &cell : tria.active_cell_iterators())
  {
    values.reinit(cell);
    for (unsigned int q = 0; q < values.n_quadrature_points; ++q)
    {
      const dealii::Point<2> &x = values.quadrature_point(q);
      if (f.depth(x.norm(), std::atan2(x[1], x[0])) > 0)
        a.quadrature += values.JxW(q);
    }
    // circle faces (manifold id 1 + k), each counted from the cell inside its circle
    for (const auto face_no : cell->face_indices())
    {
      const auto face = cell->face(face_no);
      if (face->manifold_id() == 0 || face->manifold_id() == dealii::numbers::flat_manifold_id)
        continue;
      const dealii::Point<2> &c = centres[face->manifold_id() - 1];
      if (cell->center().distance(c) > R)
        continue;
      for (const unsigned int v : {0u, 1u})
        a.off_circle = std::max(a.off_circle, std::abs(face->vertex(v).distance(c) - R));
      const double phi = 2 * std::asin(0.5 * face->vertex(0).distance(face->vertex(1)) / R);
      a.polygon -= 0.5 * R * R * (phi - std::sin(phi));
      a.angle += phi;
      a.largest_angle = std::max(a.largest_angle, phi);
    }
  }
  return a;
}
} // namespace

TEST(FeatureMesh, DimpleCirclesAreMeshLinesAndTheFilmIsThePolygonal)
{
  // one row of 29 dimples r_p = 2 mm (S_p = 0.2), quads of about 1 mm, refined once and twice
  DimpledSeal seal;
  seal.radius = 2e-3;
  seal.mesh_size = 1e-3;
  seal.mesh_file = temporary_mesh("circles");
  std::vector<DimpleArea> areas;
  for (const unsigned int refinements : {0u, 1u, 2u})
  {
    seal.refinements = refinements;
    const DimpleArea a = dimple_area(seal, 3);
    const double deficit = (a.circle - a.polygon) / a.circle;
    std::cout << "refinements " << refinements << ": " << a.cells << " cells, largest angle "
              << a.largest_angle << " rad, polygon / circle - 1 = " << -deficit
              << ", quadrature / polygon - 1 = " << a.quadrature / a.polygon - 1 << "\n";
    // closed circles: the faces on circle k subtend 2 pi in all
    EXPECT_NEAR(a.angle, 2 * M_PI * 29, 1e-9);
    EXPECT_LT(a.off_circle, 1e-9 * seal.radius);
    // The Gauss points see the film of the polygonal mesh once no point falls in a segment: they
    // are 0.11 h from the cell edges, the segments h^2 / (8 R) thick (the coarse mesh's thinnest
    // cells next to a circle still put some in). In any case the film departs from the polygonal
    // one within the segments only.
    if (refinements > 0)
      EXPECT_NEAR(a.quadrature / a.polygon, 1.0, 1e-12);
    else
      EXPECT_LT(std::abs(a.quadrature - a.polygon), a.circle - a.polygon);
    // a segment is R^2/2 (phi - sin phi) <= R^2 phi^3 / 12: in all <= pi R^2 phi_max^2 / 6 a circle
    EXPECT_GT(deficit, 0.0);
    EXPECT_LT(deficit, a.largest_angle * a.largest_angle / 6);
    areas.push_back(a);
  }
  // O(h^2): a refinement splits every chord at the arc's midpoint, and
  // (phi - sin phi) / (2 (phi/2 - sin phi/2)) = 4 (1 - 3 phi^2 / 80 + ...)
  for (std::size_t k = 1; k < areas.size(); ++k)
  {
    const double ratio =
        (areas[k - 1].circle - areas[k - 1].polygon) / (areas[k].circle - areas[k].polygon);
    const double phi = areas[k - 1].largest_angle;
    EXPECT_LE(ratio, 4.0 + 1e-9);
    EXPECT_GE(ratio, 4 * (1 - 3 * phi * phi / 80) - 1e-3);
  }
  std::filesystem::remove(seal.mesh_file);
}

TEST(FeatureMesh, JfoMassBalanceOnTheFittedMesh)
{
  // JFO with its coarse start: with Global refinements = 1 the coarse level is the generated mesh
  // unrefined (nested); the start does not go on to meshes generated again at 2 h, 4 h
  // (AnnulusMesh::sequences_jfo)
  DimpledSeal seal;
  seal.radius = 2e-3;
  seal.degree = 1;
  seal.mesh_size = 1e-3;
  seal.refinements = 1;
  seal.mesh_file = temporary_mesh("jfo");
  ReynoldsSolver solver(seal.settings(), MPI_COMM_WORLD);
  const FilmLoads jfo = solver.run();
  EXPECT_LT(relative_mass_imbalance(solver, jfo, "JFO on the fitted mesh"), 1e-8);
  EXPECT_GT(jfo.cavitated_fraction, 0.0);
  EXPECT_LT(jfo.cavitated_fraction, 1.0);
  std::filesystem::remove(seal.mesh_file);
}

TEST(FeatureMesh, ValuesFromParentCellsAreTheCoarseFunction)
{
  using namespace dealii;
  // The transfer of the JFO coarse start on a refined mesh: a fine node's value is the coarse
  // function at its parent cell's reference point (child corner + unit point / 2). On a distorted
  // quad mesh with flat manifolds refinement puts the new vertices at the edge midpoints and the
  // cell centre, so each child is exactly its parent's bilinear image of a quarter of the square:
  // the values equal the coarse function at the fine support points up to round-off.
  Triangulation<2> coarse_tria, fine_tria;
  GridGenerator::subdivided_hyper_rectangle(coarse_tria, {5, 4}, Point<2>(0, 0), Point<2>(2, 1));
  GridTools::distort_random(0.25, coarse_tria, false, 7);
  fine_tria.copy_triangulation(coarse_tria);
  fine_tria.refine_global(1);
  const FE_Q<2> fe(2);
  DoFHandler<2> coarse(coarse_tria), fine(fine_tria);
  coarse.distribute_dofs(fe);
  fine.distribute_dofs(fe);
  // a function of the coarse FE space: the interpolant of a smooth function
  TrilinosWrappers::MPI::Vector u(complete_index_set(coarse.n_dofs()), MPI_COMM_SELF);
  Vector<double> u_serial(coarse.n_dofs());
  VectorTools::interpolate(coarse, Functions::SquareFunction<2>(), u_serial);
  for (unsigned int i = 0; i < u_serial.size(); ++i)
    u[i] = u_serial[i] + std::sin(3.0 * i); // not a polynomial of the coordinates alone
  for (unsigned int i = 0; i < u_serial.size(); ++i)
    u_serial[i] = u[i];
  std::vector<types::global_dof_index> dofs(fine.n_dofs());
  for (types::global_dof_index i = 0; i < fine.n_dofs(); ++i)
    dofs[i] = i;
  std::vector<std::vector<double>> values;
  ASSERT_TRUE(values_from_parent_cells(fine, coarse, {&u}, dofs, values));
  std::map<types::global_dof_index, Point<2>> support;
  DoFTools::map_dofs_to_support_points(MappingQ1<2>(), fine, support);
  double worst = 0;
  for (const auto i : dofs)
    worst = std::max(
        worst, std::abs(values[0][i] - VectorTools::point_value(coarse, u_serial, support[i])));
  std::cout << "values from parent cells vs point values: max difference " << worst << "\n";
  // round-off, and the inverse mapping point_value solves by Newton (to about 1e-12 of a cell)
  EXPECT_LT(worst, 1e-10 * u_serial.linfty_norm());
}

TEST(FeatureMesh, ValuesAtPointsOfAnotherMesh)
{
  using namespace dealii;
  // The transfer of the JFO coarse start between unrelated meshes on one rank: Q2 on bilinear
  // cells reproduces every function linear in x and y exactly (x and y are themselves in the
  // mapped space), so the interpolant of f = 1 + 2x - 3y evaluated at the support points of an
  // unrelated distorted mesh of the same rectangle is f there, up to round-off and the inverse
  // mapping's Newton tolerance. Both meshes keep the rectangle's boundary (points there lie on
  // shared edges or corners).
  Triangulation<2> coarse_tria, other_tria;
  GridGenerator::subdivided_hyper_rectangle(coarse_tria, {5, 4}, Point<2>(0, 0), Point<2>(2, 1));
  GridTools::distort_random(0.25, coarse_tria, true, 7);
  GridGenerator::subdivided_hyper_rectangle(other_tria, {13, 7}, Point<2>(0, 0), Point<2>(2, 1));
  GridTools::distort_random(0.3, other_tria, true, 11);
  const FE_Q<2> fe(2);
  DoFHandler<2> coarse(coarse_tria), other(other_tria);
  coarse.distribute_dofs(fe);
  other.distribute_dofs(fe);
  auto f = [](const Point<2> &x) { return 1 + 2 * x[0] - 3 * x[1]; };
  std::map<types::global_dof_index, Point<2>> coarse_support, other_support;
  const MappingQ1<2> mapping;
  DoFTools::map_dofs_to_support_points(mapping, coarse, coarse_support);
  DoFTools::map_dofs_to_support_points(mapping, other, other_support);
  TrilinosWrappers::MPI::Vector u(complete_index_set(coarse.n_dofs()), MPI_COMM_SELF);
  for (const auto &[i, x] : coarse_support)
    u[i] = f(x);
  std::vector<Point<2>> points;
  for (const auto &[i, x] : other_support)
    points.push_back(x);
  std::vector<std::vector<double>> values;
  ASSERT_TRUE(values_at_points(mapping, coarse, {&u, &u}, points, values));
  double worst = 0;
  for (std::size_t q = 0; q < points.size(); ++q)
    worst = std::max(
        {worst, std::abs(values[0][q] - f(points[q])), std::abs(values[1][q] - f(points[q]))});
  std::cout << "values at points of another mesh: " << points.size() << " points, max error "
            << worst << "\n";
  EXPECT_LT(worst, 1e-10);
}
