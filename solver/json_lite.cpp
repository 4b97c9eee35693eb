#include "json_lite.h"

#include "mesh_ops/errors.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <locale>
#include <sstream>
#include <system_error>

namespace mrcloth {
namespace {

constexpr int kMaxDepth = 512;

const char* kind_name(JsonValue::Kind kind) {
  switch (kind) {
    case JsonValue::Kind::null: return "null";
    case JsonValue::Kind::boolean: return "a boolean";
    case JsonValue::Kind::number: return "a number";
    case JsonValue::Kind::string: return "a string";
    case JsonValue::Kind::array: return "an array";
    case JsonValue::Kind::object: return "an object";
  }
  return "a value";
}

/// A character for a message: printable ASCII as itself, the rest as a code.
std::string shown(char c) {
  const auto byte = static_cast<unsigned char>(c);
  if (byte >= 0x20 && byte < 0x7f) return std::string("'") + c + "'";
  std::ostringstream out;
  out << "byte 0x" << std::hex << static_cast<int>(byte);
  return out.str();
}

void append_utf8(std::string& out, std::uint32_t code) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

}  // namespace

/// Recursive descent over the text; tracks the line for messages.
class JsonParser {
 public:
  JsonParser(std::string_view text, std::shared_ptr<const std::string> source)
      : text_(text), source_(std::move(source)) {}

  JsonValue parse_document() {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;
    skip_whitespace();
    JsonValue root = parse_value(0);
    skip_whitespace();
    if (pos_ < text_.size()) fail("unexpected " + shown(text_[pos_]) + " after the value", "the end of the text");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& problem, const std::string& expected) const {
    throw InputError(*source_ + ":" + std::to_string(line_) + ": " + problem + "; expected " + expected);
  }

  bool at_end() const { return pos_ >= text_.size(); }
  char peek() const { return text_[pos_]; }

  void skip_whitespace() {
    while (!at_end()) {
      const char c = peek();
      if (c == '\n') ++line_;
      else if (c != ' ' && c != '\t' && c != '\r') return;
      ++pos_;
    }
  }

  JsonValue make(JsonValue::Kind kind) const {
    JsonValue value;
    value.kind_ = kind;
    value.line_ = line_;
    value.source_ = source_;
    return value;
  }

  JsonValue parse_value(int depth) {
    if (at_end()) fail("the text ends", "a value");
    switch (peek()) {
      case '{': return parse_object(depth);
      case '[': return parse_array(depth);
      case '"': {
        JsonValue value = make(JsonValue::Kind::string);
        value.string_ = parse_string();
        return value;
      }
      case 't': return parse_literal("true", JsonValue::Kind::boolean, true);
      case 'f': return parse_literal("false", JsonValue::Kind::boolean, false);
      case 'n': return parse_literal("null", JsonValue::Kind::null, false);
      default: break;
    }
    if (peek() == '-' || (peek() >= '0' && peek() <= '9')) return parse_number();
    fail("unexpected " + shown(peek()), "a value (object, array, string, number, true, false or null)");
  }

  JsonValue parse_literal(std::string_view word, JsonValue::Kind kind, bool truth) {
    if (text_.substr(pos_, word.size()) != word) fail("unknown word", "true, false or null");
    JsonValue value = make(kind);
    value.boolean_ = truth;
    pos_ += word.size();
    return value;
  }

  void enter(int depth) const {
    if (depth >= kMaxDepth) fail("nesting deeper than " + std::to_string(kMaxDepth), "shallower arrays and objects");
  }

  JsonValue parse_array(int depth) {
    enter(depth);
    JsonValue value = make(JsonValue::Kind::array);
    ++pos_;  // '['
    skip_whitespace();
    if (!at_end() && peek() == ']') {
      ++pos_;
      return value;
    }
    for (;;) {
      skip_whitespace();
      value.items_.push_back(parse_value(depth + 1));
      skip_whitespace();
      if (at_end()) fail("the text ends inside an array", "',' or ']'");
      if (peek() == ',') {
        ++pos_;
        skip_whitespace();
        if (!at_end() && peek() == ']') fail("a trailing comma", "a value after ','");
        continue;
      }
      if (peek() == ']') {
        ++pos_;
        return value;
      }
      fail("unexpected " + shown(peek()) + " in an array", "',' or ']'");
    }
  }

