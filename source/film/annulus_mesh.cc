#include <sealfe/film/annulus_mesh.h>
#include <sealfe/film/feature_mesh.h>

#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace sealfe
{
using namespace dealii;

void AnnulusMesh::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Discretization");
  prm.declare_entry("Radial cells", "8", Patterns::Integer(1),
                    "Cells across the dam (r direction) of the built-in annulus mesh.");
  prm.declare_entry("Circumferential cells", "128", Patterns::Integer(3),
                    "Cells around the annulus (theta direction) of the built-in mesh.");
  prm.declare_entry("Global refinements", "0", Patterns::Integer(0, 12),
                    "Uniform refinements of the coarse mesh (each halves the cells in r, theta).");
  prm.declare_entry("Radial grading", "true", Patterns::Bool(),
                    "Grade the built-in mesh radially: nodes equidistribute int dr/h0^1.5 of the "
                    "axisymmetric film h0(r), so cells are small where the film is thin (the "
                    "pressure gradient scales like 1/h^3). false: uniform radial cells.");
  prm.declare_entry("Mesh file", "", Patterns::Anything(),
                    "Optional gmsh .msh file of the annulus (replaces the built-in mesh). Its "
                    "boundary must be the two circles r = ri and r = ro of the Geometry section; "
                    "the boundary is classified by radius, physical tags are not needed.");
  prm.declare_entry("Mesh size", "0", Patterns::Double(0),
                    "> 0: generate the Mesh file with gmsh (overwriting it; empty: a temporary "
                    "file): all quadrilaterals of "
                    "about this size (m) with mesh lines on the circles of dimples (the film's "
                    "steps), then refined by Global refinements with the circles kept. The JFO "
                    "coarse levels are first this mesh refined fewer times (none at the coarsest "
                    "of these), then meshes generated at 2, 4, ... times this size. 0: read the "
                    "Mesh file as it is.");
  prm.declare_entry("Align with features", "true", Patterns::Bool(),
                    "Put cell edges of the built-in mesh on the steps of surface features "
                    "(pads: theta and r lines; spiral grooves: the mesh lines follow the spirals; "
                    "dimples: the band edges) when Circumferential cells is a multiple of their "
                    "number. false: the plain polar grid (for convergence comparisons).");
  prm.leave_subsection();
}

void AnnulusMesh::parse_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Discretization");
  radial_cells = prm.get_integer("Radial cells");
  circumferential_cells = prm.get_integer("Circumferential cells");
  global_refinements = prm.get_integer("Global refinements");
  mesh_file = prm.get("Mesh file");
  mesh_size = prm.get_double("Mesh size");
  if (mesh_size > 0 && mesh_file.empty())
  {
    // the generated mesh goes to a temporary file of this run
    static unsigned int count = 0;
    mesh_file =
        (std::filesystem::temp_directory_path() /
         ("sealfe-mesh-" + std::to_string(::getpid()) + "-" + std::to_string(count++) + ".msh"))
            .string();
    temporary_mesh_file = true;
  }
  radial_grading = prm.get_bool("Radial grading");
  align_with_features = prm.get_bool("Align with features");
  prm.leave_subsection();
}

void AnnulusMesh::check_resolves_waves(const double wave_number, const unsigned int degree) const
{
  if (!mesh_file.empty() || wave_number <= 0)
    return;
  const double cells =
      double(circumferential_cells) * double(1u << std::min(global_refinements, 20u));
  const double nodes_per_wave = cells * degree / wave_number;
  if (nodes_per_wave < 4)
  {
    std::ostringstream s;
    s << "Discretization: " << cells << " circumferential cells of degree " << degree << " give "
      << nodes_per_wave << " nodes per wave for Wave number = " << wave_number
      << "; at least 4 are needed to resolve the waviness (raise Circumferential cells to "
      << std::ceil(4 * wave_number / degree) << " or more)";
    throw std::runtime_error(s.str());
  }
}

