#include <sealfe/film/film_output.h>
#include <sealfe/film/polar_cell_values.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/io/vtu_piece.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <optional>
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
    // point_values writes into arrays of max_components
    AssertThrow(
        get_names().size() <= max_components,
        ExcMessage("FilmPostprocessor: " + std::to_string(get_names().size()) +
                   " fields, more than max_components = " + std::to_string(max_components)));
  }
  void evaluate_scalar_field(const DataPostprocessorInputs::Scalar<2> &in,
                             std::vector<Vector<double>> &out) const override
  {
    Vector<double> nodal_void;
    if (needs_void_fraction())
    {
      AssertDimension(in.evaluation_points.size(), shape_values.size());
      nodal_void.reinit(shape_values[0].size());
      in.template get_cell<2>()->get_dof_values(*void_fraction, nodal_void);
    }
    std::array<double, max_components> values;
    const Point<2> center = in.template get_cell<2>()->center();
    for (unsigned int q = 0; q < in.evaluation_points.size(); ++q)
    {
      const double liquid = needs_void_fraction() ? liquid_fraction(nodal_void, q) : 1.0;
      const unsigned int n =
          point_values(in.evaluation_points[q], center,
                       flux ? in.solution_gradients[q] : Tensor<1, 2>(), liquid, values.data());
      for (unsigned int k = 0; k < n; ++k)
        out[q](k) = values[k];
    }
  }
  /// The fields at the output point x of the cell with centre `cell_center`, from the pressure
  /// gradient there and the liquid fraction (1 - v: 1 outside a JFO cavity); writes
  /// get_names().size() values to `out` and returns their number. Both routes to the patches
  /// (DataOut and the polar rows) compute them here.
  unsigned int point_values(const Point<2> &x, const Point<2> &cell_center,
                            const Tensor<1, 2> &grad_p, const double liquid, double *out) const
  {
    // The film is taken a hair inside the cell (1e-9 of the way to its centre): a vertex on a
    // step of a surface feature (a mesh aligned to the steps) then shows this cell's side of the
    // step, not whichever side the round-off of its coordinates falls on (the two routes compute
    // the point to ~1e-16 relative, 1e-7 of the shift). For a smooth film the shift changes h by
    // ~1e-9 of its variation across the cell, far below the Float32 of the file (6e-8).
    const ReynoldsSolver::LocalFilm f = film(x + inward_shift * (cell_center - x));
    // in a JFO cavity the pressure part vanishes (p = p_cav) and the Couette part carries the
    // liquid fraction: the flux stream tracers follow is the flux that is conserved
    unsigned int k = 0;
    if (thickness)
      out[k++] = f.h;
    if (flux)
    {
      const Tensor<1, 2> q_flux = -(f.K * grad_p) + liquid * f.c;
      out[k++] = q_flux[0];
      out[k++] = q_flux[1];
    }
    if (rough)
    {
      out[k++] = f.h_T;
      out[k++] = f.phi_r;
      out[k++] = f.phi_theta;
      out[k++] = f.phi_s;
    }
    if (contact)
      out[k++] = f.contact_pressure;
    return k;
  }
  /// Whether point_values needs the liquid fraction (flux with JFO), and the solution gradient.
  bool needs_void_fraction() const { return void_fraction != nullptr && flux; }
  bool needs_gradients() const { return flux; }
  const TrilinosWrappers::MPI::Vector &void_fraction_vector() const { return *void_fraction; }
  /// 1 - v at output point q (the lattice (i/n, j/n), i fastest) from the cell's nodal v.
  double liquid_fraction(const Vector<double> &nodal_void, const unsigned int q) const
  {
    double liquid = 1.0;
    for (unsigned int k = 0; k < nodal_void.size(); ++k)
      liquid -= nodal_void[k] * shape_values[q][k];
    return liquid;
  }
  static constexpr unsigned int max_components = 8;
  static constexpr double inward_shift = 1e-9;
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

/// One data set of the output, in the order DataOut numbers them: the nodal `vector`
/// interpolated to the output points under `name`, or (`postprocessed`) the components of the
/// postprocessor with `vector` as the pressure.
struct DataSet
{
  const TrilinosWrappers::MPI::Vector *vector;
  std::string name;
  bool postprocessed = false;
};