  JsonValue parse_object(int depth) {
    enter(depth);
    JsonValue value = make(JsonValue::Kind::object);
    ++pos_;  // '{'
    skip_whitespace();
    if (!at_end() && peek() == '}') {
      ++pos_;
      return value;
    }
    for (;;) {
      skip_whitespace();
      if (at_end()) fail("the text ends inside an object", "a key string");
      if (peek() != '"') {
        fail(peek() == '}' ? std::string("a trailing comma") : "unexpected " + shown(peek()) + " in an object",
             "a key string");
      }
      const int key_line = line_;
      std::string key = parse_string();
      for (const auto& member : value.members_) {
        if (member.first == key) {
          throw InputError(*source_ + ":" + std::to_string(key_line) + ": duplicate key \"" + key +
                           "\"; expected unique keys in an object");
        }
      }
      skip_whitespace();
      if (at_end() || peek() != ':') fail(at_end() ? std::string("the text ends") : "unexpected " + shown(peek()), "':' after a key");
      ++pos_;
      skip_whitespace();
      JsonValue member = parse_value(depth + 1);
      value.members_.emplace_back(std::move(key), std::move(member));
      skip_whitespace();
      if (at_end()) fail("the text ends inside an object", "',' or '}'");
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      if (peek() == '}') {
        ++pos_;
        return value;
      }
      fail("unexpected " + shown(peek()) + " in an object", "',' or '}'");
    }
  }

  std::uint32_t parse_hex4() {
    if (pos_ + 4 > text_.size()) fail("the text ends inside a \\u escape", "4 hex digits");
    std::uint32_t code = 0;
    for (int i = 0; i < 4; ++i) {
      const char c = text_[pos_++];
      code <<= 4;
      if (c >= '0' && c <= '9') code |= static_cast<std::uint32_t>(c - '0');
      else if (c >= 'a' && c <= 'f') code |= static_cast<std::uint32_t>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') code |= static_cast<std::uint32_t>(c - 'A' + 10);
      else fail("bad hex digit " + shown(c) + " in a \\u escape", "4 hex digits");
    }
    return code;
  }

  std::string parse_string() {
    ++pos_;  // opening quote
    std::string out;
    for (;;) {
      if (at_end()) fail("the text ends inside a string", "a closing '\"'");
      const char c = text_[pos_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) {
        fail(std::string(c == '\n' ? "a line break" : "a control character (" + shown(c) + ")") + " inside a string",
             "an escape such as \\n");
      }
      if (c != '\\') {
        out += c;
        continue;
      }
      if (at_end()) fail("the text ends inside an escape", "an escape character");
      const char e = text_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t code = parse_hex4();
          if (code >= 0xDC00 && code <= 0xDFFF) fail("an unpaired low surrogate \\u escape", "a high surrogate first");
          if (code >= 0xD800 && code <= 0xDBFF) {
            if (text_.substr(pos_, 2) != "\\u") fail("an unpaired high surrogate \\u escape", "a \\u low surrogate after it");
            pos_ += 2;
            const std::uint32_t low = parse_hex4();
            if (low < 0xDC00 || low > 0xDFFF) fail("a high surrogate followed by another \\u escape", "a low surrogate (\\uDC00-\\uDFFF)");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          append_utf8(out, code);
          break;
        }
        default: fail("unknown escape \\" + std::string(1, e), "one of \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\u");
      }
    }
  }

