#include "ply_layout.h"

#include "errors.h"
#include "text_words.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string_view>

namespace mrcloth {
namespace {

/// One of PLY's scalar types: its size in binary data and, for integers,
/// the range its text may hold.
struct ScalarType {
  const char* name;
  std::size_t bytes;
  bool is_float;
  long long lowest, highest;
};

constexpr ScalarType kScalarTypes[] = {
    {"char", 1, false, -128, 127},
    {"int8", 1, false, -128, 127},
    {"uchar", 1, false, 0, 255},
    {"uint8", 1, false, 0, 255},
    {"short", 2, false, -32768, 32767},
    {"int16", 2, false, -32768, 32767},
    {"ushort", 2, false, 0, 65535},
    {"uint16", 2, false, 0, 65535},
    {"int", 4, false, -2147483648LL, 2147483647LL},
    {"int32", 4, false, -2147483648LL, 2147483647LL},
    {"uint", 4, false, 0, 4294967295LL},
    {"uint32", 4, false, 0, 4294967295LL},
    {"float", 4, true, 0, 0},
    {"float32", 4, true, 0, 0},
    {"double", 8, true, 0, 0},
    {"float64", 8, true, 0, 0},
};

const ScalarType* scalar_type(std::string_view name) {
  for (const ScalarType& type : kScalarTypes)
    if (name == type.name) return &type;
  return nullptr;
}

/// The list length types OpenMesh's reader knows (it refuses the others).
bool openmesh_reads_list_length(std::string_view name) {
  return name == "uchar" || name == "uint8" || name == "uint16" || name == "int";
}

struct Property {
  std::string name;
  const ScalarType* type = nullptr;          ///< a list's item type
  const ScalarType* length_type = nullptr;  ///< set for a list only
  std::size_t line = 0;
  bool is_list() const { return length_type != nullptr; }
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::size_t line = 0;
  std::vector<Property> properties;
};

struct Header {
  std::string format;  ///< ascii, binary_little_endian or binary_big_endian
  std::vector<Element> elements;
  std::size_t end_line = 0;  ///< the end_header line
};

InputError error(const std::string& path, const std::string& problem) { return InputError(with_path(path, problem)); }

/// A word of the file as a message may show it: printable, not too long.
std::string shown(std::string_view word) {
  std::string text;
  for (const char c : word.substr(0, 40)) text += (c >= 32 && c < 127) ? c : '?';
  return word.size() > 40 ? text + "..." : text;
}

template <typename Integer>
bool parse_whole(std::string_view text, Integer& value) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  const auto [stop, problem] = std::from_chars(text.data(), text.data() + text.size(), value);
  return problem == std::errc() && stop == text.data() + text.size();
}

/// A number OpenMesh's reader takes from text into a value of `type`.
bool is_number_of(const ScalarType& type, std::string_view text) {
  if (!type.is_float) {
    long long value = 0;
    return parse_whole(text, value) && value >= type.lowest && value <= type.highest;
  }
  double value = 0.0;
  if (!parse_whole(text, value) || !std::isfinite(value)) return false;
  // Read into a float, a larger value fails the stream.
  return type.bytes == 8 || std::abs(value) <= static_cast<double>(std::numeric_limits<float>::max());
}

const char* const kTypeList =
    "PLY's types (char, uchar, short, ushort, int, uint, float, double, or int8 ... float64)";

Property read_property(const std::string& path, const std::string& line, const std::vector<std::string>& words,
                       std::size_t line_number) {
  Property property;
  property.line = line_number;
  property.name = words.back();
  const bool list = words.size() > 1 && words[1] == "list";
  if (!list && words.size() == 3) property.type = scalar_type(words[1]);
  if (list && words.size() == 5) {
    property.length_type = scalar_type(words[2]);
    property.type = scalar_type(words[3]);
  }
  if (!property.type || (list && !property.length_type))
    throw error(path, "the PLY header's property" + at_line(line_number) + " is '" + shown(line) +
                          "'; expected 'property <type> <name>' or 'property list <length type> <item type> <name>' "
                          "with " + kTypeList);
  if (list && !openmesh_reads_list_length(words[2]))
    throw error(path, "the PLY header's property" + at_line(line_number) + " gives its list length as " + shown(words[2]) +
                          "; expected uchar, uint8, uint16 or int (the types OpenMesh's reader takes)");
  return property;
}

/// The header after the "ply" line, held to the grammar: OpenMesh's reader
/// takes it word by word and loops for ever on a word it cannot convert.
Header read_header(const std::string& path, std::istream& in) {
  Header header;
  std::string line;
  std::size_t line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    const std::vector<std::string> words = split_words(line);
    if (line_number == 2) {
      double version = 0.0;
      const bool known = words.size() == 3 && words[0] == "format" &&
                         (words[1] == "ascii" || words[1] == "binary_little_endian" ||
                          words[1] == "binary_big_endian") &&
                         parse_whole(std::string_view(words[2]), version) && std::isfinite(version);
      if (!known)
        throw error(path, "the PLY header's line 2 is '" + shown(line) +
                              "'; expected 'format ascii 1.0' (or binary_little_endian or binary_big_endian)");
      header.format = words[1];
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "end_header") {
      if (words.size() != 1)
        throw error(path, "the PLY header's end" + at_line(line_number) + " is '" + shown(line) +
                              "'; expected 'end_header' alone on its line");
      header.end_line = line_number;
      return header;
    }
    if (words[0] == "element") {
      Element element;
      element.line = line_number;
      unsigned int count = 0;  // OpenMesh reads counts as unsigned int
      if (words.size() != 3 || !parse_whole(std::string_view(words[2]), count) || words[2].front() == '+')
        throw error(path, "the PLY header's element" + at_line(line_number) + " is '" + shown(line) +
                              "'; expected 'element <name> <count>' with a count from 0 to 4294967295");
      element.name = words[1];
      element.count = count;
      for (const Element& earlier : header.elements) {
        if ((element.name == "vertex" || element.name == "face") && earlier.name == element.name)
          throw error(path, "the PLY header's element" + at_line(line_number) + " is a second '" + element.name +
                                "' element (the first is on line " + std::to_string(earlier.line) +
                                "); expected one");
      }
      header.elements.push_back(element);
      continue;
    }
    if (words[0] == "property") {
      if (header.elements.empty())  // OpenMesh's PLY reader crashes on it
        throw error(path, "the PLY header's property" + at_line(line_number) +
                              " comes before any element; expected 'element <name> <count>' first");
      header.elements.back().properties.push_back(read_property(path, line, words, line_number));
      continue;
    }
    throw error(path, "the PLY header's line " + std::to_string(line_number) + " is '" + shown(line) +
                          "'; expected comment, obj_info, element, property or end_header");
  }
  if (line_number < 2)
    throw error(path, "the PLY file ends after its first line; expected a 'format' line and a header");
  // OpenMesh's PLY reader never returns from a header without its end.
  throw error(path, "the PLY header has no 'end_header' line; expected one after the element and property lines");
}

