// BVH reading and writing (the Biovision hierarchy + motion format).
//
// The reader walks the file's tokens with line numbers as it goes (a
// cursor, not a list of every token: a clip of 200,000 frames held 24 bytes
// a value that way), parses the HIERARCHY block without recursion (so deeply
// nested garbage cannot exhaust the stack), and reads the MOTION data as a
// token stream: rows may wrap across lines, and every error names the line
// of the offending token.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "mesh_ops/atomic_file.h"
#include "mesh_ops/errors.h"
#include "skeleton.h"

namespace mrcloth {
namespace {

struct Token {
  std::string_view text;
  int line = 1;
};

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

/// The file's tokens one at a time: split on white space; '{' and '}' are
/// tokens of their own, and a ':' ends a token ("Frames:472" gives "Frames:"
/// and "472"). A copy walks on independently (to look ahead).
class TokenCursor {
 public:
  explicit TokenCursor(std::string_view text) : text_(text) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") i_ = 3;  // UTF-8 byte order mark
  }

  /// The next token into `token`; false at the end of the text.
  bool next(Token& token) {
    while (i_ < text_.size() && is_space(text_[i_])) {
      if (ends_line(i_)) ++line_;
      ++i_;
    }
    if (i_ >= text_.size()) return false;
    const std::size_t start = i_;
    if (text_[i_] == '{' || text_[i_] == '}') {
      ++i_;
    } else {
      while (i_ < text_.size() && !is_space(text_[i_]) && text_[i_] != '{' && text_[i_] != '}') {
        ++i_;
        if (text_[i_ - 1] == ':') break;
      }
    }
    token = {text_.substr(start, i_ - start), line_};
    return true;
  }

  /// The line of the text's last token (1 if it has none).
  int last_line() const {
    std::size_t end = text_.size();
    while (end > 0 && is_space(text_[end - 1])) --end;
    int line = 1;
    for (std::size_t k = 0; k < end; ++k) line += ends_line(k) ? 1 : 0;
    return line;
  }

 private:
  /// Whether the character at k ends a line: LF, CRLF (at its LF), or a CR
  /// alone (classic Mac OS files).
  bool ends_line(std::size_t k) const {
    return text_[k] == '\n' || (text_[k] == '\r' && (k + 1 >= text_.size() || text_[k + 1] != '\n'));
  }

  std::string_view text_;
  std::size_t i_ = 0;
  int line_ = 1;
};

/// Parses the whole token as a finite double (locale-independent); a leading '+' is allowed.
std::optional<double> parse_double(std::string_view s) {
  if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

/// What is wrong with a token that parse_double rejected: "non-finite"
/// (nan, inf), "out-of-range" (1e999) or "non-numeric".
std::string bad_number_kind(std::string_view s) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (end != s.data() + s.size()) return "non-numeric";
  return ec == std::errc::result_out_of_range ? "out-of-range" : ec == std::errc() ? "non-finite" : "non-numeric";
}

std::optional<long long> parse_integer(std::string_view s) {
  if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.remove_prefix(1);
  long long value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return value;
}

std::optional<Channel> parse_channel(std::string_view s) {
  if (s == "Xposition") return Channel::x_position;
  if (s == "Yposition") return Channel::y_position;
  if (s == "Zposition") return Channel::z_position;
  if (s == "Xrotation") return Channel::x_rotation;
  if (s == "Yrotation") return Channel::y_rotation;
  if (s == "Zrotation") return Channel::z_rotation;
  return std::nullopt;
}

const char* channel_name(Channel c) {
  switch (c) {
    case Channel::x_position:
      return "Xposition";
    case Channel::y_position:
      return "Yposition";
    case Channel::z_position:
      return "Zposition";
    case Channel::x_rotation:
      return "Xrotation";
    case Channel::y_rotation:
      return "Yrotation";
    case Channel::z_rotation:
      return "Zrotation";
  }
  return "?";
}

/// The axis (0-2) a position channel moves along.
int position_axis(Channel c) { return c == Channel::x_position ? 0 : c == Channel::y_position ? 1 : 2; }

/// A token quoted for a message, shortened, with control and non-ASCII bytes escaped (garbage files).
std::string quoted(std::string_view s) {
  std::string out = "'";
  const std::size_t limit = 40;
  for (std::size_t i = 0; i < s.size() && i < limit; ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c >= 0x7F) {
      static const char* hex = "0123456789ABCDEF";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else {
      out += static_cast<char>(c);
    }
  }
  if (s.size() > limit) out += "...";
  return out + "'";
}

/// The longest frame a clip may hold, seconds.
constexpr double kLongestFrameTime = 60.0;
/// The shortest: 100,000 frames a second, far beyond any capture system.
/// Shorter ones are damage ("1e-300"), whose frame counts for a second of
/// motion no longer fit in an int.
constexpr double kShortestFrameTime = 1e-5;

class BvhParser {
 public:
  BvhParser(std::string path, std::string_view text, const BvhReadOptions& options)
      : path_(std::move(path)), cursor_(text), options_(options) {
    has_ahead_ = cursor_.next(ahead_);
  }

