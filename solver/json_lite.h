#pragma once
// A minimal, strict JSON reader (RFC 8259): objects, arrays, strings with
// every escape (\uXXXX and surrogate pairs to UTF-8), numbers, true, false,
// null. Enough for MakeHuman's .mhskel and .mhw files; no writer. Every value
// remembers its source and line, so the checked accessors can say where a
// file is not what the caller expected.
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mrcloth {

class JsonValue {
 public:
  enum class Kind { null, boolean, number, string, array, object };

  JsonValue() = default;

  Kind kind() const { return kind_; }
  bool is_null() const { return kind_ == Kind::null; }
  bool is_bool() const { return kind_ == Kind::boolean; }
  bool is_number() const { return kind_ == Kind::number; }
  bool is_string() const { return kind_ == Kind::string; }
  bool is_array() const { return kind_ == Kind::array; }
  bool is_object() const { return kind_ == Kind::object; }
  /// 1-based line where the value starts, and the source it was read from
  /// (a file path, or the name given to parse_json).
  int line() const { return line_; }
  const std::string& source() const;

  // Checked accessors: each throws InputError "<source>:<line>: <what> is
  // <kind>; expected <kind>" when the value is of another kind. `what`
  // names the value for the message ("bone \"Hips\" head").
  bool as_bool(std::string_view what = "value") const;
  double as_number(std::string_view what = "value") const;
  /// A number that is an integer within int range.
  int as_int(std::string_view what = "value") const;
  const std::string& as_string(std::string_view what = "value") const;
  const std::vector<JsonValue>& as_array(std::string_view what = "value") const;
  /// Members in file order (keys are unique: the parser refuses duplicates).
  const std::vector<std::pair<std::string, JsonValue>>& as_object(std::string_view what = "value") const;

  /// Member `key` of an object, nullptr when absent (or not an object).
  const JsonValue* find(std::string_view key) const;
  /// Member `key` of an object; InputError naming the key when absent.
  const JsonValue& at(std::string_view key, std::string_view what = "object") const;

  /// Throws InputError "<source>:<line>: <problem>".
  [[noreturn]] void fail(const std::string& problem) const;

 private:
  friend class JsonParser;
  Kind kind_ = Kind::null;
  int line_ = 0;
  bool boolean_ = false;
  double number_ = 0.0;
  std::string string_;
  std::vector<JsonValue> items_;
  std::vector<std::pair<std::string, JsonValue>> members_;
  std::shared_ptr<const std::string> source_;
};

/// Parses a whole JSON text (one value, surrounded by optional whitespace;
/// a leading UTF-8 byte order mark is skipped). Throws InputError
/// "<source>:<line>: <problem>; expected <what>" on the first error:
/// trailing commas, comments, single quotes, leading zeros, control
/// characters in strings, bad escapes or unpaired surrogates, numbers out
/// of double range, duplicate keys, nesting deeper than 512, trailing text.
JsonValue parse_json(std::string_view text, const std::string& source = "<json>");

/// Reads and parses a file; InputError naming the file when it cannot be read.
JsonValue read_json(const std::string& path);

}  // namespace mrcloth
