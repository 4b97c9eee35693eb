#include "mode_painting.h"

#include "atomic_file.h"
#include "errors.h"
#include "mode_layer.h"
#include "units.h"

#include <OpenMesh/Core/Utils/Property.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <queue>
#include <sstream>
#include <utility>

namespace mrcloth {
namespace {

constexpr const char* kPrefix = "mrcloth:";

/// "mean_curvature" and "mrcloth:mean_curvature" name the same layer.
std::string stored_name(const std::string& name) {
  return name.rfind(kPrefix, 0) == 0 ? name : std::string(kPrefix) + name;
}
std::string shown_name(const std::string& name) {
  return name.rfind(kPrefix, 0) == 0 ? name.substr(std::string(kPrefix).size()) : name;
}

OpenMesh::VPropHandleT<int> computed_handle(QuadMesh& mesh) {
  OpenMesh::VPropHandleT<int> handle;
  if (!mesh.get_property_handle(handle, layer::computed_mode)) {
    mesh.add_property(handle, layer::computed_mode);
    for (const auto v : mesh.vertices()) mesh.property(handle, v) = 0;
  }
  mesh.property(handle).set_persistent(true);
  return handle;
}

/// The persistent per-vertex double layers (mrcloth's, by stored name), in
/// the order the mesh holds them.
std::vector<std::string> double_layers(const QuadMesh& mesh) {
  std::vector<std::string> names;
  for (auto it = mesh.vprops_begin(); it != mesh.vprops_end(); ++it) {
    const OpenMesh::BaseProperty* property = *it;
    // R is the refinement's own scratch value, not an artist's layer.
    if (!property || property->name().rfind(kPrefix, 0) != 0 || property->name() == layer::r_value) continue;
    if (dynamic_cast<const OpenMesh::PropertyT<double>*>(property)) names.push_back(property->name());
  }
  return names;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

std::string csv_number(double value) {
  char buffer[32];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 17);
  return error == std::errc() ? std::string(buffer, end) : std::string("nan");
}

/// One CSV line's fields as RFC 4180 has them (what spreadsheets export):
/// a field in double quotes may hold commas and doubled quotes; blanks and
/// a line's carriage return around a field are dropped. `closed` says
/// whether every quote opened was closed.
std::vector<std::string> split_csv(const std::string& line, bool& closed) {
  std::vector<std::string> fields;
  std::string field;
  bool quoted = false;     // inside a quoted part
  bool was_quoted = false;  // this field had one (its blanks inside stay)
  const auto finish = [&] {
    if (!was_quoted) {
      field.erase(0, field.find_first_not_of(" \t"));
      field.erase(field.find_last_not_of(" \t\r") + 1);
    }
    fields.push_back(field);
    field.clear();
    was_quoted = false;
  };
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c != '"') field += c;
      else if (i + 1 < line.size() && line[i + 1] == '"') field += line[++i];
      else quoted = false;
    } else if (c == '"' && field.find_first_not_of(" \t") == std::string::npos) {
      field.clear();
      quoted = was_quoted = true;
    } else if (c == ',') {
      finish();
    } else if (!(was_quoted && (c == ' ' || c == '\t' || c == '\r'))) {
      field += c;
    }
  }
  finish();
  closed = !quoted;
  return fields;
}

}  // namespace

void ensure_analysis_layers(QuadMesh& mesh) {
  computed_handle(mesh);
  for (const char* name : {layer::mean_curvature, layer::curvature_deviation}) {
    OpenMesh::VPropHandleT<double> handle;
    if (!mesh.get_property_handle(handle, name)) {
      mesh.add_property(handle, name);
      for (const auto v : mesh.vertices()) mesh.property(handle, v) = 0.0;
    }
    mesh.property(handle).set_persistent(true);
  }
}