  Motion parse() {
    parse_hierarchy();
    parse_motion();
    return std::move(motion_);
  }

 private:
  /// A joint whose '{' has been read and whose '}' has not.
  struct OpenBlock {
    int joint = -1;
    int brace_line = 0;
    bool has_offset = false;
    bool has_channels = false;
    int channels_line = 0;
  };

  [[noreturn]] void fail(int line, const std::string& problem, const std::string& expected) const {
    throw InputError(path_ + ":" + std::to_string(line) + ": " + problem + "; expected " + expected);
  }

  int last_line() const { return cursor_.last_line(); }
  bool at_end() const { return !has_ahead_; }
  /// The next token without taking it (nullopt at the end).
  std::optional<Token> peek() const { return has_ahead_ ? std::optional<Token>(ahead_) : std::nullopt; }
  /// Takes the next token (there must be one).
  Token take() {
    const Token token = ahead_;
    has_ahead_ = cursor_.next(ahead_);
    return token;
  }
  /// The tokens not yet taken, from the next one on (a copy of the cursor).
  TokenCursor rest() const { return cursor_; }

  /// The next token; at the end of the file fails with "<what is missing>; expected <expected>".
  Token next(const std::string& missing, const std::string& expected) {
    if (at_end()) fail(last_line(), "end of file: " + missing, expected);
    return take();
  }

  double number(const Token& token, const std::string& what) const {
    const auto value = parse_double(token.text);
    if (!value)
      fail(token.line, bad_number_kind(token.text) + " " + what + " " + quoted(token.text), "a finite number");
    return *value;
  }

  std::string joint_label(int joint) const {
    const Joint& j = motion_.skeleton.joints[joint];
    return (j.end_site ? "End Site of '" + motion_.skeleton.joints[j.parent].name + "'" : "joint '" + j.name + "'");
  }

  [[noreturn]] void fail_unclosed(const OpenBlock& block, const std::string& before) const {
    fail(block.brace_line, "'{' of " + joint_label(block.joint) + " is never closed", "'}' before " + before);
  }

  // ---- HIERARCHY -------------------------------------------------------

