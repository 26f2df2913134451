#include <sealfe/io/vtu_piece.h>

#include <lz4.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
namespace output
{
namespace
{
/// Position of lattice point (i, j), i, j in [0, n], in VTK's node order of a Lagrange
/// quadrilateral of order n: the 4 vertices, the edges (0-1, 1-2, 3-2, 0-3), then the interior
/// with i fastest (vtkHigherOrderQuadrilateral::PointIndexFromIJK).
unsigned int vtk_node_index(const unsigned int i, const unsigned int j, const unsigned int n)
{
  const bool i_boundary = i == 0 || i == n, j_boundary = j == 0 || j == n;
  if (i_boundary && j_boundary)
    return i ? (j ? 2 : 1) : (j ? 3 : 0);
  if (j_boundary) // on an edge along i
    return 4 + (i - 1) + (j ? 2 * (n - 1) : 0);
  if (i_boundary) // on an edge along j
    return 4 + (j - 1) + (i ? n - 1 : 3 * (n - 1));
  return 4 + 4 * (n - 1) + (i - 1) + (n - 1) * (j - 1);
}

/// The appended-data section: every array as VTK's compressed-block header (UInt64: number of
/// blocks, block size, size of a partial last block or 0, the compressed size of each block)
/// followed by its LZ4 blocks.
class AppendedData
{
public:
  /// Appends `bytes` and returns the offset the DataArray element names.
  std::size_t add(const void *bytes, const std::size_t size)
  {
    const std::size_t offset = data.size();
    const std::size_t n_full = size / block_size, last = size % block_size;
    const std::size_t n_blocks = n_full + (last ? 1 : 0);
    std::vector<std::uint64_t> header{n_blocks, block_size, last};
    std::string blocks;
    const char *source = static_cast<const char *>(bytes);
    std::vector<char> buffer(LZ4_compressBound(block_size));
    for (std::size_t b = 0; b < n_blocks; ++b)
    {
      const std::size_t n = (b == n_full) ? last : block_size;
      const int compressed =
          LZ4_compress_default(source + b * block_size, buffer.data(), int(n), int(buffer.size()));
      if (compressed <= 0)
        throw std::runtime_error("LZ4 could not compress a block of the VTU output");
      header.push_back(std::uint64_t(compressed));
      blocks.append(buffer.data(), std::size_t(compressed));
    }
    data.append(reinterpret_cast<const char *>(header.data()),
                header.size() * sizeof(std::uint64_t));
    data += blocks;
    return offset;
  }
  template <typename T>
  std::size_t add(const std::vector<T> &values)
  {
    return add(values.data(), values.size() * sizeof(T));
  }
  const std::string &bytes() const { return data; }

private:
  // 1 MiB of uncompressed data per block: large enough that the headers cost nothing, small
  // enough for a reader's buffer
  static constexpr std::size_t block_size = std::size_t(1) << 20;
  std::string data;
};

/// One point array of a piece: its name, its number of components (3 for a 2D vector, padded
/// with 0), and the first of its data sets. Vectors first, then the scalars, in data-set order:
/// the order of the piece's arrays and of the .pvtu record's.
struct ArrayLayout
{
  std::string name;
  unsigned int components, first_set;
};

std::vector<ArrayLayout> array_layouts(const VtuFields &fields)
{
  std::vector<ArrayLayout> arrays;
  std::vector<bool> in_vector(fields.names.size(), false);
  for (const auto &[first, name] : fields.vectors)
  {
    arrays.push_back({name, 3, first});
    in_vector.at(first) = in_vector.at(first + 1) = true;
  }
  for (unsigned int set = 0; set < fields.names.size(); ++set)
    if (!in_vector[set])
      arrays.push_back({fields.names[set], 1, set});
  return arrays;
}

std::string data_array(const std::string &type, const std::string &name,
                       const unsigned int components, const std::size_t offset)
{
  std::ostringstream s;
  s << "<DataArray type=\"" << type << "\"";
  if (!name.empty())
    s << " Name=\"" << name << "\"";
  s << " NumberOfComponents=\"" << components << "\" format=\"appended\" offset=\"" << offset
    << "\"/>\n";
  return s.str();
}
} // namespace

VtuPieceArrays::VtuPieceArrays(const VtuFields &fields, const std::size_t n_cells,
                               const unsigned int n_subdivisions, const double rotation)
    : cells(n_cells), order(n_subdivisions),
      points_per_cell((n_subdivisions + 1) * (n_subdivisions + 1)), n_sets(fields.names.size()),
      cos_r(std::cos(rotation)), sin_r(std::sin(rotation))
{
  if (n_points() > std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw std::runtime_error("VTU output: more points than a 32-bit connectivity can name");
  point_coordinates.resize(3 * n_points());
  filled.assign(n_cells, false);
  for (const ArrayLayout &array : array_layouts(fields))
    arrays.push_back({array.name, array.components, array.first_set,
                      std::vector<float>(array.components * n_points())});
}

void VtuPieceArrays::set_cell(const std::size_t cell, const dealii::DataOutBase::Patch<2, 2> &patch)
{
  const unsigned int n = patch.n_subdivisions, per_row = n + 1;
  if (n != order || cell >= cells)
    throw std::runtime_error("VTU output: a patch of " + std::to_string(n) +
                             " subdivisions as cell " + std::to_string(cell) + " of a piece of " +
                             std::to_string(cells) + " cells of " + std::to_string(order));
  if (!filled[cell])
  {
    filled[cell] = true;
    ++n_filled;
  }
  const std::size_t first = cell * points_per_cell;
  float *point = point_coordinates.data() + 3 * first;
  for (unsigned int j = 0; j <= n; ++j)
    for (unsigned int i = 0; i <= n; ++i, point += 3)
    {
      double x, y;
      if (patch.points_are_available)
      {
        x = patch.data(n_sets, i + j * per_row);
        y = patch.data(n_sets + 1, i + j * per_row);
      }
      else
      {
        const double u = double(i) / n, v = double(j) / n;
        const auto p = (1 - u) * (1 - v) * patch.vertices[0] + u * (1 - v) * patch.vertices[1] +
                       (1 - u) * v * patch.vertices[2] + u * v * patch.vertices[3];
        x = p[0];
        y = p[1];
      }
      point[0] = float(cos_r * x - sin_r * y);
      point[1] = float(sin_r * x + cos_r * y);
      point[2] = 0.0f;
    }
  for (PointArray &array : arrays)
  {
    const unsigned int set = array.first_set;
    float *value = array.values.data() + array.components * first;
    if (array.components == 1)
      for (unsigned int q = 0; q < points_per_cell; ++q)
        value[q] = patch.data(set, q);
    else
      for (unsigned int q = 0; q < points_per_cell; ++q, value += 3)
      {
        const double vx = patch.data(set, q), vy = patch.data(set + 1, q);
        value[0] = float(cos_r * vx - sin_r * vy);
        value[1] = float(sin_r * vx + cos_r * vy);
        value[2] = 0.0f;
      }
  }
}

void write_vtu_piece(std::ostream &out, const VtuPieceArrays &piece,
                     const std::vector<std::pair<std::string, std::vector<int>>> &cell_data)
{
  if (!piece.complete())
    throw std::runtime_error("VTU output: a piece of " + std::to_string(piece.n_cells()) +
                             " cells with some of them not set");
  // connectivity in VTK's node order, offsets, cell types
  const unsigned int n = piece.n_subdivisions(), per_row = n + 1;
  const std::size_t per_cell = per_row * per_row, n_cells = piece.n_cells();
  std::vector<std::int32_t> node_of(per_cell);
  for (unsigned int j = 0; j <= n; ++j)
    for (unsigned int i = 0; i <= n; ++i)
      node_of[vtk_node_index(i, j, n)] = std::int32_t(i + j * per_row);
  std::vector<std::int32_t> connectivity(per_cell * n_cells), offsets(n_cells);
  for (std::size_t c = 0; c < n_cells; ++c)
  {
    const std::int32_t first = std::int32_t(c * per_cell);
    for (std::size_t k = 0; k < per_cell; ++k)
      connectivity[c * per_cell + k] = first + node_of[k];
    offsets[c] = std::int32_t(first + per_cell);
  }
  const std::vector<std::uint8_t> types(n_cells, 70 /* VTK_LAGRANGE_QUADRILATERAL */);

  AppendedData appended;
  std::string point_data, cell_arrays;
  for (const VtuPieceArrays::PointArray &array : piece.point_arrays())
    point_data += data_array("Float32", array.name, array.components, appended.add(array.values));
  for (const auto &[name, values] : cell_data)
  {
    if (values.size() != n_cells)
      throw std::runtime_error("VTU output: cell array " + name + " has the wrong length");
    std::vector<std::int32_t> v(values.begin(), values.end());
    cell_arrays += data_array("Int32", name, 1, appended.add(v));
  }
  const std::string points_array = data_array("Float32", "", 3, appended.add(piece.points()));
  // one statement each: the arrays' order in the file does not depend on the compiler
  std::string cells = data_array("Int32", "connectivity", 1, appended.add(connectivity));
  cells += data_array("Int32", "offsets", 1, appended.add(offsets));
  cells += data_array("UInt8", "types", 1, appended.add(types));

  const std::uint16_t one = 1;
  std::uint8_t first_byte;
  std::memcpy(&first_byte, &one, 1);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\""
      << (first_byte == 1 ? "LittleEndian" : "BigEndian")
      << "\" header_type=\"UInt64\" compressor=\"vtkLZ4DataCompressor\">\n"
      << "<UnstructuredGrid>\n"
      << "<Piece NumberOfPoints=\"" << piece.n_points() << "\" NumberOfCells=\"" << n_cells
      << "\">\n"
      << "<PointData>\n"
      << point_data << "</PointData>\n"
      << "<CellData>\n"
      << cell_arrays << "</CellData>\n"
      << "<Points>\n"
      << points_array << "</Points>\n"
      << "<Cells>\n"
      << cells << "</Cells>\n"
      << "</Piece>\n"
      << "</UnstructuredGrid>\n"
      << "<AppendedData encoding=\"raw\">\n_";
  out.write(appended.bytes().data(), std::streamsize(appended.bytes().size()));
  out << "\n</AppendedData>\n</VTKFile>\n";
}

void write_vtu_piece(std::ostream &out,
                     const std::vector<dealii::DataOutBase::Patch<2, 2>> &patches,
                     const VtuFields &fields,
                     const std::vector<std::pair<std::string, std::vector<int>>> &cell_data,
                     const double rotation)
{
  VtuPieceArrays piece(fields, patches.size(), patches.empty() ? 1 : patches.front().n_subdivisions,
                       rotation);
  for (std::size_t c = 0; c < patches.size(); ++c)
    piece.set_cell(c, patches[c]);
  write_vtu_piece(out, piece, cell_data);
}
VtuFields VtuFields::from(
    const std::vector<std::string> &names,
    const std::vector<std::tuple<unsigned int, unsigned int, std::string,
                                 dealii::DataComponentInterpretation::DataComponentInterpretation>>
        &ranges)
{
  VtuFields fields;
  fields.names = names;
  for (const auto &[first, last, name, kind] : ranges)
  {
    if (kind != dealii::DataComponentInterpretation::component_is_part_of_vector ||
        last != first + 1 || name.empty())
      throw std::runtime_error("VTU output: the data sets " + std::to_string(first) + "-" +
                               std::to_string(last) +
                               " are not a named 2D vector (the only kind written)");
    fields.vectors.emplace_back(first, name);
  }
  return fields;
}

void write_pvtu_record(std::ostream &out, const VtuFields &fields,
                       const std::vector<std::string> &cell_data_names,
                       const std::vector<std::string> &pieces)
{
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" header_type=\"UInt64\">\n"
      << "<PUnstructuredGrid GhostLevel=\"0\">\n<PPointData>\n";
  for (const ArrayLayout &array : array_layouts(fields))
    out << "<PDataArray type=\"Float32\" Name=\"" << array.name << "\" NumberOfComponents=\""
        << array.components << "\"/>\n";
  out << "</PPointData>\n<PCellData>\n";
  for (const auto &name : cell_data_names)
    out << "<PDataArray type=\"Int32\" Name=\"" << name << "\" NumberOfComponents=\"1\"/>\n";
  out << "</PCellData>\n<PPoints>\n<PDataArray type=\"Float32\" NumberOfComponents=\"3\"/>\n"
      << "</PPoints>\n";
  for (const auto &piece : pieces)
    out << "<Piece Source=\"" << piece << "\"/>\n";
  out << "</PUnstructuredGrid>\n</VTKFile>\n";
}
} // namespace output
} // namespace sealfe