void set_computed_modes(QuadMesh& mesh, const std::vector<int>& modes) {
  if (modes.size() != mesh.n_vertices()) {
    throw ArgumentError("set_computed_modes: " + std::to_string(modes.size()) + " modes for " +
                        std::to_string(mesh.n_vertices()) + " vertices; expected one per vertex");
  }
  for (std::size_t v = 0; v < modes.size(); ++v)
    if (modes[v] < 1 || modes[v] > kLargestMode)
      throw ArgumentError("set_computed_modes: vertex " + std::to_string(v) + " has mode " + std::to_string(modes[v]) +
                          "; expected computed modes from 1 to " + std::to_string(kLargestMode));
  const auto computed = computed_handle(mesh);
  const auto current = ensure_layers(mesh).mode;
  for (const auto v : mesh.vertices()) {
    mesh.property(computed, v) = modes[static_cast<std::size_t>(v.idx())];
    mesh.property(current, v) = modes[static_cast<std::size_t>(v.idx())];
  }
}

void set_computed_layer(QuadMesh& mesh, const std::vector<int>& modes) {
  if (modes.size() != mesh.n_vertices())
    throw ArgumentError("set_computed_layer: " + std::to_string(modes.size()) + " modes for " +
                        std::to_string(mesh.n_vertices()) + " vertices; expected one per vertex");
  for (std::size_t v = 0; v < modes.size(); ++v)
    if (modes[v] < 0 || modes[v] > kLargestMode)
      throw ArgumentError("set_computed_layer: vertex " + std::to_string(v) + " has mode " + std::to_string(modes[v]) +
                          "; expected modes from 0 to " + std::to_string(kLargestMode));
  const auto computed = computed_handle(mesh);
  for (const auto v : mesh.vertices()) mesh.property(computed, v) = modes[static_cast<std::size_t>(v.idx())];
}

std::vector<int> computed_modes(const QuadMesh& mesh) {
  std::vector<int> modes(mesh.n_vertices(), kDefaultMode);
  OpenMesh::VPropHandleT<int> handle;
  if (!mesh.get_property_handle(handle, layer::computed_mode)) return modes;
  for (const auto v : mesh.vertices()) modes[static_cast<std::size_t>(v.idx())] = mesh.property(handle, v);
  return modes;
}

void set_vertex_layer(QuadMesh& mesh, const std::string& name, const std::vector<double>& values) {
  const std::string stored = stored_name(name);
  if (stored == layer::mode || stored == layer::computed_mode || stored == layer::r_value || stored == layer::hanging ||
      stored == layer::parents)
    throw ArgumentError("set_vertex_layer: '" + shown_name(stored) + "' is a reserved layer; choose another name");
  if (values.size() != mesh.n_vertices()) {
    throw ArgumentError("set_vertex_layer: " + std::to_string(values.size()) + " values for layer '" + shown_name(stored) +
                        "' on " + std::to_string(mesh.n_vertices()) + " vertices; expected one per vertex");
  }
  OpenMesh::VPropHandleT<double> handle;
  if (!mesh.get_property_handle(handle, stored)) mesh.add_property(handle, stored);
  mesh.property(handle).set_persistent(true);
  for (const auto v : mesh.vertices()) mesh.property(handle, v) = values[static_cast<std::size_t>(v.idx())];
}

std::vector<std::string> vertex_layer_names(const QuadMesh& mesh) {
  std::vector<std::string> names{"mode", "computed_mode"};
  for (const std::string& name : double_layers(mesh)) names.push_back(shown_name(name));
  return names;
}

std::vector<double> vertex_layer(const QuadMesh& mesh, const std::string& name) {
  std::vector<double> values(mesh.n_vertices());
  const std::string stored = stored_name(name);
  OpenMesh::VPropHandleT<int> ints;
  if ((stored == layer::mode || stored == layer::computed_mode) && mesh.get_property_handle(ints, stored)) {
    for (const auto v : mesh.vertices()) values[static_cast<std::size_t>(v.idx())] = mesh.property(ints, v);
    return values;
  }
  // Before any analysis: the default mode erasing goes back to, as the layers' CSV gives it.
  if (stored == layer::computed_mode) return std::vector<double>(mesh.n_vertices(), kDefaultMode);
  OpenMesh::VPropHandleT<double> doubles;
  if (!mesh.get_property_handle(doubles, stored)) {
    const bool analysed = stored == layer::mean_curvature || stored == layer::curvature_deviation;
    throw ArgumentError("the mesh has no per-vertex layer '" + shown_name(stored) + "'; it has " +
                        joined(vertex_layer_names(mesh)) +
                        (analysed ? " (the curvature layers come from analysing a cache of the mesh: extractModes)" : ""));
  }
  for (const auto v : mesh.vertices()) values[static_cast<std::size_t>(v.idx())] = mesh.property(doubles, v);
  return values;
}

