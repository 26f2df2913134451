// FeatureMesh: an all-quadrilateral gmsh mesh of the dam whose lines follow the circular steps of
// the film (dimples), written as a gmsh geometry and meshed by the gmsh program.
#pragma once

#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace sealfe::FeatureMesh
{
/// The gmsh geometry (.geo text) of the annulus ri..ro with the circles of radius `radius` about
/// `centres` as inner curves (each disc its own surface, so that mesh lines lie on the circles),
/// meshed into quadrilaterals of about `size` (m): Frontal-Delaunay triangles of size 2 `size`,
/// recombined (Blossom) and subdivided once (all quads). Boundary tags 1 (r = ri), 2 (r = ro).
std::string geometry(const double ri, const double ro, const std::vector<dealii::Point<2>> &centres,
                     const double radius, const double size);

/// Meshes `geo_text` with the gmsh program into `msh_file` (gmsh 2.2 ASCII, the format GridIn
/// reads), which appears whole (renamed into place) or not at all. Throws std::runtime_error with
/// gmsh's last message if gmsh is missing or fails.
void generate(const std::string &geo_text, const std::string &msh_file);
} // namespace sealfe::FeatureMesh