void AnnulusMesh::check_memory(const unsigned int degree, const double ri, const double ro) const
{
  // a generated mesh: quads of about Mesh size over the dam, refined (checked before gmsh runs)
  const bool generated = mesh_size > 0 && ro > ri;
  if (!mesh_file.empty() && !generated)
    return;
  const double coarse_cells = generated
                                  ? numbers::PI * (ro * ro - ri * ri) / (mesh_size * mesh_size)
                                  : double(radial_cells) * double(circumferential_cells);
  const double cells = coarse_cells * std::pow(4.0, double(global_refinements));
  const double dofs = cells * degree * degree;
  const double stencil = (2.0 * degree + 1) * (2.0 * degree + 1);
  // matrix and graph (12 bytes a nonzero), the factorisation or AMG hierarchy and copies (x4),
  // about 30 vectors of 8 bytes
  const double bytes = dofs * (stencil * 12 * 4 + 30 * 8);
  const double machine = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGE_SIZE));
  if (machine > 0 && bytes > machine)
  {
    std::ostringstream s;
    s.precision(3);
    s << "Discretization: " << cells << " cells of degree " << degree << " (" << dofs
      << " unknowns) would need about " << bytes / 1e9 << " GB of memory; this machine has "
      << machine / 1e9 << " GB ("
      << (generated ? "raise Mesh size or lower Global refinements"
                    : "lower Radial cells, Circumferential cells or Global refinements")
      << ")";
    throw std::runtime_error(s.str());
  }
}

double AnnulusMesh::generated_size(const unsigned int coarsening) const
{
  if (!(mesh_size > 0) || coarsening <= global_refinements)
    return 0;
  return mesh_size * double(1u << std::min(coarsening - global_refinements, 20u));
}

bool AnnulusMesh::can_coarsen(const unsigned int coarsening) const
{
  if (coarsening <= global_refinements)
    return true;
  // a generated mesh: cells no larger than the circles (at least 8 faces around each: gmsh
  // meshes each circle as four quarter arcs)
  if (mesh_size > 0)
    return alignment.circle_radius > 0 && generated_size(coarsening) <= alignment.circle_radius;
  if (!mesh_file.empty())
    return false;
  const unsigned int extra = coarsening - global_refinements;
  const unsigned int f = 1u << extra;
  return radial_cells % f == 0 && circumferential_cells % f == 0 && circumferential_cells / f >= 3;
}

bool AnnulusMesh::sequences_jfo(const unsigned int coarsening, const double ri,
                                const double ro) const
{
  if (coarsening <= global_refinements)
    return true;
  // a mesh file or a generated gmsh mesh (mesh_size > 0, the file name may not be set yet when
  // used as a library): its coarser levels would be regenerated, which buys the start nothing
  if (mesh_size > 0 || !mesh_file.empty())
    return false;
  if (!(alignment.circle_radius > 0))
    return true;
  const double f = double(1u << std::min(coarsening - global_refinements, 20u));
  const double radial = (ro - ri) / radial_cells, around = 2 * M_PI * ro / circumferential_cells;
  return f * std::max(radial, around) <= alignment.circle_radius * (1 + 1e-9);
}

double AnnulusMesh::Alignment::shift(const double r) const
{
  if (spiral_cot == 0)
    return 0;
  return spiral_cot * std::log(std::min(std::max(r, spiral_r0), spiral_r1) / spiral_r0);
}

namespace
{
/// Share n cells among pieces of the given lengths (summing to 1) in proportion, at least one
/// each (largest remainders); empty if n is smaller than the number of pieces.
std::vector<unsigned int> share_cells(const unsigned int n, const std::vector<double> &lengths)
{
  const std::size_t m = lengths.size();
  if (n < m)
    return {};
  std::vector<unsigned int> count(m);
  std::vector<double> rest(m);
  unsigned int used = 0;
  for (std::size_t k = 0; k < m; ++k)
  {
    const double want = n * lengths[k];
    count[k] = std::max(1u, static_cast<unsigned int>(std::floor(want)));
    rest[k] = want - count[k];
    used += count[k];
  }
  while (used < n)
  {
    const std::size_t k = std::max_element(rest.begin(), rest.end()) - rest.begin();
    ++count[k];
    rest[k] -= 1;
    ++used;
  }
  while (used > n)
  {
    std::size_t best = m;
    for (std::size_t k = 0; k < m; ++k)
      if (count[k] > 1 && (best == m || rest[k] < rest[best]))
        best = k;
    if (best == m)
      return {};
    --count[best];
    rest[best] += 1;
    --used;
  }
  return count;
}
} // namespace