/// Fills `patch` as DataOut::build_patches(mapping, k, curved_inner_cells) does for `cell`
/// (the (k + 1)^2 lattice points (i/k, j/k), i fastest, their mapped positions as the last two
/// rows of the data), from `values` reinitialised on the cell with that lattice as quadrature:
/// FEValues, or PolarCellValues (the row's first cell turned).
/// `film_used`: whether one of `sets` is the postprocessor's.
template <class Values>
void fill_patch(const Values &values, const DoFHandler<2>::active_cell_iterator &cell,
                const std::vector<DataSet> &sets, const FilmPostprocessor &film,
                const bool film_used, const unsigned int n_sets, const unsigned int degree,
                const unsigned int n_q, DataOutBase::Patch<2, 2> &patch)
{
  const unsigned int n = values.get_fe().n_dofs_per_cell();
  patch.n_subdivisions = degree;
  patch.reference_cell = ReferenceCells::Quadrilateral;
  patch.points_are_available = true;
  for (unsigned int v = 0; v < 4; ++v)
    patch.vertices[v] = cell->vertex(v);
  patch.data.reinit(n_sets + 2, n_q);
  Vector<double> nodal(n), nodal_void, pressure(n);
  if (film_used && film.needs_void_fraction())
  {
    nodal_void.reinit(n);
    cell->get_dof_values(film.void_fraction_vector(), nodal_void);
  }
  std::array<double, FilmPostprocessor::max_components> film_values;
  const Point<2> center = cell->center();
  unsigned int row = 0;
  for (const DataSet &set : sets)
  {
    if (!set.postprocessed)
    {
      cell->get_dof_values(*set.vector, nodal);
      for (unsigned int q = 0; q < n_q; ++q)
      {
        double u = 0;
        for (unsigned int i = 0; i < n; ++i)
          u += nodal[i] * values.shape_value(i, q);
        patch.data(row, q) = u;
      }
      ++row;
      continue;
    }
    // the postprocessor's fields, from the pressure gradient (the solution is the pressure)
    if (film.needs_gradients())
      cell->get_dof_values(*set.vector, pressure);
    unsigned int n_film = 0;
    for (unsigned int q = 0; q < n_q; ++q)
    {
      Tensor<1, 2> grad_p;
      if (film.needs_gradients())
        for (unsigned int i = 0; i < n; ++i)
          grad_p += pressure[i] * values.shape_grad(i, q);
      const double liquid = nodal_void.size() ? film.liquid_fraction(nodal_void, q) : 1.0;
      n_film =
          film.point_values(values.quadrature_point(q), center, grad_p, liquid, film_values.data());
      for (unsigned int k = 0; k < n_film; ++k)
        patch.data(row + k, q) = film_values[k];
    }
    row += n_film;
  }
  AssertDimension(row, n_sets);
  for (unsigned int q = 0; q < n_q; ++q)
    for (unsigned int d = 0; d < 2; ++d)
      patch.data(n_sets + d, q) = values.quadrature_point(q)[d];
}

