// The annulus the tests of the structured paths (CellSparsity, LevelTransfer, PolarCellValues)
// run on: 8 x 64 cells, graded radially, with the multigrid hierarchy.
#pragma once

#include <sealfe/film/annulus_mesh.h>

#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/multigrid/mg_constrained_dofs.h>

#include <mpi.h>

namespace sealfe::test
{
/// The dam of Green 2002 (Table 1: 35.5..40.8 mm), 8 x 64 cells graded towards the faces'
/// edges (C0 = 1 um, coning 1 mrad), refined from 2 x 16 coarse cells: three levels.
struct GradedAnnulus
{
  static constexpr double ri = 0.0355, ro = 0.0408;
  dealii::parallel::distributed::Triangulation<2> tria;

  explicit GradedAnnulus(const MPI_Comm comm)
      : tria(comm, dealii::Triangulation<2>::limit_level_difference_at_vertices,
             dealii::parallel::distributed::Triangulation<2>::construct_multigrid_hierarchy)
  {
    AnnulusMesh m;
    m.radial_cells = 8;
    m.circumferential_cells = 64;
    m.grading_clearance = 1e-6;
    m.grading_coning = 1e-3;
    m.create(tria, ri, ro, 0);
  }
};

/// That annulus with FE_Q(degree) dofs on the active mesh and on every level, and the level
/// constraints of the multigrid: the dofs on both circles zero on every level.
struct GradedAnnulusDoFs
{
  GradedAnnulus annulus;
  dealii::FE_Q<2> fe;
  dealii::DoFHandler<2> dof_handler;
  dealii::MGConstrainedDoFs level_boundary;

  GradedAnnulusDoFs(const MPI_Comm comm, const unsigned int degree)
      : annulus(comm), fe(degree), dof_handler(annulus.tria)
  {
    dof_handler.distribute_dofs(fe);
    dof_handler.distribute_mg_dofs();
    level_boundary.initialize(dof_handler);
    level_boundary.make_zero_boundary_constraints(
        dof_handler, {AnnulusMesh::inner_boundary, AnnulusMesh::outer_boundary});
  }
};
} // namespace sealfe::test