std::size_t paint_modes_geodesic(QuadMesh& mesh, const std::vector<int>& seeds, double radius, int mode) {
  check_mode(mode);
  if (!(radius >= 0.0) || !std::isfinite(radius))
    throw ArgumentError("brush radius must be a finite number >= 0 metres (got " + std::to_string(radius) + ")");
  const int n = static_cast<int>(mesh.n_vertices());
  for (std::size_t i = 0; i < seeds.size(); ++i)
    if (seeds[i] < 0 || seeds[i] >= n)
      throw ArgumentError("seed vertex " + std::to_string(seeds[i]) + " (entry " + std::to_string(i) +
                          ") is out of range; the mesh has " + std::to_string(n) + " vertices");
  // Dijkstra along the edges, stopped at the radius.
  std::vector<double> distance(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (const int s : seeds) {
    distance[static_cast<std::size_t>(s)] = 0.0;
    queue.push({0.0, s});
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[static_cast<std::size_t>(v)]) continue;
    const auto handle = mesh.vertex_handle(static_cast<unsigned>(v));
    for (const auto u : mesh.vv_range(handle)) {
      const double next = d + (mesh.point(u) - mesh.point(handle)).norm();
      if (next <= radius && next < distance[static_cast<std::size_t>(u.idx())]) {
        distance[static_cast<std::size_t>(u.idx())] = next;
        queue.push({next, u.idx()});
      }
    }
  }
  const auto layer_handle = ensure_layers(mesh).mode;
  std::size_t painted = 0;
  for (const auto v : mesh.vertices()) {
    if (!(distance[static_cast<std::size_t>(v.idx())] <= radius)) continue;
    mesh.property(layer_handle, v) = mode;
    ++painted;
  }
  return painted;
}

std::size_t fill_modes_threshold(QuadMesh& mesh, const std::string& name, double threshold, int mode, bool above) {
  check_mode(mode);
  if (!std::isfinite(threshold)) throw ArgumentError("the fill threshold must be a finite number");
  const std::vector<double> values = vertex_layer(mesh, name);
  const auto layer_handle = ensure_layers(mesh).mode;
  std::size_t filled = 0;
  for (const auto v : mesh.vertices()) {
    const double value = values[static_cast<std::size_t>(v.idx())];
    if (!(above ? value >= threshold : value <= threshold)) continue;
    mesh.property(layer_handle, v) = mode;
    ++filled;
  }
  return filled;
}

std::size_t erase_modes(QuadMesh& mesh, const std::vector<int>& vertex_ids) {
  const int n = static_cast<int>(mesh.n_vertices());
  for (std::size_t i = 0; i < vertex_ids.size(); ++i)
    if (vertex_ids[i] < 0 || vertex_ids[i] >= n)
      throw ArgumentError("vertex id " + std::to_string(vertex_ids[i]) + " (entry " + std::to_string(i) +
                          ") is out of range; the mesh has " + std::to_string(n) + " vertices");
  const std::vector<int> computed = computed_modes(mesh);
  const auto layer_handle = ensure_layers(mesh).mode;
  std::size_t changed = 0;
  const auto erase = [&](int v) {
    const int target = computed[static_cast<std::size_t>(v)];
    int& mode = mesh.property(layer_handle, mesh.vertex_handle(static_cast<unsigned>(v)));
    changed += mode != target;
    mode = target;
  };
  if (vertex_ids.empty())
    for (int v = 0; v < n; ++v) erase(v);
  else
    for (const int v : vertex_ids) erase(v);
  return changed;
}

