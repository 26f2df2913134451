// Field output of a film solve: pressure, film thickness, the conserved volume flux, flow
// factors, contact pressure, liquid fraction and cavitated region as point data of Lagrange
// cells of the element's degree, and the owning MPI rank as cell data; VTU + PVTU + PVD.
#pragma once

#include <sealfe/film/film_settings.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace sealfe
{
class ReynoldsSolver;

/// Which fields the VTU carries (`Output/Fields`): "all" writes every field the film model has;
/// a list writes only those (each field is a share of the write, which at 1e6 dofs is seconds).
struct FieldSelection
{
  /// Declares "Fields" in the current subsection.
  static void declare_parameters(dealii::ParameterHandler &prm);
  /// Reads "Fields" in the current subsection; one-line error for an unknown name.
  void parse_parameters(dealii::ParameterHandler &prm);
  /// Throws std::runtime_error naming a requested field that the model of `settings` does not
  /// have (liquid fraction without JFO, flow factors with smooth faces, ...). Call it before the
  /// solve so that a bad list costs nothing.
  void check_against(const FilmSettings &settings) const;

  /// "all" (the default: every flag set; a field the model lacks is then skipped, not refused)
  /// or a list naming the fields.
  bool everything = true;
  bool pressure = true, film_thickness = true, volume_flux = true, flow_factors = true,
       contact_pressure = true, liquid_fraction = true, cavitated = true;
};

/// Write the fields of the last run() of `solver` into `directory` (which must exist); returns
/// the PVD file name, "solution.pvd". Collective over the solver's communicator. On the built-in
/// annulus the output points and their shape values come from one FEValues evaluation per radial
/// row (PolarCellValues), as in the assembly; with a mesh file or `solver.polar_rows` false,
/// from deal.II's DataOut::build_patches (the same values to round-off).
std::string write_film_output(const ReynoldsSolver &solver, const std::string &directory,
                              const FieldSelection &fields = FieldSelection());

/// The same fields as `<basename>_<counter>.pvtu` (+ its VTU pieces) without a PVD, for a time
/// series whose PVD the caller writes; returns the PVTU file name. `frame_angle`: the angle of
/// the frame the solver worked in from the stator frame (rotor-borne features at rotor angle phi
/// are solved in their own frame, FilmState::feature_frame_angle); the points and the flux are
/// turned by it, so that every picture of a time series stands in the stator frame.
std::string write_film_fields(const ReynoldsSolver &solver, const std::string &directory,
                              const std::string &basename, unsigned int counter,
                              const FieldSelection &fields = FieldSelection(),
                              double frame_angle = 0);

} // namespace sealfe
