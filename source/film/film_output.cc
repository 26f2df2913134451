#include <sealfe/film/film_output.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/io/vtu_piece.h>

#include <deal.II/base/utilities.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace sealfe
{
using namespace dealii;

namespace
{
/// Film thickness and the volume flux the film equation conserves, q = -K grad p + (1 - v) c
/// (K = phi_p h^3/(12 mu), c the Couette flux h u_mean with its shear flow factor, v the JFO
/// void fraction: 0 outside a cavity and for every other cavitation model), at the output points;
/// with rough faces the Patir & Cheng quantities, with asperity contact the contact pressure.
class FilmPostprocessor : public DataPostprocessor<2>
{
public:
  /// `void_fraction`: the nodal JFO void fraction, or nullptr (v = 0).
  /// The flags say which of its fields to write.
  FilmPostprocessor(std::function<ReynoldsSolver::LocalFilm(const Point<2> &)> film,
                    const FiniteElement<2> &fe, const unsigned int n_subdivisions,
                    const TrilinosWrappers::MPI::Vector *void_fraction, const bool thickness,
                    const bool flux, const bool rough, const bool contact)
      : film(std::move(film)), void_fraction(void_fraction), thickness(thickness), flux(flux),
        rough(rough), contact(contact)
  {
    // DataOut evaluates on each cell the lattice (i/n, j/n), i fastest: the values of the shape
    // functions there interpolate the nodal void fraction to the output points
    for (unsigned int j = 0; j <= n_subdivisions; ++j)
      for (unsigned int i = 0; i <= n_subdivisions; ++i)
      {
        const Point<2> unit(double(i) / n_subdivisions, double(j) / n_subdivisions);
        std::vector<double> values(fe.n_dofs_per_cell());
        for (unsigned int k = 0; k < values.size(); ++k)
          values[k] = fe.shape_value(k, unit);
        shape_values.push_back(std::move(values));
      }
  }
  void evaluate_scalar_field(const DataPostprocessorInputs::Scalar<2> &in,
                             std::vector<Vector<double>> &out) const override
  {
    std::vector<double> liquid(in.evaluation_points.size(), 1.0);
    if (void_fraction != nullptr && flux)
    {
      AssertDimension(in.evaluation_points.size(), shape_values.size());
      const auto cell = in.template get_cell<2>();
      Vector<double> nodal_void(shape_values[0].size());
      cell->get_dof_values(*void_fraction, nodal_void);
      for (unsigned int q = 0; q < liquid.size(); ++q)
        for (unsigned int k = 0; k < nodal_void.size(); ++k)
          liquid[q] -= nodal_void[k] * shape_values[q][k];
    }
    for (unsigned int q = 0; q < in.evaluation_points.size(); ++q)
    {
      // in a JFO cavity the pressure part vanishes (p = p_cav) and the Couette part carries the
      // liquid fraction: the flux stream tracers follow is the flux that is conserved
      const ReynoldsSolver::LocalFilm f = film(in.evaluation_points[q]);
      unsigned int k = 0;
      if (thickness)
        out[q](k++) = f.h;
      if (flux)
      {
        const Tensor<1, 2> q_flux = -(f.K * in.solution_gradients[q]) + liquid[q] * f.c;
        out[q](k++) = q_flux[0];
        out[q](k++) = q_flux[1];
      }
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
    std::vector<std::string> names;
    if (thickness)
      names.push_back("film_thickness");
    if (flux)
      names.insert(names.end(), {"volume_flux", "volume_flux"});
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
    if (flux)
      kinds[thickness ? 1 : 0] = kinds[thickness ? 2 : 1] =
          DataComponentInterpretation::component_is_part_of_vector;
    return kinds;
  }
  UpdateFlags get_needed_update_flags() const override
  {
    return flux ? update_values | update_gradients | update_quadrature_points
                : update_quadrature_points;
  }
  /// Whether it writes anything at all.
  bool empty() const { return !thickness && !flux && !rough && !contact; }

private:
  std::function<ReynoldsSolver::LocalFilm(const Point<2> &)> film;
  const TrilinosWrappers::MPI::Vector *void_fraction;
  const bool thickness, flux, rough, contact;
  std::vector<std::vector<double>> shape_values; ///< [output point][cell dof]
};

/// deal.II's DataOut with the names and vector ranges of its data sets public, for the VTU writer.
class FieldDataOut : public DataOut<2>
{
public:
  output::VtuFields fields() const
  {
    return output::VtuFields::from(get_dataset_names(), get_nonscalar_data_ranges());
  }
};

/// Writes `content` to `name`, with a one-line reason if the file system refuses.
void write_file(const std::string &name, const std::string &content)
{
  std::ofstream out(name, std::ios::binary);
  out << content;
  if (!out.flush())
    throw std::runtime_error("cannot write the field file " + name);
}
} // namespace

namespace
{
/// The names a user may list, and the flag each sets.
const std::vector<std::pair<std::string, bool FieldSelection::*>> field_names = {
    {"pressure", &FieldSelection::pressure},
    {"film thickness", &FieldSelection::film_thickness},
    {"volume flux", &FieldSelection::volume_flux},
    {"flow factors", &FieldSelection::flow_factors},
    {"contact pressure", &FieldSelection::contact_pressure},
    {"liquid fraction", &FieldSelection::liquid_fraction},
    {"cavitated", &FieldSelection::cavitated}};

/// "pressure, film thickness, ..." for the documentation and the messages.
std::string listed_names()
{
  std::string list;
  for (const auto &[name, flag] : field_names)
    list += (list.empty() ? "" : ", ") + name;
  return list;
}
} // namespace

void FieldSelection::declare_parameters(ParameterHandler &prm)
{
  prm.declare_entry("Fields", "all", Patterns::Anything(),
                    "Fields in the VTU: all (every field the film model has) or a "
                    "comma-separated list of " +
                        listed_names() +
                        ". flow factors needs rough faces, contact pressure asperity contact, "
                        "liquid fraction the jfo model, cavitated a cavitation model. Each field "
                        "is a share of the write, which at 1e6 dofs takes seconds.");
}

void FieldSelection::parse_parameters(ParameterHandler &prm)
{
  const std::string text = prm.get("Fields");
  *this = FieldSelection();
  if (Utilities::trim(text) == "all")
    return;
  const std::vector<std::string> items = Utilities::split_string_list(text, ',');
  if (items.empty())
    throw std::runtime_error("Output/Fields is empty (all, or a list of " + listed_names() +
                             "); to write no fields set Write fields = false");
  everything = false;
  for (const auto &[name, flag] : field_names)
    this->*flag = false;
  for (const std::string &item : items)
  {
    const auto known = std::find_if(field_names.begin(), field_names.end(),
                                    [&item](const auto &entry) { return entry.first == item; });
    if (known == field_names.end())
      throw std::runtime_error("Output/Fields: unknown field '" + item + "' (all, or a list of " +
                               listed_names() + ")");
    this->*(known->second) = true;
  }
}

void FieldSelection::check_against(const FilmSettings &settings) const
{
  if (everything)
    return;
  auto refuse = [](const std::string &field, const std::string &needs)
  { throw std::runtime_error("Output/Fields: " + field + " needs " + needs); };
  if (flow_factors && settings.flow_factors.is_smooth())
    refuse("flow factors", "rough faces (Roughness/Model)");
  if (contact_pressure && !settings.contact.enabled())
    refuse("contact pressure", "an asperity contact model (Contact/Model)");
  if (liquid_fraction && settings.cavitation.model != Cavitation::jfo)
    refuse("liquid fraction", "Cavitation/Model = jfo");
  if (cavitated && settings.cavitation.model == Cavitation::none)
    refuse("cavitated", "a cavitation model (Cavitation/Model)");
}

std::string write_film_fields(const ReynoldsSolver &s, const std::string &directory,
                              const std::string &basename, const unsigned int counter,
                              const FieldSelection &fields, const double frame_angle)
{
  // Only the fields that carry information for this model (and, with an Output/Fields list,
  // that were asked for): the Patir & Cheng quantities with rough faces, the contact pressure
  // with asperity contact, the liquid fraction with JFO and the cavity indicator with a
  // cavitation model (elsewhere they are 1, 0 or h everywhere). The owning rank is cell data
  // (one number per cell).
  const bool jfo = s.cavitation.model == Cavitation::jfo;
  const bool cavitating = s.cavitation.model != Cavitation::none;
  const bool write_flux = fields.volume_flux;
  FilmPostprocessor postprocessor(
      [&s](const Point<2> &x) { return s.local_film(x); }, *s.fe, s.polynomial_degree,
      jfo && write_flux ? &s.locally_relevant_void : nullptr, fields.film_thickness, write_flux,
      !s.flow_factors.is_smooth() && fields.flow_factors,
      s.contact.enabled() && fields.contact_pressure);
  FieldDataOut data_out;
  data_out.attach_dof_handler(s.dof_handler);
  if (fields.pressure)
    data_out.add_data_vector(s.locally_relevant_solution, "pressure");
  if (!postprocessor.empty())
    data_out.add_data_vector(s.locally_relevant_solution, postprocessor);
  // Liquid fraction s = 1 - v (nodal, so exact at the nodes) and an indicator of the cavitated
  // region (1 where p <= p_cav or s < 1).
  const bool write_liquid = jfo && fields.liquid_fraction;
  const bool write_cavitated = cavitating && fields.cavitated;
  TrilinosWrappers::MPI::Vector liquid_ghosted, cavitated_ghosted;
  if (write_liquid || write_cavitated)
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
    if (write_liquid)
      data_out.add_data_vector(liquid_ghosted, "liquid_fraction");
    if (write_cavitated)
      data_out.add_data_vector(cavitated_ghosted, "cavitated");
  }
  // one patch of the element's degree per cell, written as a Lagrange cell
  // (VTK_LAGRANGE_QUADRILATERAL): ParaView shows the curved element and its degree instead of
  // k^2 straight sub-quads
  data_out.build_patches(*s.mapping, s.polynomial_degree, DataOut<2>::curved_inner_cells);
  // Each rank writes its own piece, LZ4-compressed raw binary (output::write_vtu_piece, several
  // times faster than deal.II's base64 writer), with `rank` as cell data (one value per cell)
  const unsigned int rank = Utilities::MPI::this_mpi_process(s.mpi_communicator);
  const std::string stem = basename + "_" + Utilities::int_to_string(counter, 4);
  auto piece_name = [&stem](const unsigned int r)
  { return stem + "." + std::to_string(r) + ".vtu"; };
  const output::VtuFields vtu_fields = data_out.fields();
  {
    const std::string name = directory + "/" + piece_name(rank);
    std::ofstream piece(name, std::ios::binary);
    if (!piece)
      throw std::runtime_error("cannot write the field file " + name);
    output::write_vtu_piece(piece, data_out.get_patches(), vtu_fields,
                            {{"rank", std::vector<int>(data_out.get_patches().size(), int(rank))}},
                            frame_angle);
    if (!piece.flush())
      throw std::runtime_error("cannot write the field file " + name);
  }
  if (rank == 0)
  {
    std::vector<std::string> pieces;
    for (unsigned int r = 0; r < Utilities::MPI::n_mpi_processes(s.mpi_communicator); ++r)
      pieces.push_back(piece_name(r));
    std::ostringstream record;
    output::write_pvtu_record(record, vtu_fields, {"rank"}, pieces);
    write_file(directory + "/" + stem + ".pvtu", record.str());
  }
  // every piece is on disk before the caller publishes the directory
  MPI_Barrier(s.mpi_communicator);
  return stem + ".pvtu";
}

std::string write_film_output(const ReynoldsSolver &s, const std::string &directory,
                              const FieldSelection &fields)
{
  const std::string pvtu = write_film_fields(s, directory, "solution", 0, fields);
  if (Utilities::MPI::this_mpi_process(s.mpi_communicator) == 0)
  {
    std::ofstream pvd(directory + "/solution.pvd");
    DataOutBase::write_pvd_record(pvd, {{0.0, pvtu}});
  }
  return "solution.pvd";
}

} // namespace sealfe