/// The patches of build_patches(mapping, k, curved_inner_cells) on the built-in annulus, where
/// every cell of a radial row is the row's first cell turned about the axis: the mapped output
/// points and the shape gradients there come from one FEValues evaluation per row
/// (PolarCellValues), which removes the per-cell mapping and gradient transformation (measured:
/// 0.13-0.15 s of the 0.78 s of build_patches with every field, doc/performance.md). A cell
/// PolarCellValues cannot prove to be such a rotation (its vertices checked; the mesh of a
/// surface-feature layout, say) gets FEValues, i.e. what build_patches computes for it. The values
/// equal build_patches' to the round-off of the rotation (tests/regression/film_output_patches.cc).
/// Each patch goes into `piece` as soon as it is made: one patch is reused instead of one held per
/// cell (output at 1.05e6 Q2 dofs 0.90-1.05 s with one held per cell, 0.61-0.74 s without;
/// doc/performance.md "Field output").
void polar_patches(const DoFHandler<2> &dof_handler, const Mapping<2> &mapping,
                   const unsigned int degree, const std::vector<DataSet> &sets,
                   const FilmPostprocessor &film, const unsigned int n_sets,
                   output::VtuPieceArrays &piece)
{
  const QIterated<2> lattice(QTrapezoid<1>(), degree); // DataOut's output points
  const FiniteElement<2> &fe = dof_handler.get_fe();
  PolarCellValues polar(mapping, fe, lattice);
  FEValues<2> fe_values(mapping, fe, lattice,
                        update_values | update_gradients | update_quadrature_points);
  const bool film_used =
      std::any_of(sets.begin(), sets.end(), [](const DataSet &d) { return d.postprocessed; });
  DataOutBase::Patch<2, 2> patch;
  std::size_t n_cells = 0;
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      patch.patch_index = n_cells;
      if (polar.reinit(cell))
        fill_patch(polar, cell, sets, film, film_used, n_sets, degree, lattice.size(), patch);
      else
      {
        fe_values.reinit(cell);
        fill_patch(fe_values, cell, sets, film, film_used, n_sets, degree, lattice.size(), patch);
      }
      piece.set_cell(n_cells++, patch);
    }
}

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
  std::vector<DataSet> sets;
  if (fields.pressure)
    sets.push_back({&s.locally_relevant_solution, "pressure"});
  if (!postprocessor.empty())
    sets.push_back({&s.locally_relevant_solution, "", true});
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
      sets.push_back({&liquid_ghosted, "liquid_fraction"});
    if (write_cavitated)
      sets.push_back({&cavitated_ghosted, "cavitated"});
  }
  // One patch of the element's degree per cell, written as a Lagrange cell
  // (VTK_LAGRANGE_QUADRILATERAL): ParaView shows the curved element and its degree instead of
  // k^2 straight sub-quads. On the built-in annulus the patches come from the polar rows
  // (polar_patches); deal.II's build_patches makes them for a mesh file, or with polar_rows
  // false (the tests compare the two routes).
  // The names and vector ranges of the data sets come from DataOut on both routes (they need
  // only the data vectors added, not build_patches): one source of names.
  FieldDataOut data_out;
  data_out.attach_dof_handler(s.dof_handler);
  for (const DataSet &set : sets)
    if (set.postprocessed)
      data_out.add_data_vector(*set.vector, postprocessor);
    else
      data_out.add_data_vector(*set.vector, set.name);
  const output::VtuFields vtu_fields = data_out.fields();
  // The patches are drawn with a mapping of the element's degree k, as before the mapping of
  // the solve could be of higher degree: for k <= 2 the equidistant lattice (i/k, j/k) of a
  // patch is then that mapping's (Gauss-Lobatto) support points, which lie on the circles (and
  // on the steps of a mesh aligned to surface features). The solve's mapping of degree k + 1
  // interpolates the circles between its own support points and puts the lattice's mid-edge
  // points ~1e-7 m off them (Rayleigh pads, 40 cells around), on the other side of a step on a
  // circle. For k >= 3 the lattice's inner points are not support points of either mapping.
  std::optional<MappingQ<2>> element_degree_mapping;
  const Mapping<2> &mapping = s.settings.mapping_degree() == s.polynomial_degree
                                  ? static_cast<const Mapping<2> &>(*s.mapping)
                                  : element_degree_mapping.emplace(s.polynomial_degree);
  const auto *distributed =
      dynamic_cast<const parallel::TriangulationBase<2> *>(&s.dof_handler.get_triangulation());
  const std::size_t n_cells = distributed ? distributed->n_locally_owned_active_cells()
                                          : s.dof_handler.get_triangulation().n_active_cells();
  output::VtuPieceArrays piece(vtu_fields, n_cells, s.polynomial_degree, frame_angle);
  if (s.assembles_on_polar_rows())
    polar_patches(s.dof_handler, mapping, s.polynomial_degree, sets, postprocessor,
                  vtu_fields.names.size(), piece);
  else
  {
    data_out.build_patches(mapping, s.polynomial_degree, DataOut<2>::curved_inner_cells);
    const std::vector<DataOutBase::Patch<2, 2>> &patches = data_out.get_patches();
    for (std::size_t c = 0; c < patches.size(); ++c)
      piece.set_cell(c, patches[c]);
  }
  // Each rank writes its own piece, LZ4-compressed raw binary (output::write_vtu_piece, several
  // times faster than deal.II's base64 writer), with `rank` as cell data (one value per cell)
  const unsigned int rank = Utilities::MPI::this_mpi_process(s.mpi_communicator);
  const std::string stem = basename + "_" + Utilities::int_to_string(counter, 4);
  auto piece_name = [&stem](const unsigned int r)
  { return stem + "." + std::to_string(r) + ".vtu"; };
  {
    const std::string name = directory + "/" + piece_name(rank);
    std::ofstream file(name, std::ios::binary);
    if (!file)
      throw std::runtime_error("cannot write the field file " + name);
    output::write_vtu_piece(file, piece, {{"rank", std::vector<int>(n_cells, int(rank))}});
    if (!file.flush())
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
