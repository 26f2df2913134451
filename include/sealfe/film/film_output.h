// Field output of a film solve: pressure, film thickness, volume flux, flow factors, contact
// pressure, liquid fraction and cavitated region as VTU (per rank group) + PVTU + PVD.
#pragma once

#include <string>

namespace sealfe
{
class ReynoldsSolver;

/// Write the fields of the last run() of `solver` into `directory` (which must exist); returns
/// the PVD file name, "solution.pvd". Collective over the solver's communicator.
std::string write_film_output(const ReynoldsSolver &solver, const std::string &directory);

} // namespace sealfe