void write_vertex_layers_csv(const QuadMesh& mesh, const std::string& path) {
  require_writable_target(path);
  const std::vector<int> modes = get_modes(mesh);
  const std::vector<int> computed = computed_modes(mesh);
  const std::vector<std::string> extra = double_layers(mesh);
  std::vector<std::vector<double>> columns;
  for (const std::string& name : extra) columns.push_back(vertex_layer(mesh, name));
  write_file_atomically(path, ".csv", [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << "vertex,x,y,z,mode,computed_mode";
    for (const std::string& name : extra) out << ',' << shown_name(name);
    out << '\n';
    for (const auto v : mesh.vertices()) {
      const auto i = static_cast<std::size_t>(v.idx());
      const auto& p = mesh.point(v);
      out << v.idx() << ',' << csv_number(p[0]) << ',' << csv_number(p[1]) << ',' << csv_number(p[2]) << ',' << modes[i]
          << ',' << computed[i];
      for (const auto& column : columns) out << ',' << csv_number(column[i]);
      out << '\n';
    }
    out.flush();
    return static_cast<bool>(out);
  });
}

namespace {

/// Reads a modes CSV's rows against `mesh`: the header's columns, then each
/// row's vertex and mode (checked) and its position, compared with the
/// mesh's where the file has x, y, z columns. Errors name the file's line.
class ModesCsvParser {
 public:
  ModesCsvParser(const QuadMesh& mesh, const std::string& path)
      : mesh_(mesh), path_(path), first_line_(mesh.n_vertices(), 0) {}

  [[noreturn]] void fail(int line, const std::string& problem, const std::string& expected) const {
    throw InputError(path_ + ":" + std::to_string(line) + ": " + problem + "; expected " + expected);
  }

  /// The header line (line 1): finds the vertex, mode and x, y, z columns.
  void read_header(std::string text) {
    // A spreadsheet's export: a byte-order mark, "Vertex", " mode\r".
    if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);
    bool closed = true;
    const std::vector<std::string> header = split_csv(text, closed);
    if (!closed) fail(1, "a quote in the header is not closed", "quoted fields to end in a quote");
    const auto named = [](std::string field) {
      field.erase(0, field.find_first_not_of(" \t"));
      field.erase(field.find_last_not_of(" \t\r") + 1);
      return ascii_lower(field);
    };
    for (std::size_t c = 0; c < header.size(); ++c) {
      const std::string name = named(header[c]);
      if (name == "vertex") vertex_column_ = static_cast<int>(c);
      if (name == "mode") mode_column_ = static_cast<int>(c);
      for (int k = 0; k < 3; ++k)
        if (name == std::string(1, "xyz"[k])) position_columns_[static_cast<std::size_t>(k)] = static_cast<int>(c);
    }
    has_positions_ = std::all_of(position_columns_.begin(), position_columns_.end(), [](int c) { return c >= 0; });
    header_fields_ = header.size();
    if (vertex_column_ < 0 || mode_column_ < 0) fail(1, "the header has no 'vertex' or no 'mode' column", "vertex,mode,...");
  }

  /// One data row, at `line` (blank rows are skipped by the caller).
  void read_row(const std::string& text, int line) {
    bool closed = true;
    const std::vector<std::string> fields = split_csv(text, closed);
    if (!closed) fail(line, "a quote is not closed on this line", "quoted fields to end on their line (a field across lines is not read)");
    // More fields than the header names would be a misplaced comma
    // (a decimal comma, an unquoted name): the columns would shift. Empty
    // ones after the last (a spreadsheet's trailing commas) are no data,
    // and a short row is fine if it reaches the vertex and mode columns.
    std::size_t given = fields.size();
    while (given > 0 && fields[given - 1].empty()) --given;
    if (given > header_fields_ || static_cast<int>(fields.size()) <= std::max(vertex_column_, mode_column_))
      fail(line, std::to_string(given) + " fields", std::to_string(header_fields_) + " as in the header");
    const int n = static_cast<int>(mesh_.n_vertices());
    const int vertex = integer(fields[static_cast<std::size_t>(vertex_column_)], "vertex", line);
    const int mode = integer(fields[static_cast<std::size_t>(mode_column_)], "mode", line);
    if (vertex < 0 || vertex >= n)
      fail(line, "vertex " + std::to_string(vertex) + " is out of range", "a vertex below " + std::to_string(n));
    if (mode < 0 || mode > kLargestMode)
      fail(line, "mode " + std::to_string(mode) + " is out of range", "a mode from 0 to " + std::to_string(kLargestMode));
    int& earlier = first_line_[static_cast<std::size_t>(vertex)];
    if (earlier > 0)
      fail(line, "vertex " + std::to_string(vertex) + " is given again (first at line " + std::to_string(earlier) + ")",
           "one row per vertex");
    earlier = line;
    assignments_.emplace_back(vertex, mode);
    if (has_positions_) compare_position(fields, vertex, line);
  }