  void parse_hierarchy() {
    if (at_end()) fail(1, "empty file", "HIERARCHY");
    const Token first = next("", "HIERARCHY");
    if (first.text != "HIERARCHY") fail(first.line, "the file starts with " + quoted(first.text), "HIERARCHY");

    std::vector<OpenBlock> open;
    for (;;) {
      if (at_end()) {
        if (!open.empty()) fail_unclosed(open.back(), "the end of the file");
        fail(last_line(), "end of file in the hierarchy", "MOTION");
      }
      const Token token = take();
      const std::string_view word = token.text;
      if (open.empty()) {
        if (word == "ROOT") {
          open.push_back(open_joint(token, -1, false));
        } else if (word == "MOTION") {
          if (motion_.skeleton.joints.empty()) fail(token.line, "MOTION before any ROOT", "ROOT");
          return;
        } else if (word == "}") {
          fail(token.line, "unmatched '}'", "ROOT or MOTION");
        } else if (word == "JOINT" || word == "End" || word == "OFFSET" || word == "CHANNELS") {
          fail(token.line, quoted(word) + " outside any ROOT", "ROOT or MOTION");
        } else {
          fail(token.line, "unknown keyword " + quoted(word), "ROOT or MOTION");
        }
        continue;
      }

      OpenBlock& block = open.back();
      Joint& joint = motion_.skeleton.joints[block.joint];
      if (word == "OFFSET") {
        if (block.has_offset)
          fail(token.line, "a second OFFSET in " + joint_label(block.joint), "one OFFSET per joint");
        for (int k = 0; k < 3; ++k) {
          const Token value = next("OFFSET has " + std::to_string(k) + " values", "3 numbers after OFFSET");
          if (!parse_double(value.text) && value.line != token.line)
            fail(token.line, "OFFSET has " + std::to_string(k) + " values", "3 numbers after OFFSET");
          joint.offset[k] = number(value, "OFFSET value") * options_.scale;
        }
        block.has_offset = true;
      } else if (word == "CHANNELS") {
        if (joint.end_site) fail(token.line, "CHANNELS in an End Site", "only OFFSET in an End Site");
        if (block.has_channels)
          fail(token.line, "a second CHANNELS in " + joint_label(block.joint), "one CHANNELS per joint");
        parse_channels(token, joint);
        block.has_channels = true;
        block.channels_line = token.line;
      } else if (word == "JOINT" || word == "End") {
        if (joint.end_site) fail(token.line, quoted(word) + " inside an End Site", "only OFFSET in an End Site");
        const int parent = block.joint;
        open.push_back(open_joint(token, parent, word == "End"));  // invalidates `block` and `joint`
      } else if (word == "}") {
        if (!block.has_offset) fail(token.line, joint_label(block.joint) + " has no OFFSET", "OFFSET before '}'");
        open.pop_back();
      } else if (word == "ROOT" || word == "MOTION") {
        fail_unclosed(block, quoted(word));
      } else if (word == "{") {
        fail(token.line, "unexpected '{'", "OFFSET, CHANNELS, JOINT, End Site or '}'");
      } else if (parse_channel(word) && block.has_channels) {
        fail(block.channels_line,
             "CHANNELS declares " + std::to_string(joint.channels.size()) + " channels but lists more",
             "as many channel names as the count");
      } else {
        fail(token.line, "unknown keyword " + quoted(word), "OFFSET, CHANNELS, JOINT, End Site or '}'");
      }
    }
  }

  /// Reads "<name tokens> {" after ROOT or JOINT (or "Site {" after End) and adds the joint.
  OpenBlock open_joint(const Token& keyword, int parent, bool end_site) {
    Skeleton& skeleton = motion_.skeleton;
    Joint joint;
    joint.parent = parent;
    joint.end_site = end_site;
    joint.first_channel = channel_total_;
    if (end_site) {
      const Token site = next("'End' without 'Site'", "'End Site'");
      if (site.text != "Site") fail(site.line, "'End' followed by " + quoted(site.text), "'End Site'");
      joint.name = unused_name(skeleton.joints[parent].name + "_end");
      site_names_[joint.name] = static_cast<int>(skeleton.joints.size());
    } else {
      // The name is every token on the keyword's line up to '{' (names with
      // spaces exist), one space between tokens that white space parted;
      // tokens the tokenizer parted after a ':' join as they were (Mixamo's
      // "mixamorig:Hips", Maya's namespaces).
      const char* previous_end = nullptr;
      while (!at_end() && ahead_.line == keyword.line && ahead_.text != "{" && ahead_.text != "}") {
        const std::string_view part = take().text;
        if (!joint.name.empty() && part.data() != previous_end) joint.name += ' ';
        joint.name += std::string(part);
        previous_end = part.data() + part.size();
      }
      if (joint.name.empty()) fail(keyword.line, quoted(keyword.text) + " without a name", "a joint name");
      // A name the reader made up for an End Site gives way to the file's own.
      if (const auto site = site_names_.find(joint.name); site != site_names_.end()) {
        const int index = site->second;
        site_names_.erase(site);
        Joint& site_joint = skeleton.joints[static_cast<std::size_t>(index)];
        const std::string renamed = unused_name(site_joint.name);  // while the old one is still taken
        names_.erase(site_joint.name);
        site_joint.name = renamed;
        names_.insert(renamed);
        site_names_[renamed] = index;
      }
      if (names_.count(joint.name) > 0)
        fail(keyword.line, "a second joint named " + quoted(joint.name), "unique joint names");
    }
    const Token brace = next("no '{' after " + quoted(keyword.text), "'{'");
    if (brace.text != "{")
      fail(brace.line, quoted(brace.text) + " after " + quoted(keyword.text) + " " + quoted(joint.name), "'{'");
    names_.insert(joint.name);
    skeleton.joints.push_back(std::move(joint));
    return {static_cast<int>(skeleton.joints.size()) - 1, brace.line, false, false, 0};
  }