bool is_face_corners(const Element& element, const Property& property) {
  return element.name == "face" && property.is_list() &&
         (property.name == "vertex_indices" || property.name == "vertex_index");
}

/// The elements OpenMesh's reader reads: up to the faces, after which it
/// stops.
std::size_t elements_read(const Header& header) {
  for (std::size_t e = 0; e < header.elements.size(); ++e)
    if (header.elements[e].name == "face") return e + 1;
  return header.elements.size();
}

/// The layout the garment needs and OpenMesh's reader can follow.
void check_layout(const std::string& path, const Header& header) {
  const auto& elements = header.elements;
  const auto vertex = std::find_if(elements.begin(), elements.end(), [](const Element& e) { return e.name == "vertex"; });
  if (vertex == elements.end())
    throw error(path, "the PLY header declares no vertex element; expected 'element vertex <count>' with properties "
                      "x, y and z");
  const auto face = std::find_if(elements.begin(), elements.end(), [](const Element& e) { return e.name == "face"; });
  if (face != elements.end() && face < vertex)
    throw error(path, "the PLY header's face element" + at_line(face->line) +
                          " comes before its vertex element; expected the vertices first");
  for (const char* axis : {"x", "y", "z"}) {
    const auto named = [&](const Property& p) { return p.name == axis; };
    const auto count = std::count_if(vertex->properties.begin(), vertex->properties.end(), named);
    if (count != 1)
      throw error(path, "the PLY header's vertex element" + at_line(vertex->line) + " has " + std::to_string(count) +
                            " properties named " + axis + "; expected one each of x, y and z");
    const Property& property = *std::find_if(vertex->properties.begin(), vertex->properties.end(), named);
    if (property.is_list())
      throw error(path, "the PLY header's property" + at_line(property.line) + " makes " + axis +
                            " a list; expected a number");
    if (header.format != "ascii" && !property.type->is_float)
      throw error(path, "the PLY header's property" + at_line(property.line) + " stores " + axis + " as " +
                            property.type->name + "; expected float or double (OpenMesh's reader reads binary "
                            "coordinates as nothing else)");
  }
  for (std::size_t e = 0; e < elements_read(header); ++e) {
    for (const Property& property : elements[e].properties) {
      if (property.is_list() && !is_face_corners(elements[e], property))
        throw error(path, "the PLY header's property" + at_line(property.line) + " is a list ('" + property.name +
                              "' of element '" + elements[e].name + "'); expected lists only for the faces' "
                              "vertex_indices (OpenMesh's reader misreads every other list and the data after it)");
    }
  }
}