std::vector<double> AnnulusMesh::angular_nodes(const unsigned int nt) const
{
  std::vector<double> nodes(nt + 1);
  for (unsigned int j = 0; j <= nt; ++j)
    nodes[j] = 2 * M_PI * j / nt;
  const Alignment &a = alignment;
  if (!align_with_features || !mesh_file.empty() || a.periods == 0 || nt % a.periods != 0)
    return nodes;
  std::vector<double> breaks = a.theta_breaks;
  breaks.push_back(0);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  std::vector<double> lengths;
  for (std::size_t k = 0; k < breaks.size(); ++k)
    lengths.push_back((k + 1 < breaks.size() ? breaks[k + 1] : 1.0) - breaks[k]);
  const std::vector<unsigned int> count = share_cells(nt / a.periods, lengths);
  if (count.empty())
    return nodes;
  const double period = 2 * M_PI / a.periods;
  unsigned int j = 0;
  for (unsigned int p = 0; p < a.periods; ++p)
    for (std::size_t k = 0; k < breaks.size(); ++k)
      for (unsigned int c = 0; c < count[k]; ++c)
        nodes[j++] = a.phase + period * (p + breaks[k] + lengths[k] * c / count[k]);
  nodes[nt] = nodes[0] + 2 * M_PI;
  return nodes;
}

std::vector<double> AnnulusMesh::radial_nodes(const unsigned int nr, const double ri,
                                              const double ro) const
{
  std::vector<double> breaks;
  if (align_with_features && mesh_file.empty())
    for (const double b : alignment.radial_breaks)
      if (b > ri + 1e-9 * ro && b < ro - 1e-9 * ro)
        breaks.push_back(b);
  if (!breaks.empty())
  {
    // Nodes on the feature circles: the pieces between them get cells in proportion to their
    // share of the grading measure (uniform within each in that measure).
    AnnulusMesh plain = *this;
    plain.alignment.radial_breaks.clear();
    const unsigned int fine = 4096;
    const std::vector<double> map = plain.radial_nodes(fine, ri, ro); // s = i / fine
    auto to_s = [&](const double r)
    {
      const std::size_t i =
          std::min<std::size_t>(std::lower_bound(map.begin(), map.end(), r) - map.begin(), fine);
      if (i == 0)
        return 0.0;
      return (i - 1 + (r - map[i - 1]) / (map[i] - map[i - 1])) / fine;
    };
    auto from_s = [&](const double s)
    {
      const double x = std::min(std::max(s, 0.0), 1.0) * fine;
      const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(x), fine - 1);
      return map[i] + (x - i) * (map[i + 1] - map[i]);
    };
    std::sort(breaks.begin(), breaks.end());
    std::vector<double> s_breaks{0.0}, lengths;
    for (const double b : breaks)
      s_breaks.push_back(to_s(b));
    s_breaks.push_back(1.0);
    for (std::size_t k = 0; k + 1 < s_breaks.size(); ++k)
      lengths.push_back(s_breaks[k + 1] - s_breaks[k]);
    const std::vector<unsigned int> count = share_cells(nr, lengths);
    if (!count.empty())
    {
      std::vector<double> nodes{ri};
      for (std::size_t k = 0; k < count.size(); ++k)
        for (unsigned int c = 1; c <= count[k]; ++c)
          nodes.push_back(c == count[k] ? (k < breaks.size() ? breaks[k] : ro)
                                        : from_s(s_breaks[k] + lengths[k] * c / count[k]));
      return nodes;
    }
  }
  std::vector<double> nodes(nr + 1);
  for (unsigned int i = 0; i <= nr; ++i)
    nodes[i] = ri + (ro - ri) * i / nr;
  const double h_in = grading_clearance, h_out = grading_clearance + grading_coning * (ro - ri);
  if (!radial_grading || !(h_in > 0) || !(h_out > 0) || std::abs(h_out / h_in - 1) < 1e-3)
    return nodes;
  // W(r) = int_ri^r h0(s)^-a ds = (h_in^(1-a) - h0(r)^(1-a)) / (b (a - 1)); invert W at equal
  // fractions of W(ro).
  const double b = grading_coning, a = grading_exponent;
  auto W = [&](double h) { return (std::pow(h_in, 1 - a) - std::pow(h, 1 - a)) / (b * (a - 1)); };
  const double total = W(h_out);
  for (unsigned int i = 1; i < nr; ++i)
  {
    const double w = total * i / nr;
    const double h = std::pow(std::pow(h_in, 1 - a) - w * b * (a - 1), 1 / (1 - a));
    nodes[i] = ri + (h - h_in) / b;
  }
  return nodes;
}