  /// `base`, or base2, base3, ...: the first no joint has yet.
  std::string unused_name(const std::string& base) const {
    std::string name = base;
    for (int k = 2; names_.count(name) > 0; ++k) name = base + std::to_string(k);
    return name;
  }

  void parse_channels(const Token& keyword, Joint& joint) {
    const Token count_token = next("CHANNELS without a count", "a channel count in 0..6");
    const auto count = parse_integer(count_token.text);
    if (!count || *count < 0 || *count > 6)
      fail(count_token.line, "channel count " + quoted(count_token.text), "an integer in 0..6");
    const std::string declared = "CHANNELS declares " + std::to_string(*count) + " channels";
    joint.first_channel = channel_total_;  // columns follow the order of the CHANNELS lines
    for (long long k = 0; k < *count; ++k) {
      const std::optional<Token> name = peek();
      const auto channel = name ? parse_channel(name->text) : std::nullopt;
      if (!channel) {
        // A keyword, a brace or the next line: the list is shorter than its count.
        if (!name || name->line != keyword.line || name->text == "{" || name->text == "}")
          fail(keyword.line, declared + " but lists " + std::to_string(k), std::to_string(*count) + " channel names");
        fail(name->line, "unknown channel " + quoted(name->text),
             "Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation");
      }
      for (const Channel c : joint.channels)
        if (c == *channel)
          fail(name->line, "channel " + quoted(name->text) + " listed twice", "each channel at most once");
      joint.channels.push_back(*channel);
      take();
    }
    if (const std::optional<Token> after = peek(); after && parse_channel(after->text))
      fail(keyword.line, declared + " but lists more", std::to_string(*count) + " channel names");
    channel_total_ += static_cast<int>(joint.channels.size());
  }

  // ---- MOTION ----------------------------------------------------------

  void parse_motion() {
    const FrameCount count = parse_frame_count();
    motion_.frame_time = parse_frame_time();
    const long long channels = channel_total_;
    const long long rows = count.frames;
    const std::string expectation = require_motion_data(count.line, rows, channels);
    read_frames(count.line, rows, channels);
    if (!at_end())
      fail(ahead_.line, "extra value " + quoted(ahead_.text) + " after " + std::to_string(rows) + " frames",
           "the end of the file after " + expectation);
  }

  struct FrameCount {
    long long frames;  // positive
    int line;          // where the count is written
  };

  /// 'Frames: <count>'.
  FrameCount parse_frame_count() {
    const Token frames_word = next("no 'Frames:' after MOTION", "'Frames: <count>'");
    if (frames_word.text == "Frames" && peek() && peek()->text == ":")
      take();
    else if (frames_word.text != "Frames:")
      fail(frames_word.line, quoted(frames_word.text) + " after MOTION", "'Frames: <count>'");
    const Token count_token = next("no frame count", "'Frames: <count>'");
    const auto count = parse_integer(count_token.text);
    if (!count) {
      // A number written otherwise ("40.0", "1e3") is named as one.
      const std::string text(count_token.text);
      char* end = nullptr;
      std::strtod(text.c_str(), &end);
      const bool number = !text.empty() && end == text.c_str() + text.size();
      fail(count_token.line, (number ? "frame count " : "non-numeric frame count ") + quoted(count_token.text) +
                                 (number ? " is not written as a whole number" : ""),
           "a positive integer");
    }
    if (*count <= 0) fail(count_token.line, "frame count " + std::to_string(*count), "a positive integer");
    return {*count, count_token.line};
  }

