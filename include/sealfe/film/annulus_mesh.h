// AnnulusMesh: the triangulation of the sealing dam ri <= r <= ro, built in (r, theta) cells or
// read from a gmsh file, with boundary id 0 on the inner circle and 1 on the outer circle.
#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/distributed/tria.h>

#include <string>
#include <vector>

namespace sealfe
{
/// Reads subsection "Discretization" (mesh part) and builds the annulus mesh. Cells carry a
/// PolarManifold about the origin so that refinement and a MappingQ of the element's degree
/// follow the circles exactly.
class AnnulusMesh
{
public:
  static constexpr dealii::types::boundary_id inner_boundary = 0;
  static constexpr dealii::types::boundary_id outer_boundary = 1;

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);

  /// Build the mesh for the dam ri..ro into `tria`, `coarsening` times coarser than asked for
  /// (each coarsening halves the cells in r and theta, or removes one global refinement). Throws
  /// std::runtime_error if the mesh file is missing, unreadable or not an annulus ri..ro.
  void create(dealii::parallel::distributed::Triangulation<2> &tria, const double ri,
              const double ro, const unsigned int coarsening = 0) const;

  /// Radial node positions of the built-in mesh (nr + 1 values from ri to ro). With grading on,
  /// the nodes equidistribute int dr / h0(r)^1.5, h0 = film at theta's mean, so cells shrink where
  /// the film is thin and the pressure gradient (~1/h^3) is steep.
  std::vector<double> radial_nodes(const unsigned int nr, const double ri, const double ro) const;

  /// Throws std::runtime_error if the requested built-in mesh (elements of `degree`) has fewer
  /// than 4 nodes per wave of `wave_number` waves around the circumference: it cannot resolve the
  /// waviness. Mesh files are not checked.
  void check_resolves_waves(const double wave_number, const unsigned int degree) const;

  /// Throws std::runtime_error, with the figures, if the requested built-in mesh with elements of
  /// `degree` would need more memory than the machine has (estimate: 1.5 kB per degree of
  /// freedom for degree 2, scaled with the stencil (2 degree + 1)^2). Mesh files: not checked.
  void check_memory(const unsigned int degree) const;

  /// True if a mesh `coarsening` levels coarser than the requested one can be built.
  bool can_coarsen(const unsigned int coarsening) const;

  /// The built-in mesh is built from a coarse grid with at least this many cells around and
  /// refined globally (few p4est trees); the vertices end where the direct construction puts them.
  static constexpr unsigned int min_coarse_cells = 16;

  unsigned int radial_cells = 8;
  unsigned int circumferential_cells = 128;
  unsigned int global_refinements = 0;
  std::string mesh_file;
  bool radial_grading = true;
  /// Axisymmetric film h0(r) = clearance_inner + coning (r - ri) used by the grading.
  double grading_clearance = 1;
  double grading_coning = 0;
  double grading_exponent = 1.5;

private:
  /// Move the vertices of the refined coarse grid (`extra` + `refinements` global refinements)
  /// to the nodes of the mesh asked for: graded `radii`, nt 2^refinements uniform angles.
  static void place_vertices(dealii::parallel::distributed::Triangulation<2> &tria,
                             const std::vector<double> &radii, const unsigned int nt,
                             const unsigned int extra, const unsigned int refinements);
};

} // namespace sealfe