namespace
{
/// Classify each boundary face of a mesh by its radius; throw if it is not on r = ri or r = ro.
void set_boundary_ids(Triangulation<2> &tria, const double ri, const double ro,
                      const std::string &where)
{
  const double tol = 1e-6 * ro;
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto f : cell->face_indices())
      if (cell->face(f)->at_boundary())
      {
        const auto face = cell->face(f);
        const double r0 = face->vertex(0).norm(), r1 = face->vertex(1).norm();
        if (std::abs(r0 - ri) < tol && std::abs(r1 - ri) < tol)
          face->set_boundary_id(AnnulusMesh::inner_boundary);
        else if (std::abs(r0 - ro) < tol && std::abs(r1 - ro) < tol)
          face->set_boundary_id(AnnulusMesh::outer_boundary);
        else
        {
          std::ostringstream s;
          s << where << " is not an annulus ri = " << ri << " m .. ro = " << ro
            << " m: a boundary edge runs from radius " << r0 << " m to " << r1 << " m";
          throw std::runtime_error(s.str());
        }
      }
}

/// Give the faces that lie on one of the alignment's circles (both vertices on it) a
/// PolarManifold about its centre (manifold ids 1, 2, ...), so that refinement and a higher-order
/// mapping keep them on the circle; the rest keeps the annulus' manifold 0.
void attach_circles(Triangulation<2> &tria, const AnnulusMesh::Alignment &alignment)
{
  const double R = alignment.circle_radius, tol = 1e-6 * R;
  if (!(R > 0) || alignment.circle_centres.empty())
    return;
  // centres hashed on a grid of spacing 2 R: a point within R of a centre is in one of the 3 x 3
  // buckets around its own
  std::map<std::pair<long, long>, std::vector<unsigned int>> buckets;
  auto key = [&](const Point<2> &x)
  { return std::make_pair(long(std::floor(x[0] / (2 * R))), long(std::floor(x[1] / (2 * R)))); };
  for (unsigned int k = 0; k < alignment.circle_centres.size(); ++k)
    buckets[key(alignment.circle_centres[k])].push_back(k);
  auto circle_of = [&](const Point<2> &x) -> int
  {
    const auto [i, j] = key(x);
    for (long di = -1; di <= 1; ++di)
      for (long dj = -1; dj <= 1; ++dj)
      {
        const auto it = buckets.find({i + di, j + dj});
        if (it != buckets.end())
          for (const unsigned int k : it->second)
            if (std::abs(x.distance(alignment.circle_centres[k]) - R) < tol)
              return int(k);
      }
    return -1;
  };
  std::vector<bool> used(alignment.circle_centres.size(), false);
  for (const auto &cell : tria.active_cell_iterators())
    for (const auto f : cell->face_indices())
    {
      const auto face = cell->face(f);
      const int k = circle_of(face->vertex(0));
      if (k >= 0 && circle_of(face->vertex(1)) == k &&
          face->vertex(0).distance(face->vertex(1)) < R)
      {
        face->set_manifold_id(1 + k);
        used[k] = true;
      }
    }
  for (unsigned int k = 0; k < used.size(); ++k)
    if (used[k])
      tria.set_manifold(1 + k, PolarManifold<2>(alignment.circle_centres[k]));
}
} // namespace