  /// 'Frame Time: <seconds>': the seconds, within the bounds a clip can play.
  double parse_frame_time() {
    const Token frame_word = next("no 'Frame Time:'", "'Frame Time: <seconds>'");
    const std::optional<Token> time_word = peek();
    if (frame_word.text != "Frame" || !time_word || (time_word->text != "Time:" && time_word->text != "Time"))
      fail(frame_word.line, quoted(frame_word.text) + " after the frame count", "'Frame Time: <seconds>'");
    take();
    if (time_word->text == "Time" && peek() && peek()->text == ":") take();
    const Token time_token = next("no frame time", "'Frame Time: <seconds>'");
    const auto time = parse_double(time_token.text);
    if (!time)
      fail(time_token.line, bad_number_kind(time_token.text) + " frame time " + quoted(time_token.text),
           "a positive number of seconds");
    if (!(*time > 0.0))
      fail(time_token.line, "frame time " + std::string(time_token.text), "a positive number of seconds");
    // Keyframed clips hold a frame a second or so; "1e300" plays as a still pose.
    if (*time > kLongestFrameTime)
      fail(time_token.line, "frame time " + std::string(time_token.text) + " s",
           "at most " + std::to_string(static_cast<int>(kLongestFrameTime)) + " seconds per frame");
    if (*time < kShortestFrameTime)
      fail(time_token.line, "frame time " + std::string(time_token.text) + " s",
           "at least 0.00001 seconds per frame (100,000 frames a second)");
    return *time;
  }

  /// Refuses motion data that holds fewer than `rows` x `channels` values
  /// (naming a bad value first where there is one: it comes earlier in the
  /// file). Returns what is expected, "<rows> frames x <channels> channels
  /// = <values> values", for later messages.
  std::string require_motion_data(int count_line, long long rows, long long channels) {
    if (rows > 2147483647) fail(count_line, "frame count " + std::to_string(rows), "at most 2147483647 frames");
    const long long available = survey_rows(channels);
    const bool fits = channels == 0 || rows <= available / channels;  // rows x channels <= available, no overflow
    std::string expectation = std::to_string(rows) + " frames x " + std::to_string(channels) + " channels";
    if (rows <= std::numeric_limits<long long>::max() / std::max(channels, 1LL))
      expectation += " = " + std::to_string(rows * channels) + " values";
    if (fits) return expectation;
    if (!at_end()) {
      check_value(ahead_, 0, channels);
      TokenCursor values = rest();
      Token token;
      for (std::size_t k = 1; values.next(token); ++k) check_value(token, k, channels);
    }
    const long long complete = channels > 0 ? available / channels : 0;
    fail(last_line(),
         "motion data ends after " + std::to_string(available) + " values (" + std::to_string(complete) +
             " complete frames)",
         expectation);
  }

  /// Reads the `rows` frames of `channels` values (the first dropped when
  /// the options skip it), positions scaled to metres relative to the rest.
  void read_frames(int frames_line, long long rows, long long channels) {
    const int skip = options_.skip_first_frame ? 1 : 0;
    if (rows - skip < 1)
      fail(frames_line, "skip_first_frame leaves no frame of " + std::to_string(rows), "at least 2 frames");
    motion_.frames.resize(rows - skip, channels);
    for (long long r = 0; r < rows && channels > 0; ++r)
      for (long long c = 0; c < channels; ++c) {
        const Token token = take();
        const double value = check_value(token, static_cast<std::size_t>(r * channels + c), channels);
        if (r < skip) continue;
        motion_.frames(r - skip, c) =
            is_position(channel_of_column(c)) ? value * options_.scale - rest_of_column_[static_cast<std::size_t>(c)] : value;
      }
  }

  /// Counts the values left (the next token on) without taking them, and
  /// checks their rows: where the data's first line holds one whole frame,
  /// every line before the last must: a row short by a value and the next
  /// long by one would otherwise shift a frame's channels silently, and a
  /// short row within the data is named, not the end of the file. (The last
  /// line is checked against the frame count; rows that wrap over lines are
  /// read as one stream of values.)
  long long survey_rows(long long channels) const {
    if (at_end()) return 0;
    TokenCursor values = rest();
    const int first_line = ahead_.line;
    long long available = 1, first_count = 1, count = 0;
    int line = first_line;
    Token token;
    while (values.next(token)) {
      ++available;
      if (token.line == first_line) {
        ++first_count;
        continue;
      }
      if (token.line != line) {
        // `line` ended with a token after it: not the last line.
        if (line != first_line && first_count == channels && count != channels) fail_row(line, count, channels, first_line);
        line = token.line;
        count = 0;
      }
      ++count;
    }
    return available;
  }

