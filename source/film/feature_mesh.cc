#include <sealfe/film/feature_mesh.h>

#include <deal.II/base/config.h>
#include <deal.II/base/numbers.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace sealfe::FeatureMesh
{
namespace
{
struct GeoWriter
{
  std::ostringstream out;
  unsigned int points = 0, curves = 0, loops = 0;
  GeoWriter() { out.precision(17); }
  unsigned int point(const double x, const double y)
  {
    out << "Point(" << ++points << ") = {" << x << ", " << y << ", 0};\n";
    return points;
  }
  /// A circle as four quarter arcs (gmsh's Circle needs arcs below pi); returns its curve loop
  /// and the tags of the arcs.
  unsigned int circle(const dealii::Point<2> &c, const double r, std::vector<unsigned int> &arcs)
  {
    const unsigned int centre = point(c[0], c[1]);
    unsigned int on[4];
    for (unsigned int k = 0; k < 4; ++k)
      on[k] = point(c[0] + r * std::cos(k * dealii::numbers::PI / 2),
                    c[1] + r * std::sin(k * dealii::numbers::PI / 2));
    arcs.clear();
    for (unsigned int k = 0; k < 4; ++k)
    {
      out << "Circle(" << ++curves << ") = {" << on[k] << ", " << centre << ", " << on[(k + 1) % 4]
          << "};\n";
      arcs.push_back(curves);
    }
    out << "Curve Loop(" << ++loops << ") = {" << arcs[0] << ", " << arcs[1] << ", " << arcs[2]
        << ", " << arcs[3] << "};\n";
    return loops;
  }
};

std::string list(const std::vector<unsigned int> &tags)
{
  std::ostringstream s;
  for (std::size_t k = 0; k < tags.size(); ++k)
    s << (k ? ", " : "") << tags[k];
  return s.str();
}

/// `text` as one word for /bin/sh: in single quotes, each ' written as '\''.
std::string shell_quoted(const std::string &text)
{
  std::string q = "'";
  for (const char c : text)
    q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}
} // namespace

std::string geometry(const double ri, const double ro, const std::vector<dealii::Point<2>> &centres,
                     const double radius, const double size)
{
  GeoWriter w;
  w.out << "// sealfe: the dam " << ri << " .. " << ro << " m with " << centres.size()
        << " circles of radius " << radius << " m as mesh lines, quads of about " << size << " m\n";
  // Triangles of twice the size, recombined and then subdivided once: all quadrilaterals of about
  // `size`. (gmsh 4.8's Frontal-Delaunay for quads, Algorithm 8, crashes on the holed annulus.)
  w.out << "Mesh.MeshSizeMin = " << 2 * size << ";\nMesh.MeshSizeMax = " << 2 * size << ";\n"
        << "Mesh.MeshSizeFromPoints = 0;\nMesh.MeshSizeExtendFromBoundary = 0;\n"
        << "Mesh.MeshSizeFromCurvature = 0;\nMesh.Algorithm = 6;\nMesh.RecombineAll = 1;\n"
        << "Mesh.RecombinationAlgorithm = 1;\nMesh.SubdivisionAlgorithm = 1;\n"
        << "Mesh.Smoothing = 2;\nMesh.MshFileVersion = 2.2;\n";
  std::vector<unsigned int> inner_arcs, outer_arcs, arcs, holes;
  const dealii::Point<2> origin;
  const unsigned int inner = w.circle(origin, ri, inner_arcs);
  const unsigned int outer = w.circle(origin, ro, outer_arcs);
  for (const dealii::Point<2> &c : centres)
  {
    const unsigned int loop = w.circle(c, radius, arcs);
    w.out << "Plane Surface(" << loop << ") = {" << loop << "};\n";
    holes.push_back(loop);
  }
  const unsigned int land = w.loops + 1;
  std::vector<unsigned int> land_loops{outer, inner};
  land_loops.insert(land_loops.end(), holes.begin(), holes.end());
  w.out << "Plane Surface(" << land << ") = {" << list(land_loops) << "};\n";
  // Physical groups: gmsh writes only their elements. One surface group (material id 3, as in
  // meshes/annulus.geo); sealfe classifies the boundary by radius.
  std::vector<unsigned int> surfaces{land};
  surfaces.insert(surfaces.end(), holes.begin(), holes.end());
  w.out << "Physical Curve(\"inner\", 1) = {" << list(inner_arcs) << "};\n"
        << "Physical Curve(\"outer\", 2) = {" << list(outer_arcs) << "};\n"
        << "Physical Surface(\"dam\", 3) = {" << list(surfaces) << "};\n";
  return w.out.str();
}

void generate(const std::string &geo_text, const std::string &msh_file)
{
#ifdef DEAL_II_GMSH_EXECUTABLE_PATH
  const std::string gmsh = DEAL_II_GMSH_EXECUTABLE_PATH;
#else
  const std::string gmsh = "gmsh";
#endif
  namespace fs = std::filesystem;
  // A directory of its own for the geometry, gmsh's output and messages: several processes may
  // generate the same file at once (the ranks of `sealfe table`, two runs of one prm). The target
  // appears only whole, by a rename, so no reader sees a half-written file and no process removes
  // another's fresh one.
  std::string pattern = (fs::temp_directory_path() / "sealfe-mesh-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw std::runtime_error("Discretization: cannot create a temporary directory for gmsh");
  const fs::path dir = pattern;
  struct RemoveDirectory
  {
    fs::path path;
    ~RemoveDirectory()
    {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } remove_dir{dir};
  const fs::path geo = dir / "features.geo", log = dir / "gmsh.log", out = dir / "mesh.msh";
  std::ofstream(geo) << geo_text;
  const std::string command = shell_quoted(gmsh) + " -2 " + shell_quoted(geo.string()) + " -o " +
                              shell_quoted(out.string()) + " -v 2 > " + shell_quoted(log.string()) +
                              " 2>&1";
  const int status = std::system(command.c_str());
  if (status != 0 || !fs::exists(out))
  {
    std::string last;
    std::ifstream in(log);
    for (std::string line; std::getline(in, line);)
      if (!line.empty())
        last = line;
    throw std::runtime_error("Discretization: gmsh ('" + gmsh + "') failed to mesh the dam with " +
                             "its features into '" + msh_file + "'" +
                             (last.empty() ? std::string() : ": " + last));
  }
  const fs::path target = fs::absolute(msh_file);
  std::error_code error;
  if (target.has_parent_path())
    fs::create_directories(target.parent_path(), error);
  fs::rename(out, target, error);
  if (error)
  {
    // another file system: a copy beside the target, then the (atomic) rename onto it
    const fs::path copy =
        target.parent_path() / (target.filename().string() + ".tmp." + std::to_string(::getpid()));
    error.clear();
    fs::copy_file(out, copy, fs::copy_options::overwrite_existing, error);
    if (!error)
      fs::rename(copy, target, error);
    if (error)
    {
      std::error_code ignored;
      fs::remove(copy, ignored);
      throw std::runtime_error("Discretization: cannot write the generated mesh to '" + msh_file +
                               "': " + error.message());
    }
  }
}
} // namespace sealfe::FeatureMesh