std::string header_for_reader(const Header& header) {
  std::string text = "ply\nformat " + header.format + " 1.0\n";
  for (const Element& element : header.elements) {
    text += "element " + element.name + " " + std::to_string(element.count) + "\n";
    for (const Property& property : element.properties) {
      text += "property ";
      if (property.is_list()) text += std::string("list ") + property.length_type->name + " ";
      text += std::string(property.type->name) + " " + property.name + "\n";
    }
  }
  return text + "end_header\n";
}

/// "vertex 3", "face 0" or "item 2 of element 'edge'".
std::string item_name(const Element& element, std::size_t item) {
  if (element.name == "vertex" || element.name == "face") return element.name + " " + std::to_string(item);
  return "item " + std::to_string(item) + " of element '" + shown(element.name) + "'";
}

/// Words of text data and the line each stands on.
class Words {
 public:
  Words(const std::string& text, std::size_t first_line) : text_(text), line_(first_line) {}

  bool next(std::string_view& word, std::size_t& line) {
    while (at_ < text_.size() && is_space(text_[at_])) {
      if (text_[at_] == '\n') ++line_;
      ++at_;
    }
    if (at_ == text_.size()) return false;
    const std::size_t start = at_;
    while (at_ < text_.size() && !is_space(text_[at_])) ++at_;
    word = std::string_view(text_).substr(start, at_ - start);
    line = line_;
    return true;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }
  const std::string& text_;
  std::size_t at_ = 0;
  std::size_t line_;
};

InputError cut_short(const std::string& path, const Element& element, std::size_t item) {
  return error(path, "the PLY data ends at " + item_name(element, item) + "; expected the " +
                         std::to_string(element.count) + " items the header's element '" + shown(element.name) + "'" +
                         at_line(element.line) + " counts");
}