void AnnulusMesh::create(Triangulation<2> &tria, const double ri, const double ro,
                         const unsigned int coarsening) const
{
  if (!can_coarsen(coarsening))
    throw std::runtime_error("Discretization: cannot build a mesh coarser than the one asked for");
  unsigned int refinements = global_refinements;
  unsigned int nr = radial_cells, nt = circumferential_cells;
  if (coarsening <= global_refinements)
    refinements -= coarsening;
  else
  {
    refinements = 0;
    nr >>= (coarsening - global_refinements);
    nt >>= (coarsening - global_refinements);
  }

  Triangulation<2> coarse;
  // Built-in mesh: a coarse polar grid, `extra` times coarser than the nr x nt cells asked for,
  // refined globally, then every vertex put where the direct construction would put it. p4est
  // then holds a few coarse cells (trees) instead of one per cell: at 128 x 2048 cells the
  // setup of one tree per cell took most of the setup stage (doc/performance.md).
  unsigned int extra = 0;
  if (mesh_file.empty())
    while ((nr >> extra) % 2 == 0 && (nt >> extra) % 2 == 0 &&
           (nt >> extra) / 2 >= min_coarse_cells)
      ++extra;
  if (mesh_file.empty())
  {
    // Vertices on a polar grid; cells (i, j) span [r_i, r_i+1] x [theta_j, theta_j+1], wrapping
    // around in theta. Lexicographic vertex order (r fastest) keeps the cells right-handed.
    const unsigned int nr0 = nr >> extra, nt0 = nt >> extra;
    std::vector<Point<2>> vertices;
    const std::vector<double> radii = radial_nodes(nr, ri, ro);
    const std::vector<double> angles = angular_nodes(nt);
    for (unsigned int j = 0; j < nt0; ++j)
      for (unsigned int i = 0; i <= nr0; ++i)
      {
        const double r = radii[i << extra], t = angles[j << extra] + alignment.shift(r);
        vertices.emplace_back(r * std::cos(t), r * std::sin(t));
      }
    auto index = [&](unsigned int i, unsigned int j) { return (j % nt0) * (nr0 + 1) + i; };
    std::vector<CellData<2>> cells;
    for (unsigned int j = 0; j < nt0; ++j)
      for (unsigned int i = 0; i < nr0; ++i)
      {
        CellData<2> c;
        c.vertices = {index(i, j), index(i + 1, j), index(i, j + 1), index(i + 1, j + 1)};
        cells.push_back(c);
      }
    coarse.create_triangulation(vertices, cells, SubCellData());
    set_boundary_ids(coarse, ri, ro, "built-in mesh");
  }
  else
  {
    // Generated mesh: the file asked for at Mesh size (refined), or a coarser one in a temporary
    // file for the coarse levels. Rank 0 generates and reads the file and sends its text to all
    // ranks (which may be on other nodes, without that file); all agree on an error before any
    // throws. Every rank parses the same text, so they fail or succeed together.
    const MPI_Comm comm = tria.get_communicator();
    std::string file = mesh_file, text, error;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      try
      {
        // a temporary file is removed once read, or on an error
        struct RemoveFile
        {
          std::string path;
          ~RemoveFile()
          {
            std::error_code ignored;
            if (!path.empty())
              std::filesystem::remove(path, ignored);
          }
        } remove_file;
        if (mesh_size > 0)
        {
          const double size =
              coarsening > global_refinements ? generated_size(coarsening) : mesh_size;
          if (coarsening > global_refinements)
          {
            std::string name =
                (std::filesystem::temp_directory_path() / "sealfe-coarse-XXXXXX").string();
            const int fd = ::mkstemp(name.data());
            if (fd < 0)
              throw std::runtime_error("Discretization: cannot create a temporary file for the "
                                       "coarse mesh in " +
                                       std::filesystem::temp_directory_path().string());
            ::close(fd);
            std::filesystem::remove(name);
            file = name + ".msh";
          }
          if (file != mesh_file || temporary_mesh_file)
            remove_file.path = file;
          FeatureMesh::generate(FeatureMesh::geometry(ri, ro, alignment.circle_centres,
                                                      alignment.circle_radius, size),
                                file);
        }
        std::ifstream in(file);
        if (!in)
          throw std::runtime_error("Discretization: Mesh file '" + file +
                                   "' is missing or unreadable");
        std::ostringstream s;
        s << in.rdbuf();
        text = s.str();
      }
      catch (std::exception &e)
      {
        error = e.what();
      }
    error = Utilities::MPI::broadcast(comm, error, 0);
    if (!error.empty())
      throw std::runtime_error(error);
    file = Utilities::MPI::broadcast(comm, file, 0);
    text = Utilities::MPI::broadcast(comm, text, 0);
    std::istringstream in(text);
    GridIn<2> grid_in(coarse);
    try
    {
      grid_in.read_msh(in);
    }
    catch (std::exception &e)
    {
      throw std::runtime_error("Discretization: Mesh file '" + file +
                               "' is not a readable gmsh mesh");
    }
    set_boundary_ids(coarse, ri, ro, "Discretization: Mesh file '" + file + "'");
    // Every boundary face must have been classified; both circles must be present.
    bool has_inner = false, has_outer = false;
    for (const auto &face : coarse.active_face_iterators())
      if (face->at_boundary())
        (face->boundary_id() == inner_boundary ? has_inner : has_outer) = true;
    if (!has_inner || !has_outer)
      throw std::runtime_error("Discretization: Mesh file '" + file +
                               "' does not have both circles r = ri and r = ro on its boundary");
  }

  tria.copy_triangulation(coarse);
  tria.set_all_manifold_ids(0);
  tria.set_manifold(0, PolarManifold<2>(Point<2>()));
  if (!mesh_file.empty())
    attach_circles(tria, alignment);
  tria.refine_global(refinements + extra);
  if (extra > 0)
    place_vertices(tria, radial_nodes(nr, ri, ro), nt, extra, refinements);
}