  [[noreturn]] void fail_row(int line, long long count, long long channels, int first_line) const {
    fail(line, "a row of " + std::to_string(count) + " values",
         std::to_string(channels) + " values per row, as the first frame's row (line " + std::to_string(first_line) +
             ")");
  }

  double check_value(const Token& token, std::size_t index, long long channels) const {
    const auto value = parse_double(token.text);
    if (!value) {
      const std::string where = channels > 0 ? " in frame " + std::to_string(index / channels) : std::string();
      fail(token.line, bad_number_kind(token.text) + " value " + quoted(token.text) + where, "a finite number");
    }
    return *value;
  }

  Channel channel_of_column(long long column) {
    if (column_channels_.empty()) {
      column_channels_.resize(channel_total_);
      rest_of_column_.assign(static_cast<std::size_t>(channel_total_), 0.0);
      const bool absolute = options_.position_channels == PositionChannels::absolute;
      for (const Joint& joint : motion_.skeleton.joints)
        for (std::size_t k = 0; k < joint.channels.size(); ++k) {
          const auto column_k = static_cast<std::size_t>(joint.first_channel) + k;
          const Channel channel = joint.channels[k];
          column_channels_[column_k] = channel;
          if (absolute && is_position(channel)) rest_of_column_[column_k] = joint.offset[position_axis(channel)];
        }
    }
    return column_channels_[column];
  }

  std::string path_;
  TokenCursor cursor_;  ///< just after ahead_
  Token ahead_;         ///< the next token, when has_ahead_
  bool has_ahead_ = false;
  BvhReadOptions options_;
  Motion motion_;
  int channel_total_ = 0;
  std::vector<Channel> column_channels_;
  /// Per column, what its value is measured from beyond the offset's (the
  /// offset's component for an absolute position channel, else 0), metres.
  std::vector<double> rest_of_column_;
  std::unordered_set<std::string> names_;  ///< of the joints so far (End Sites included)
  std::unordered_map<std::string, int> site_names_;  ///< the names made up for End Sites, to their joints
};

// ---- writing ------------------------------------------------------------

/// Shortest of up to 12 significant digits, independent of the C locale.
void append_number(std::string& out, double value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, 12);
  if (ec != std::errc()) throw OutputError("write_bvh: cannot format the value " + std::to_string(value));
  out.append(buffer, end);
}

void check_writable(const Motion& motion, double scale) {
  const Skeleton& skeleton = motion.skeleton;
  if (!(scale > 0.0) || !std::isfinite(scale)) throw ArgumentError("write_bvh: scale must be positive and finite");
  if (skeleton.joints.empty()) throw ArgumentError("write_bvh: the skeleton has no joint");
  if (!(motion.frame_time > 0.0) || !std::isfinite(motion.frame_time))
    throw ArgumentError("write_bvh: frame_time must be positive and finite");
  if (motion.frames.rows() < 1) throw ArgumentError("write_bvh: the motion has no frame");
  const int channels = skeleton.channel_count();
  if (motion.frames.cols() != channels)
    throw ArgumentError("write_bvh: frames has " + std::to_string(motion.frames.cols()) +
                        " columns but the skeleton has " + std::to_string(channels) + " channels");
  if (!motion.frames.allFinite()) throw ArgumentError("write_bvh: frames holds a non-finite value");
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    const std::string label = "write_bvh: joint " + std::to_string(j) + " '" + joint.name + "'";
    if (joint.parent < -1 || joint.parent >= static_cast<int>(j))
      throw ArgumentError(label + " has parent " + std::to_string(joint.parent) + ", not an earlier joint");
    if (joint.end_site && (joint.parent < 0 || !joint.channels.empty()))
      throw ArgumentError(label + " is an End Site with channels or without a parent");
    if (joint.parent >= 0 && skeleton.joints[joint.parent].end_site)
      throw ArgumentError(label + " is the child of an End Site");
    if (!joint.end_site) {
      if (joint.name.empty() || joint.name.find_first_of("{}\t\r\n") != std::string::npos ||
          joint.name.front() == ' ' || joint.name.back() == ' ' || joint.name.find("  ") != std::string::npos)
        throw ArgumentError(label + ": the name must be non-empty, single-spaced, without tabs, newlines or braces");
    }
    if (joint.first_channel < 0 || joint.first_channel + static_cast<int>(joint.channels.size()) > channels)
      throw ArgumentError(label + " has channels outside the frame columns");
    if (!joint.offset.allFinite()) throw ArgumentError(label + " has a non-finite offset");
  }
}

}  // namespace