void walk_text(const std::string& path, const Header& header, const std::string& data, PlyScan& scan) {
  Words words(data, header.end_line + 1);
  for (std::size_t e = 0; e < elements_read(header); ++e) {
    const Element& element = header.elements[e];
    const bool is_vertex = element.name == "vertex", is_face = element.name == "face";
    if (element.properties.empty()) continue;
    for (std::size_t item = 0; item < element.count; ++item) {
      std::size_t item_line = 0;
      std::array<std::string, 3> coordinates;
      for (const Property& property : element.properties) {
        std::string_view word;
        std::size_t line = 0;
        if (!words.next(word, line)) throw cut_short(path, element, item);
        if (item_line == 0) item_line = line;
        const std::string where = item_name(element, item) + at_line(line);
        if (!property.is_list()) {
          const bool axis = is_vertex && property.name.size() == 1 && property.name[0] >= 'x' && property.name[0] <= 'z';
          if (axis) {
            coordinates[static_cast<std::size_t>(property.name[0] - 'x')] = std::string(word);
          } else if (!is_number_of(*property.type, word)) {
            throw error(path, where + " has '" + shown(word) + "' for its " + property.name + "; expected a " +
                                  property.type->name + " number");
          }
          continue;
        }
        unsigned int corners = 0;  // OpenMesh reads the length as unsigned int
        if (!parse_whole(word, corners) || !is_number_of(*property.length_type, word))
          throw error(path, where + " has '" + shown(word) + "' for its number of corners; expected a " +
                                property.length_type->name + " count");
        for (unsigned int k = 0; k < corners; ++k) {
          if (!words.next(word, line)) throw cut_short(path, element, item);
          long long index = 0;
          if (!parse_whole(word, index) || index < 0 || !is_number_of(*property.type, word))
            throw error(path, where + " has '" + shown(word) + "' among its vertex indices; expected " +
                                  std::to_string(corners) + " indices from 0 (the first vertex)");
        }
      }
      if (is_vertex) {
        scan.coordinates.push_back(std::move(coordinates));
        scan.vertex_lines.push_back(item_line);
      }
      if (is_face) scan.face_lines.push_back(item_line);
    }
  }
}

/// A list length as OpenMesh's reader takes it from binary data: an "int"
/// of -1 becomes 4294967295.
unsigned int binary_length(const ScalarType& type, const unsigned char* bytes, bool big_endian) {
  std::uint32_t value = 0;
  for (std::size_t k = 0; k < type.bytes; ++k) {
    const std::size_t at = big_endian ? k : type.bytes - 1 - k;
    value = (value << 8) | bytes[at];
  }
  return value;
}

void walk_binary(const std::string& path, const Header& header, const std::string& data) {
  const bool big_endian = header.format == "binary_big_endian";
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  std::size_t at = 0;
  for (std::size_t e = 0; e < elements_read(header); ++e) {
    const Element& element = header.elements[e];
    std::size_t fixed = 0;
    bool has_list = false;
    for (const Property& property : element.properties) {
      fixed += property.is_list() ? property.length_type->bytes : property.type->bytes;
      has_list = has_list || property.is_list();
    }
    const std::size_t left = data.size() - at;
    if (!has_list) {
      // Up to 2^32 items of a few bytes: no overflow in 64 bits.
      if (fixed > 0 && element.count > left / fixed) throw cut_short(path, element, left / fixed);
      at += element.count * fixed;
      continue;
    }
    for (std::size_t item = 0; item < element.count; ++item) {
      for (const Property& property : element.properties) {
        const ScalarType& first = property.is_list() ? *property.length_type : *property.type;
        if (data.size() - at < first.bytes) throw cut_short(path, element, item);
        at += first.bytes;
        if (!property.is_list()) continue;
        const std::uint64_t corners = binary_length(first, bytes + at - first.bytes, big_endian);
        const std::uint64_t needed = corners * property.type->bytes;
        if (needed > data.size() - at)
          throw error(path, "the PLY binary data's " + item_name(element, item) + " has " + std::to_string(corners) +
                                " corners (as OpenMesh reads its " + property.length_type->name + " count), but only " +
                                std::to_string(data.size() - at) + " bytes of data remain; expected a count its "
                                "data holds");
        at += static_cast<std::size_t>(needed);
      }
    }
  }
}

}  // namespace

std::optional<PlyScan> scan_ply_layout(const std::string& path, std::istream& in) {
  std::string first;
  if (!std::getline(in, first)) return std::nullopt;
  const std::vector<std::string> magic = split_words(first);
  if (magic.size() != 1 || (magic[0] != "ply" && magic[0] != "PLY")) return std::nullopt;
  const Header header = read_header(path, in);
  check_layout(path, header);
  const std::string data(std::istreambuf_iterator<char>(in), {});
  PlyScan scan;
  scan.binary = header.format != "ascii";
  if (scan.binary) {
    walk_binary(path, header, data);
  } else {
    walk_text(path, header, data, scan);
  }
  scan.text_for_reader = header_for_reader(header) + data;
  return scan;
}

}  // namespace mrcloth
