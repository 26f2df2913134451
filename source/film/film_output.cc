#include <sealfe/film/film_output.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <fstream>

namespace sealfe
{
using namespace dealii;

namespace
{
/// Film thickness and volume flux q = -h^3/(12 mu) grad p + h u_mean at the output points, and
/// with rough faces the Patir & Cheng quantities, with asperity contact the contact pressure.
class FilmPostprocessor : public DataPostprocessor<2>
{
public:
  FilmPostprocessor(std::function<ReynoldsSolver::LocalFilm(const Point<2> &)> film,
                    const bool rough, const bool contact)
      : film(std::move(film)), rough(rough), contact(contact)
  {
  }
  void evaluate_scalar_field(const DataPostprocessorInputs::Scalar<2> &in,
                             std::vector<Vector<double>> &out) const override
  {
    for (unsigned int q = 0; q < in.evaluation_points.size(); ++q)
    {
      // q = -K grad p + c: the full-film flux (in a JFO cavity the Couette part carries the
      // liquid fraction: multiply c by liquid_fraction there; the pressure part is zero).
      const ReynoldsSolver::LocalFilm f = film(in.evaluation_points[q]);
      const Tensor<1, 2> flux = -(f.K * in.solution_gradients[q]) + f.c;
      unsigned int k = 0;
      out[q](k++) = f.h;
      out[q](k++) = flux[0];
      out[q](k++) = flux[1];
      if (rough)
      {
        out[q](k++) = f.h_T;
        out[q](k++) = f.phi_r;
        out[q](k++) = f.phi_theta;
        out[q](k++) = f.phi_s;
      }
      if (contact)
        out[q](k++) = f.contact_pressure;
    }
  }
  std::vector<std::string> get_names() const override
  {
    std::vector<std::string> names = {"film_thickness", "volume_flux", "volume_flux"};
    if (rough)
      names.insert(names.end(), {"expected_gap", "pressure_flow_factor_r",
                                 "pressure_flow_factor_theta", "shear_flow_factor"});
    if (contact)
      names.push_back("contact_pressure");
    return names;
  }
  std::vector<DataComponentInterpretation::DataComponentInterpretation>
  get_data_component_interpretation() const override
  {
    std::vector<DataComponentInterpretation::DataComponentInterpretation> kinds(
        get_names().size(), DataComponentInterpretation::component_is_scalar);
    kinds[1] = kinds[2] = DataComponentInterpretation::component_is_part_of_vector;
    return kinds;
  }
  UpdateFlags get_needed_update_flags() const override
  {
    return update_values | update_gradients | update_quadrature_points;
  }

private:
  std::function<ReynoldsSolver::LocalFilm(const Point<2> &)> film;
  const bool rough, contact;
};
} // namespace

std::string write_film_fields(const ReynoldsSolver &s, const std::string &directory,
                              const std::string &basename, const unsigned int counter)
{
  // Only the fields that carry information for this model: the Patir & Cheng quantities with
  // rough faces, the contact pressure with asperity contact, the liquid fraction with JFO and the
  // cavity indicator with a cavitation model (elsewhere they are 1, 0 or h everywhere, and
  // each field costs about a tenth of the write at 1e6 dofs).
  FilmPostprocessor postprocessor([&s](const Point<2> &x) { return s.local_film(x); },
                                  !s.flow_factors.is_smooth(), s.contact.enabled());
  DataOut<2> data_out;
  data_out.attach_dof_handler(s.dof_handler);
  data_out.add_data_vector(s.locally_relevant_solution, "pressure");
  data_out.add_data_vector(s.locally_relevant_solution, postprocessor);
  // Liquid fraction s = 1 - v (nodal, so exact at the nodes) and an indicator of the cavitated
  // region (1 where p <= p_cav or s < 1).
  const bool jfo = s.cavitation.model == Cavitation::jfo;
  const bool cavitating = s.cavitation.model != Cavitation::none;
  TrilinosWrappers::MPI::Vector liquid_ghosted, cavitated_ghosted;
  if (cavitating)
  {
    TrilinosWrappers::MPI::Vector liquid(s.locally_owned_dofs, s.mpi_communicator),
        cavitated(s.locally_owned_dofs, s.mpi_communicator);
    const double p_tol = 1e-9 * std::max(s.pressure_scale, 1.0);
    for (const auto i : s.locally_owned_dofs)
    {
      const double v = jfo ? s.locally_relevant_void[i] : 0.0;
      liquid[i] = 1 - v;
      cavitated[i] =
          (v > 0 || s.locally_relevant_solution[i] <= s.cavitation.pressure + p_tol) ? 1.0 : 0.0;
    }
    liquid.compress(VectorOperation::insert);
    cavitated.compress(VectorOperation::insert);
    liquid_ghosted.reinit(s.locally_owned_dofs, s.locally_relevant_dofs, s.mpi_communicator);
    cavitated_ghosted.reinit(s.locally_owned_dofs, s.locally_relevant_dofs, s.mpi_communicator);
    liquid_ghosted = liquid;
    cavitated_ghosted = cavitated;
    if (jfo)
      data_out.add_data_vector(liquid_ghosted, "liquid_fraction");
    data_out.add_data_vector(cavitated_ghosted, "cavitated");
  }
  // the owning rank, for a run on more than one
  Vector<float> subdomain;
  if (Utilities::MPI::n_mpi_processes(s.mpi_communicator) > 1)
  {
    subdomain.reinit(s.triangulation.n_active_cells());
    subdomain = s.triangulation.locally_owned_subdomain();
    data_out.add_data_vector(subdomain, "rank");
  }
  // one Lagrange cell of the element's degree per cell (VTK_LAGRANGE_QUADRILATERAL): ParaView
  // shows the curved element and its degree instead of k^2 straight sub-quads; zlib at its
  // fastest level (the write is a large share of a big solve's time)
  DataOutBase::VtkFlags flags;
  flags.write_higher_order_cells = true;
  flags.compression_level = DataOutBase::VtkFlags::best_speed;
  data_out.set_flags(flags);
  data_out.build_patches(*s.mapping, s.polynomial_degree, DataOut<2>::curved_inner_cells);
  return data_out.write_vtu_with_pvtu_record(directory + "/", basename, counter, s.mpi_communicator,
                                             4, 1);
}

std::string write_film_output(const ReynoldsSolver &s, const std::string &directory)
{
  const std::string pvtu = write_film_fields(s, directory, "solution", 0);
  if (Utilities::MPI::this_mpi_process(s.mpi_communicator) == 0)
  {
    std::ofstream pvd(directory + "/solution.pvd");
    DataOutBase::write_pvd_record(pvd, {{0.0, pvtu}});
  }
  return "solution.pvd";
}

} // namespace sealfe