  /// The rows' (vertex, mode) pairs in file order.
  const std::vector<std::pair<int, int>>& assignments() const { return assignments_; }
  /// What the position comparison found (misplaced rows, the farthest).
  ModesCsvRead& read() { return read_; }

 private:
  int integer(const std::string& field, const char* what, int line) const {
    int value = 0;
    const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
    if (error == std::errc::result_out_of_range)
      fail(line, std::string(what) + " " + field + " is out of range",
           what == std::string("mode") ? "a mode from 0 to " + std::to_string(kLargestMode)
                                       : "a vertex below " + std::to_string(mesh_.n_vertices()));
    if (error != std::errc() || end != field.data() + field.size() || field.empty())
      fail(line, std::string(what) + " \"" + field + "\" is not an integer", std::string("an integer ") + what);
    return value;
  }

  void compare_position(const std::vector<std::string>& fields, int vertex, int line) {
    // A position that is no finite number is another tool's column: not compared.
    OpenMesh::Vec3d p(0, 0, 0);
    bool numbers = true;
    for (int k = 0; k < 3; ++k) {
      const auto column = static_cast<std::size_t>(position_columns_[static_cast<std::size_t>(k)]);
      const std::string& field = column < fields.size() ? fields[column] : std::string();
      const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), p[k]);
      numbers = numbers && error == std::errc() && end == field.data() + field.size() && !field.empty() &&
                std::isfinite(p[k]);
    }
    const double off = (p - mesh_.point(mesh_.vertex_handle(static_cast<unsigned>(vertex)))).norm();
    if (numbers && !(off <= kCsvPositionTolerance)) {
      ++read_.misplaced;
      if (!(off <= read_.farthest)) {
        read_.farthest = off;
        read_.farthest_vertex = vertex;
        read_.farthest_line = line;
      }
    }
  }

  const QuadMesh& mesh_;
  const std::string& path_;
  int vertex_column_ = -1, mode_column_ = -1;
  std::array<int, 3> position_columns_{-1, -1, -1};
  bool has_positions_ = false;
  std::size_t header_fields_ = 0;
  std::vector<int> first_line_;  // per vertex, the line that set it (0: none)
  std::vector<std::pair<int, int>> assignments_;
  ModesCsvRead read_;
};

}  // namespace

ModesCsvRead read_modes_csv(QuadMesh& mesh, const std::string& path) {
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored))
    throw InputError(path + ": is a folder; expected a CSV file of vertex modes");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file for reading; expected a CSV file of vertex modes");
  ModesCsvParser parser(mesh, path);
  std::string text;
  if (!std::getline(in, text)) parser.fail(1, "the file is empty", "a header line naming the vertex and mode columns");
  parser.read_header(text);
  for (int line = 2; std::getline(in, text); ++line)
    if (text.find_first_not_of(" \t\r") != std::string::npos) parser.read_row(text, line);
  // Only a file read whole sets any mode.
  const auto layer_handle = ensure_layers(mesh).mode;
  for (const auto& [vertex, mode] : parser.assignments())
    mesh.property(layer_handle, mesh.vertex_handle(static_cast<unsigned>(vertex))) = mode;
  ModesCsvRead read = parser.read();
  read.set = parser.assignments().size();
  return read;
}

}  // namespace mrcloth