  /// The RFC grammar -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)? is checked
  /// here; std::from_chars (locale-free) converts the checked span.
  JsonValue parse_number() {
    const std::size_t start = pos_;
    auto digits = [&]() {
      const std::size_t first = pos_;
      while (!at_end() && peek() >= '0' && peek() <= '9') ++pos_;
      return pos_ - first;
    };
    if (peek() == '-') ++pos_;
    if (at_end() || !(peek() >= '0' && peek() <= '9')) fail("a '-' without digits", "a digit");
    if (peek() == '0') {
      ++pos_;
      if (!at_end() && peek() >= '0' && peek() <= '9') fail("a number with a leading zero", "a number such as 0, 0.5 or 10");
    } else {
      digits();
    }
    if (!at_end() && peek() == '.') {
      ++pos_;
      if (digits() == 0) fail("a number ending in '.'", "digits after the decimal point");
    }
    if (!at_end() && (peek() == 'e' || peek() == 'E')) {
      ++pos_;
      if (!at_end() && (peek() == '+' || peek() == '-')) ++pos_;
      if (digits() == 0) fail("an exponent without digits", "digits after 'e'");
    }
    JsonValue value = make(JsonValue::Kind::number);
    const char* first = text_.data() + start;
    const char* last = text_.data() + pos_;
    const auto result = std::from_chars(first, last, value.number_);
    if (result.ec == std::errc::result_out_of_range) {
      // Too small for a double is zero (as strtod would give); too large is refused.
      const std::string_view span(first, static_cast<std::size_t>(last - first));
      const std::size_t e = span.find_first_of("eE");
      if (e == std::string_view::npos || span[e + 1] != '-')
        fail("number " + std::string(span) + " is out of range", "a number within double range");
      value.number_ = span[0] == '-' ? -0.0 : 0.0;
    } else if (result.ec != std::errc() || result.ptr != last) {
      fail("malformed number " + std::string(first, last), "a number");
    }
    return value;
  }

  std::string_view text_;
  std::shared_ptr<const std::string> source_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

const std::string& JsonValue::source() const {
  static const std::string unknown = "<json>";
  return source_ ? *source_ : unknown;
}

void JsonValue::fail(const std::string& problem) const {
  throw InputError(source() + ":" + std::to_string(line_) + ": " + problem);
}

namespace {
[[noreturn]] void wrong_kind(const JsonValue& value, std::string_view what, JsonValue::Kind expected) {
  value.fail(std::string(what) + " is " + kind_name(value.kind()) + "; expected " + kind_name(expected));
}
}  // namespace

bool JsonValue::as_bool(std::string_view what) const {
  if (kind_ != Kind::boolean) wrong_kind(*this, what, Kind::boolean);
  return boolean_;
}

double JsonValue::as_number(std::string_view what) const {
  if (kind_ != Kind::number) wrong_kind(*this, what, Kind::number);
  return number_;
}

int JsonValue::as_int(std::string_view what) const {
  const double number = as_number(what);
  if (!(number >= std::numeric_limits<int>::min() && number <= std::numeric_limits<int>::max()) ||
      number != std::floor(number)) {
    std::ostringstream text;
    text.imbue(std::locale::classic());
    text << number;
    fail(std::string(what) + " is " + text.str() + "; expected an integer");
  }
  return static_cast<int>(number);
}

const std::string& JsonValue::as_string(std::string_view what) const {
  if (kind_ != Kind::string) wrong_kind(*this, what, Kind::string);
  return string_;
}

const std::vector<JsonValue>& JsonValue::as_array(std::string_view what) const {
  if (kind_ != Kind::array) wrong_kind(*this, what, Kind::array);
  return items_;
}

const std::vector<std::pair<std::string, JsonValue>>& JsonValue::as_object(std::string_view what) const {
  if (kind_ != Kind::object) wrong_kind(*this, what, Kind::object);
  return members_;
}

const JsonValue* JsonValue::find(std::string_view key) const {
  for (const auto& member : members_)
    if (member.first == key) return &member.second;
  return nullptr;
}

const JsonValue& JsonValue::at(std::string_view key, std::string_view what) const {
  as_object(what);
  if (const JsonValue* member = find(key)) return *member;
  fail(std::string(what) + " has no key \"" + std::string(key) + "\"");
}

JsonValue parse_json(std::string_view text, const std::string& source) {
  JsonParser parser(text, std::make_shared<const std::string>(source));
  return parser.parse_document();
}

JsonValue read_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file for reading; expected a readable JSON file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read error; expected a readable JSON file");
  const std::string text = buffer.str();
  return parse_json(text, path);
}

}  // namespace mrcloth
