// AnnulusMesh: the triangulation of the sealing dam ri <= r <= ro, built in (r, theta) cells or
// read from a gmsh file, with boundary id 0 on the inner circle and 1 on the outer circle.
#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <string>
#include <vector>

namespace sealfe
{
/// Reads subsection "Discretization" (mesh part) and builds the annulus mesh. Cells carry a
/// PolarManifold about the origin so that refinement and the curved mapping (MappingQ, of the
/// degree FilmSettings::mapping_degree()) follow the circles.
class AnnulusMesh
{
public:
  static constexpr dealii::types::boundary_id inner_boundary = 0;
  static constexpr dealii::types::boundary_id outer_boundary = 1;

  /// Where the built-in mesh must have cell edges: the steps of surface features
  /// (surface_features.h). Angles repeat with `periods` around; the mesh lines theta = const are
  /// sheared by spiral_cot ln(min(max(r, r0), r1) / r0) so that they follow log spirals.
  struct Alignment
  {
    unsigned int periods = 0;          // 0: no angular alignment
    std::vector<double> theta_breaks;  // fractions of a period, in [0, 1)
    double phase = 0;                  // rad, start of the first period
    std::vector<double> radial_breaks; // m, circles inside (ri, ro)
    double spiral_cot = 0, spiral_r0 = 1, spiral_r1 = 1;
    /// Circles of radius circle_radius (m) about these centres (dimples): not lines of the
    /// built-in grid; the generated gmsh mesh (Mesh size > 0) has them as mesh lines.
    std::vector<dealii::Point<2>> circle_centres;
    double circle_radius = 0;
    bool operator==(const Alignment &o) const
    {
      return periods == o.periods && theta_breaks == o.theta_breaks && phase == o.phase &&
             radial_breaks == o.radial_breaks && spiral_cot == o.spiral_cot &&
             spiral_r0 == o.spiral_r0 && spiral_r1 == o.spiral_r1 &&
             circle_centres == o.circle_centres && circle_radius == o.circle_radius;
    }
    /// theta shift of the mesh line through radius r
    double shift(const double r) const;
  };

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);

  /// Build the mesh for the dam ri..ro into `tria`, `coarsening` times coarser than asked for
  /// (each coarsening halves the cells in r and theta, or removes one global refinement). Throws
  /// std::runtime_error if the mesh file is missing, unreadable or not an annulus ri..ro.
  /// `tria` may be serial or distributed (p4est); a generated mesh file is made by rank 0 of its
  /// communicator.
  void create(dealii::Triangulation<2> &tria, const double ri, const double ro,
              const unsigned int coarsening = 0) const;

  /// Radial node positions of the built-in mesh (nr + 1 values from ri to ro). With grading on,
  /// the nodes equidistribute int dr / h0(r)^1.5, h0 = film at theta's mean, so cells shrink where
  /// the film is thin and the pressure gradient (~1/h^3) is steep.
  std::vector<double> radial_nodes(const unsigned int nr, const double ri, const double ro) const;
  /// Angular node positions (nt + 1 values, the last one 2 pi after the first): uniform, or with
  /// the alignment's breaks as nodes when nt is a multiple of its periods (cells shared among the
  /// pieces of a period in proportion to their length, at least one each).
  std::vector<double> angular_nodes(const unsigned int nt) const;

  /// Throws std::runtime_error if the requested built-in mesh (elements of `degree`) has fewer
  /// than 4 nodes per wave of `wave_number` waves around the circumference: it cannot resolve the
  /// waviness. Mesh files are not checked.
  void check_resolves_waves(const double wave_number, const unsigned int degree) const;

  /// Throws std::runtime_error, with the figures, if the requested built-in mesh with elements of
  /// `degree` would need more memory than the machine has (estimate: 1.5 kB per degree of
  /// freedom for degree 2, scaled with the stencil (2 degree + 1)^2). A mesh generated at Mesh
  /// size over the dam ri..ro: about pi (ro^2 - ri^2) / size^2 cells, refined; checked before gmsh
  /// runs. Mesh files read as they are: not checked.
  void check_memory(const unsigned int degree, const double ri = 0, const double ro = 0) const;

  /// True if a mesh `coarsening` levels coarser than the requested one can be built. A mesh file
  /// loses its global refinements; a generated mesh (Mesh size > 0) is then generated again with
  /// cells 2, 4, ... times larger while they stay no larger than the alignment's circles.
  bool can_coarsen(const unsigned int coarsening) const;

  /// True if the JFO coarse start (mesh sequencing) goes on to the level `coarsening` (which
  /// must exist, can_coarsen): a level that only drops global refinements, or a built-in grid
  /// whose cells (mean size in r and around the outer circle) are no larger than the dimples'
  /// radius; never a regenerated gmsh mesh (gmsh runs again, for no better start) nor a built-in
  /// grid that no longer resolves the dimples (doc/textures.md, Cost of JFO on resolved faces).
  bool sequences_jfo(const unsigned int coarsening, const double ri, const double ro) const;

  /// Mesh size (m) of the gmsh mesh generated for `coarsening` levels coarser than asked for
  /// (Mesh size > 0 and coarsening beyond the global refinements), else 0.
  double generated_size(const unsigned int coarsening) const;

  /// The built-in mesh is built from a coarse grid with at least this many cells around and
  /// refined globally (few p4est trees); the vertices end where the direct construction puts them.
  static constexpr unsigned int min_coarse_cells = 16;

  unsigned int radial_cells = 8;
  unsigned int circumferential_cells = 128;
  unsigned int global_refinements = 0;
  std::string mesh_file;
  /// > 0: the Mesh file is generated by gmsh (feature_mesh.h) with cells of about this size (m)
  /// and the alignment's circles as mesh lines, then read like any mesh file.
  double mesh_size = 0;
  /// The Mesh file was left empty: the generated mesh goes to a temporary file, removed once read.
  bool temporary_mesh_file = false;
  bool radial_grading = true;
  /// Axisymmetric film h0(r) = clearance_inner + coning (r - ri) used by the grading.
  double grading_clearance = 1;
  double grading_coning = 0;
  double grading_exponent = 1.5;
  /// Cell edges on the steps of surface features (`Align with features`, default true).
  bool align_with_features = true;
  Alignment alignment;

private:
  /// Move the vertices of the refined coarse grid (`extra` + `refinements` global refinements)
  /// to the nodes of the mesh asked for: graded `radii`, nt 2^refinements uniform angles.
  void place_vertices(dealii::Triangulation<2> &tria, const std::vector<double> &radii,
                      const unsigned int nt, const unsigned int extra,
                      const unsigned int refinements) const;
};

} // namespace sealfe