Motion read_bvh(const std::string& path, const BvhReadOptions& options) {
  if (!(options.scale > 0.0) || !std::isfinite(options.scale))
    throw ArgumentError("read_bvh: scale must be positive and finite (" + path + ")");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file; expected a readable BVH file");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path + ": cannot read the file; expected a readable BVH file");
  return BvhParser(path, text, options).parse();
}

namespace {

/// One joint's block opening: its name line, "{", OFFSET (divided by
/// `scale`) and, but for an End Site, its CHANNELS line.
void append_joint_header(std::string& text, const Joint& joint, const std::string& indent, double scale) {
  text += indent + (joint.end_site ? std::string("End Site") : (joint.parent < 0 ? "ROOT " : "JOINT ") + joint.name) +
          "\n";
  text += indent + "{\n";
  text += indent + "\tOFFSET";
  for (int k = 0; k < 3; ++k) {
    text += ' ';
    append_number(text, joint.offset[k] / scale);
  }
  text += '\n';
  if (joint.end_site) return;
  text += indent + "\tCHANNELS " + std::to_string(joint.channels.size());
  for (const Channel c : joint.channels) text += std::string(" ") + channel_name(c);
  text += '\n';
}

/// The HIERARCHY block, depth-first in joint order; returns the joints
/// with channels in the order written, which the data's columns follow.
std::vector<int> append_hierarchy(std::string& text, const Skeleton& skeleton, double scale) {
  const int n = static_cast<int>(skeleton.joints.size());
  std::vector<std::vector<int>> children(n);
  for (int j = 0; j < n; ++j)
    if (skeleton.joints[j].parent >= 0) children[skeleton.joints[j].parent].push_back(j);
  text += "HIERARCHY\n";
  std::vector<int> column_order;
  struct Item {
    int joint;
    int depth;
    bool close;
  };
  std::vector<Item> stack;
  for (int j = n - 1; j >= 0; --j)
    if (skeleton.joints[j].parent < 0) stack.push_back({j, 0, false});
  while (!stack.empty()) {
    const Item item = stack.back();
    stack.pop_back();
    const std::string indent(static_cast<std::size_t>(item.depth), '\t');
    if (item.close) {
      text += indent + "}\n";
      continue;
    }
    const Joint& joint = skeleton.joints[item.joint];
    append_joint_header(text, joint, indent, scale);
    if (!joint.end_site) column_order.push_back(item.joint);
    stack.push_back({item.joint, item.depth, true});
    for (auto it = children[item.joint].rbegin(); it != children[item.joint].rend(); ++it)
      stack.push_back({*it, item.depth + 1, false});
  }
  return column_order;
}

/// The MOTION block: the frames' channels in `column_order`'s joints'
/// order, positions back in the file's units (offset added, divided by
/// `scale`).
void append_motion(std::string& text, const Motion& motion, const std::vector<int>& column_order, double scale) {
  text += "MOTION\nFrames: " + std::to_string(motion.frames.rows()) + "\nFrame Time: ";
  append_number(text, motion.frame_time);
  text += '\n';
  for (Eigen::Index r = 0; r < motion.frames.rows(); ++r) {
    bool first = true;
    for (const int j : column_order) {
      const Joint& joint = motion.skeleton.joints[j];
      for (std::size_t k = 0; k < joint.channels.size(); ++k) {
        if (!first) text += ' ';
        first = false;
        const double value = motion.frames(r, joint.first_channel + static_cast<Eigen::Index>(k));
        const Channel channel = joint.channels[k];
        append_number(text, is_position(channel) ? (value + joint.offset[position_axis(channel)]) / scale : value);
      }
    }
    text += '\n';
  }
}

}  // namespace

void write_bvh(const std::string& path, const Motion& motion, double scale) {
  check_writable(motion, scale);
  std::string text;
  const std::vector<int> column_order = append_hierarchy(text, motion.skeleton, scale);
  append_motion(text, motion, column_order, scale);
  write_file_atomically(path, ".bvh", [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.flush();
    return static_cast<bool>(out);
  });
}

}  // namespace mrcloth
