// Field output of a film solve: pressure, film thickness, the conserved volume flux, flow
// factors, contact pressure, liquid fraction and cavitated region as point data of Lagrange
// cells of the element's degree, and the owning MPI rank as cell data; VTU + PVTU + PVD.
#pragma once

#include <string>

namespace sealfe
{
class ReynoldsSolver;

/// Write the fields of the last run() of `solver` into `directory` (which must exist); returns
/// the PVD file name, "solution.pvd". Collective over the solver's communicator.
std::string write_film_output(const ReynoldsSolver &solver, const std::string &directory);

/// The same fields as `<basename>_<counter>.pvtu` (+ its VTU pieces) without a PVD, for a time
/// series whose PVD the caller writes; returns the PVTU file name.
std::string write_film_fields(const ReynoldsSolver &solver, const std::string &directory,
                              const std::string &basename, unsigned int counter);

} // namespace sealfe
