#include <sealfe/film/annulus_mesh.h>

#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <fstream>
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
  prm.leave_subsection();
}

void AnnulusMesh::parse_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Discretization");
  radial_cells = prm.get_integer("Radial cells");
  circumferential_cells = prm.get_integer("Circumferential cells");
  global_refinements = prm.get_integer("Global refinements");
  mesh_file = prm.get("Mesh file");
  radial_grading = prm.get_bool("Radial grading");
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

void AnnulusMesh::check_memory(const unsigned int degree) const
{
  if (!mesh_file.empty())
    return;
  const double cells = double(radial_cells) * double(circumferential_cells) *
                       std::pow(4.0, double(global_refinements));
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
      << machine / 1e9 << " GB (lower Radial cells, Circumferential cells or Global refinements)";
    throw std::runtime_error(s.str());
  }
}

bool AnnulusMesh::can_coarsen(const unsigned int coarsening) const
{
  if (coarsening <= global_refinements)
    return true;
  if (!mesh_file.empty())
    return false;
  const unsigned int extra = coarsening - global_refinements;
  const unsigned int f = 1u << extra;
  return radial_cells % f == 0 && circumferential_cells % f == 0 && circumferential_cells / f >= 3;
}

std::vector<double> AnnulusMesh::radial_nodes(const unsigned int nr, const double ri,
                                              const double ro) const
{
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
} // namespace

void AnnulusMesh::create(parallel::distributed::Triangulation<2> &tria, const double ri,
                         const double ro, const unsigned int coarsening) const
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
    for (unsigned int j = 0; j < nt0; ++j)
      for (unsigned int i = 0; i <= nr0; ++i)
      {
        const double r = radii[i << extra], t = 2 * M_PI * j / nt0;
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
    std::ifstream in(mesh_file);
    if (!in)
      throw std::runtime_error("Discretization: Mesh file '" + mesh_file +
                               "' is missing or unreadable");
    GridIn<2> grid_in(coarse);
    try
    {
      grid_in.read_msh(in);
    }
    catch (std::exception &e)
    {
      throw std::runtime_error("Discretization: Mesh file '" + mesh_file +
                               "' is not a readable gmsh mesh");
    }
    set_boundary_ids(coarse, ri, ro, "Discretization: Mesh file '" + mesh_file + "'");
    // Every boundary face must have been classified; both circles must be present.
    bool has_inner = false, has_outer = false;
    for (const auto &face : coarse.active_face_iterators())
      if (face->at_boundary())
        (face->boundary_id() == inner_boundary ? has_inner : has_outer) = true;
    if (!has_inner || !has_outer)
      throw std::runtime_error("Discretization: Mesh file '" + mesh_file +
                               "' does not have both circles r = ri and r = ro on its boundary");
  }

  tria.copy_triangulation(coarse);
  tria.set_all_manifold_ids(0);
  tria.set_manifold(0, PolarManifold<2>(Point<2>()));
  tria.refine_global(refinements + extra);
  if (extra > 0)
    place_vertices(tria, radial_nodes(nr, ri, ro), nt, extra, refinements);
}

void AnnulusMesh::place_vertices(parallel::distributed::Triangulation<2> &tria,
                                 const std::vector<double> &radii, const unsigned int nt,
                                 const unsigned int extra, const unsigned int refinements)
{
  // Refinement on the polar manifold halves cells in (r, theta): a vertex lies at the mean radius
  // of its parents, i.e. the radii now interpolate the coarse nodes linearly. The mesh asked for
  // has the graded nodes `radii` (nr + 1 of them), refined `refinements` times the same way. Both
  // lists are sorted and far apart compared with round-off, so a vertex is identified by the
  // nearest radius of the first list and moved to the same index of the second; theta is put
  // back on the exact grid 2 pi j / (nt 2^refinements) that the direct construction uses.
  const unsigned int nr = radii.size() - 1;
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
  std::vector<double> coarse_radii;
  for (unsigned int i = 0; i <= nr; i += (1u << extra))
    coarse_radii.push_back(radii[i]);
  const std::vector<double> now = interpolate(coarse_radii, extra + refinements);
  const std::vector<double> wanted = interpolate(radii, refinements);
  const double n_theta = double(nt) * double(1u << refinements);
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
        double turns = std::atan2(x[1], x[0]) / (2 * M_PI);
        if (turns < 0)
          turns += 1;
        const long j = std::lround(turns * n_theta) % long(n_theta);
        const double t = 2 * M_PI * double(j) / n_theta;
        x = Point<2>(wanted[i] * std::cos(t), wanted[i] * std::sin(t));
      }
}

} // namespace sealfe
