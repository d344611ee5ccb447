#include "ao4d/mesh.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string_view>

namespace ao4d {

Vec4 cell_normal(const TetMesh& mesh, std::size_t cell) {
  const Cell& c = mesh.cells[cell];
  const Vec4& a = mesh.vertices[c[0]];
  return cross(mesh.vertices[c[1]] - a, mesh.vertices[c[2]] - a, mesh.vertices[c[3]] - a);
}

std::vector<Vec4> cell_normals(const TetMesh& mesh) {
  std::vector<Vec4> normals(mesh.cells.size());
  for (std::size_t i = 0; i < mesh.cells.size(); ++i) normals[i] = normalize(cell_normal(mesh, i));
  return normals;
}

std::vector<Vec4> vertex_normals(const TetMesh& mesh) {
  std::vector<Vec4> sum(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.cells.size(); ++i) {
    const Vec4 n = cell_normal(mesh, i);  // length is proportional to the cell's volume
    for (std::uint32_t v : mesh.cells[i]) sum[v] += n;
  }
  for (Vec4& n : sum) n = normalize(n);
  return sum;
}

namespace {

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

// Splits on blanks and drops a trailing '#' comment.
std::vector<std::string_view> tokens(std::string_view line) {
  if (const auto hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

[[noreturn]] void fail(const std::string& name, std::size_t line, const std::string& what) {
  throw ParseError(name + ":" + std::to_string(line) + ": " + what);
}

double parse_number(std::string_view tok, const std::string& name, std::size_t line, const char* field) {
  double value = 0;
  const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), value);
  if (ec != std::errc{} || ptr != tok.data() + tok.size() || !std::isfinite(value))
    fail(name, line, std::string("expected a finite number for ") + field + ", got '" + std::string(tok) + "'");
  return value;
}

}  // namespace

TetMesh parse_mesh(std::istream& in, const std::string& name, std::vector<double>* values) {
  TetMesh mesh;
  std::vector<std::size_t> cell_lines;  // to name the line of a bad index once all vertices are known
  std::string text;
  std::size_t line = 0;
  std::size_t valued = 0;
  static constexpr const char* axes[] = {"x", "y", "z", "w"};
  while (std::getline(in, text)) {
    ++line;
    const auto tok = tokens(trim(text));
    if (tok.empty()) continue;
    if (tok[0] == "v") {
      if (tok.size() != 5 && tok.size() != 6)
        fail(name, line, "expected 'v x y z w' with an optional value, got " + std::to_string(tok.size() - 1) + " numbers");
      Vec4 p;
      for (std::size_t i = 0; i < 4; ++i) p[i] = parse_number(tok[i + 1], name, line, axes[i]);
      mesh.vertices.push_back(p);
      if (tok.size() == 6) {
        const double value = parse_number(tok[5], name, line, "the vertex value");
        if (values) values->push_back(value);
        ++valued;
      } else if (values) {
        values->push_back(0.0);
      }
    } else if (tok[0] == "t") {
      if (tok.size() != 5) fail(name, line, "expected 't a b c d' (four 1-based vertex indices)");
      Cell c{};
      for (std::size_t i = 0; i < 4; ++i) {
        std::uint64_t index = 0;
        const auto [ptr, ec] = std::from_chars(tok[i + 1].data(), tok[i + 1].data() + tok[i + 1].size(), index);
        if (ec != std::errc{} || ptr != tok[i + 1].data() + tok[i + 1].size() || index == 0 || index > UINT32_MAX)
          fail(name, line, "expected a 1-based vertex index, got '" + std::string(tok[i + 1]) + "'");
        c[i] = static_cast<std::uint32_t>(index - 1);
      }
      for (std::size_t i = 0; i < 4; ++i)
        for (std::size_t j = i + 1; j < 4; ++j)
          if (c[i] == c[j])
            fail(name, line, "expected four distinct vertex indices, vertex " + std::to_string(c[i] + 1) + " repeats");
      mesh.cells.push_back(c);
      cell_lines.push_back(line);
    } else {
      fail(name, line, "expected a 'v' or 't' line, got '" + std::string(tok[0]) + "'");
    }
  }
  if (in.bad()) throw ParseError(name + ": read error");
  for (std::size_t i = 0; i < mesh.cells.size(); ++i)
    for (std::uint32_t v : mesh.cells[i])
      if (v >= mesh.vertices.size())
        fail(name, cell_lines[i],
             "vertex index " + std::to_string(v + 1) + " is out of range (the file has " + std::to_string(mesh.vertices.size()) +
                 " vertices)");
  if (mesh.cells.empty()) throw ParseError(name + ": expected at least one 't' line, found none");
  if (valued != 0 && valued != mesh.vertices.size())
    throw ParseError(name + ": expected a value on every 'v' line or on none, found " + std::to_string(valued) + " of " +
                     std::to_string(mesh.vertices.size()));
  return mesh;
}

TetMesh read_mesh(const std::filesystem::path& file, std::vector<double>* values) {
  std::ifstream in(file);
  if (!in) throw ParseError(file.string() + ": cannot open the mesh file");
  return parse_mesh(in, file.string(), values);
}

void write_mesh(const std::filesystem::path& file, const TetMesh& mesh, const std::vector<double>* values) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
  out << "# ao4d tetrahedral mesh: 'v x y z w" << (values ? " ao" : "") << "', 't a b c d' (1-based)\n";
  out << std::setprecision(17);
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec4& p = mesh.vertices[i];
    out << "v " << p.x << ' ' << p.y << ' ' << p.z << ' ' << p.w;
    if (values) out << ' ' << (*values)[i];
    out << '\n';
  }
  for (const Cell& c : mesh.cells) out << "t " << c[0] + 1 << ' ' << c[1] + 1 << ' ' << c[2] + 1 << ' ' << c[3] + 1 << '\n';
  if (!out) throw std::runtime_error(file.string() + ": write failed");
}

std::vector<OrientedPoint> parse_points(std::istream& in, const std::string& name) {
  static constexpr const char* fields[] = {"px", "py", "pz", "pw", "nx", "ny", "nz", "nw"};
  std::vector<OrientedPoint> points;
  std::string text;
  std::size_t line = 0;
  while (std::getline(in, text)) {
    ++line;
    const auto tok = tokens(trim(text));
    if (tok.empty()) continue;
    if (tok.size() != 8) fail(name, line, "expected 8 numbers 'px py pz pw nx ny nz nw', got " + std::to_string(tok.size()));
    OrientedPoint p;
    for (std::size_t i = 0; i < 4; ++i) p.position[i] = parse_number(tok[i], name, line, fields[i]);
    for (std::size_t i = 0; i < 4; ++i) p.normal[i] = parse_number(tok[i + 4], name, line, fields[i + 4]);
    if (length(p.normal) == 0) fail(name, line, "expected a non-zero normal (nx ny nz nw)");
    p.normal = normalize(p.normal);
    points.push_back(p);
  }
  if (in.bad()) throw ParseError(name + ": read error");
  return points;
}

std::vector<OrientedPoint> read_points(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ParseError(file.string() + ": cannot open the points file");
  return parse_points(in, file.string());
}

}  // namespace ao4d