void AnnulusMesh::place_vertices(Triangulation<2> &tria, const std::vector<double> &radii,
                                 const unsigned int nt, const unsigned int extra,
                                 const unsigned int refinements) const
{
  // Refinement on the polar manifold halves cells in (r, theta): a vertex lies at the mean radius
  // and mean angle of its parents, i.e. radii and angles (and the spiral shift of the angles) now
  // interpolate the coarse nodes linearly in the index. The mesh asked for has the nodes `radii`
  // and angular_nodes(nt), refined `refinements` times the same way. The lists are sorted and far
  // apart compared with round-off, so a vertex is identified by the nearest radius and the
  // nearest (unshifted) angle of the first lists and moved to the same indices of the second.
  auto interpolate = [](const std::vector<double> &nodes, const unsigned int levels)
  {
    const unsigned int f = 1u << levels, n = nodes.size() - 1;
    std::vector<double> out(n * f + 1);
    for (unsigned int i = 0; i < n * f; ++i)
    {
      const double s = double(i % f) / f;
      out[i] = (1 - s) * nodes[i / f] + s * nodes[i / f + 1];
    }
    out[n * f] = nodes[n];
    return out;
  };
  const unsigned int nr = radii.size() - 1;
  const std::vector<double> angles = angular_nodes(nt);
  std::vector<double> coarse_radii, coarse_shift, coarse_angles;
  for (unsigned int i = 0; i <= nr; i += (1u << extra))
  {
    coarse_radii.push_back(radii[i]);
    coarse_shift.push_back(alignment.shift(radii[i]));
  }
  for (unsigned int j = 0; j <= nt; j += (1u << extra))
    coarse_angles.push_back(angles[j]);
  const std::vector<double> now = interpolate(coarse_radii, extra + refinements);
  const std::vector<double> now_shift = interpolate(coarse_shift, extra + refinements);
  const std::vector<double> now_angles = interpolate(coarse_angles, extra + refinements);
  const std::vector<double> wanted = interpolate(radii, refinements);
  const std::vector<double> wanted_angles = interpolate(angles, refinements);
  const std::size_t n_theta = now_angles.size() - 1;
  std::vector<double> uniform(nt + 1);
  for (unsigned int j = 0; j <= nt; ++j)
    uniform[j] = 2 * M_PI * j / nt;
  const bool plain = angles == uniform && alignment.spiral_cot == 0;
  std::vector<bool> moved(tria.n_vertices(), false);
  for (const auto &cell : tria.active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
      if (!moved[cell->vertex_index(v)])
      {
        moved[cell->vertex_index(v)] = true;
        Point<2> &x = cell->vertex(v);
        const double rho = x.norm();
        const auto above = std::lower_bound(now.begin(), now.end(), rho);
        std::size_t i = above - now.begin();
        if (i == now.size() || (i > 0 && rho - now[i - 1] < *above - rho))
          --i;
        // angle without the spiral shift, brought into [now_angles[0], now_angles[0] + 2 pi)
        double t = std::atan2(x[1], x[0]) - now_shift[i] - now_angles[0];
        t -= 2 * M_PI * std::floor(t / (2 * M_PI));
        t += now_angles[0];
        const auto after = std::lower_bound(now_angles.begin(), now_angles.end(), t);
        std::size_t j = after - now_angles.begin();
        if (j == now_angles.size() || (j > 0 && t - now_angles[j - 1] < *after - t))
          --j;
        j %= n_theta;
        // the plain polar grid keeps its exact angles 2 pi j / n
        const double theta = plain ? 2 * M_PI * double(j) / double(n_theta)
                                   : wanted_angles[j] + alignment.shift(wanted[i]);
        x = Point<2>(wanted[i] * std::cos(theta), wanted[i] * std::sin(theta));
      }
}

} // namespace sealfe
