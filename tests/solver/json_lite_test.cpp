#include "solver/json_lite.h"

#include "mesh_ops/errors.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace mrcloth {
namespace {

/// The message of the InputError that parsing `text` throws ("" if none).
std::string parse_error(const std::string& text) {
  try {
    parse_json(text, "test.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(JsonLite, ParsesNestedValuesInOrder) {
  const JsonValue root = parse_json(R"({
    "name": "rig",
    "bones": {"Hips": {"parent": null, "reference": ["root", "spine05"], "roll": -4.4e-10}},
    "flags": [true, false, null],
    "empty_array": [], "empty_object": {}
  })");
  ASSERT_TRUE(root.is_object());
  const auto& members = root.as_object();
  ASSERT_EQ(members.size(), 5u);
  EXPECT_EQ(members[0].first, "name");
  EXPECT_EQ(members[4].first, "empty_object");
  EXPECT_EQ(root.at("name").as_string(), "rig");
  const JsonValue& hips = root.at("bones").at("Hips");
  EXPECT_TRUE(hips.at("parent").is_null());
  ASSERT_EQ(hips.at("reference").as_array().size(), 2u);
  EXPECT_EQ(hips.at("reference").as_array()[1].as_string(), "spine05");
  EXPECT_DOUBLE_EQ(hips.at("roll").as_number(), -4.4e-10);
  const auto& flags = root.at("flags").as_array();
  ASSERT_EQ(flags.size(), 3u);
  EXPECT_TRUE(flags[0].as_bool());
  EXPECT_FALSE(flags[1].as_bool());
  EXPECT_TRUE(flags[2].is_null());
  EXPECT_TRUE(root.at("empty_array").as_array().empty());
  EXPECT_TRUE(root.at("empty_object").as_object().empty());
  EXPECT_EQ(root.find("missing"), nullptr);
  EXPECT_EQ(hips.line(), 3);
  EXPECT_EQ(root.at("flags").line(), 4);
}

TEST(JsonLite, NumbersFollowTheGrammar) {
  const JsonValue numbers = parse_json("[0, -0, 7, -12, 3.25, 1e3, 1E+2, 2.5e-3, -0.0, 123456789012, 1e-400]");
  const auto& n = numbers.as_array();
  ASSERT_EQ(n.size(), 11u);
  EXPECT_EQ(n[0].as_number(), 0.0);
  EXPECT_EQ(n[1].as_number(), 0.0);
  EXPECT_TRUE(std::signbit(n[1].as_number()));
  EXPECT_EQ(n[2].as_int(), 7);
  EXPECT_EQ(n[3].as_int(), -12);
  EXPECT_EQ(n[4].as_number(), 3.25);
  EXPECT_EQ(n[5].as_number(), 1000.0);
  EXPECT_EQ(n[5].as_int(), 1000);
  EXPECT_EQ(n[6].as_number(), 100.0);
  EXPECT_EQ(n[7].as_number(), 2.5e-3);
  EXPECT_EQ(n[9].as_number(), 123456789012.0);
  EXPECT_EQ(n[10].as_number(), 0.0) << "underflow is zero, as strtod gives";
  // Exact round trip of a double written with 17 digits.
  EXPECT_EQ(parse_json("0.10000000000000001").as_number(), 0.1);
  EXPECT_EQ(parse_json("-2.2250738585072014e-308").as_number(), -2.2250738585072014e-308);
}

TEST(JsonLite, StringEscapesDecodeToUtf8) {
  const JsonValue s = parse_json(R"(["a\"b\\c\/d", "\b\f\n\r\t", "\u0041\u00e9\u20ac", "\ud83d\ude00", "caf\u00E9 ok"])");
  const auto& a = s.as_array();
  EXPECT_EQ(a[0].as_string(), "a\"b\\c/d");
  EXPECT_EQ(a[1].as_string(), "\b\f\n\r\t");
  EXPECT_EQ(a[2].as_string(), "A\xC3\xA9\xE2\x82\xAC");
  EXPECT_EQ(a[3].as_string(), "\xF0\x9F\x98\x80");
  EXPECT_EQ(a[4].as_string(), "caf\xC3\xA9 ok");
  // Raw UTF-8 passes through; a leading byte order mark is skipped.
  EXPECT_EQ(parse_json("\xEF\xBB\xBF\"\xC3\xA9\"").as_string(), "\xC3\xA9");
}

TEST(JsonLite, ErrorsNameTheSourceAndLine) {
  struct Case {
    const char* text;
    const char* where;    // "test.json:<line>:"
    const char* problem;  // a fragment of the message
  };
  const Case cases[] = {
      {"{\n  \"a\": 1,\n}", "test.json:3:", "trailing comma"},
      {"[1,\n 2,\n ]", "test.json:3:", "trailing comma"},
      {"{\"a\" 1}", "test.json:1:", "expected ':'"},
      {"[1 2]", "test.json:1:", "expected ',' or ']'"},
      {"\n\n[01]", "test.json:3:", "leading zero"},
      {"[1.]", "test.json:1:", "decimal point"},
      {"[1e]", "test.json:1:", "exponent"},
      {"[-]", "test.json:1:", "'-' without digits"},
      {"[+1]", "test.json:1:", "unexpected '+'"},
      {"[.5]", "test.json:1:", "unexpected '.'"},
      {"[1e999]", "test.json:1:", "out of range"},
      {"[NaN]", "test.json:1:", "unexpected 'N'"},
      {"[tru]", "test.json:1:", "true, false or null"},
      {"['a']", "test.json:1:", "unexpected '''"},
      {"{\"a\": 1, \"a\": 2}", "test.json:1:", "duplicate key \"a\""},
      {"\n\"a\nb\"", "test.json:2:", "line break inside a string"},
      {"\"a\tb\"", "test.json:1:", "control character"},
      {"\"\\x\"", "test.json:1:", "unknown escape \\x"},
      {"\"\\u12G4\"", "test.json:1:", "bad hex digit"},
      {"\"\\ud800\"", "test.json:1:", "unpaired high surrogate"},
      {"\"\\udc00\"", "test.json:1:", "unpaired low surrogate"},
      {"\"\\ud800\\u0041\"", "test.json:1:", "low surrogate"},
      {"\"abc", "test.json:1:", "ends inside a string"},
      {"[1, 2", "test.json:1:", "ends inside an array"},
      {"{\"a\": [1]", "test.json:1:", "ends inside an object"},
      {"", "test.json:1:", "expected a value"},
      {"  \n ", "test.json:2:", "expected a value"},
      {"[1] [2]", "test.json:1:", "after the value"},
      {"// comment\n[1]", "test.json:1:", "unexpected '/'"},
      {"{1: 2}", "test.json:1:", "a key string"},
  };
  for (const Case& c : cases) {
    const std::string message = parse_error(c.text);
    EXPECT_EQ(message.rfind(c.where, 0), 0u) << "text: " << c.text << "\nmessage: " << message;
    EXPECT_NE(message.find(c.problem), std::string::npos) << "text: " << c.text << "\nmessage: " << message;
  }
  std::string deep(600, '[');
  deep += std::string(600, ']');
  EXPECT_NE(parse_error(deep).find("nesting deeper than 512"), std::string::npos);
  EXPECT_EQ(parse_error(std::string(500, '[') + std::string(500, ']')), "");
}

TEST(JsonLite, CheckedAccessorsSayWhatWasExpected) {
  const JsonValue root = parse_json("{\n\"bones\": {\n\"Hips\": {\"head\": 3, \"index\": 2.5}}}", "rig.mhskel");
  const JsonValue& hips = root.at("bones").at("Hips");
  try {
    hips.at("head").as_string("bone \"Hips\" head");
    FAIL() << "as_string accepted a number";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "rig.mhskel:3: bone \"Hips\" head is a number; expected a string");
  }
  try {
    hips.at("tail", "bone \"Hips\"");
    FAIL() << "at() accepted a missing key";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "rig.mhskel:3: bone \"Hips\" has no key \"tail\"");
  }
  EXPECT_THROW(hips.at("index").as_int(), InputError);
  EXPECT_THROW(root.as_array(), InputError);
  EXPECT_THROW(parse_json("4294967296").as_int(), InputError);
  EXPECT_EQ(parse_json("-2147483648").as_int(), -2147483647 - 1);
}

TEST(JsonLite, ReadsFilesAndNamesMissingOnes) {
  const char* tmp = std::getenv("MRCLOTH_TEST_TMP");
  const std::filesystem::path dir = tmp ? tmp : std::filesystem::temp_directory_path();
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "json_lite_test.json").string();
  {
    std::ofstream out(path);
    out << "{\n  \"weights\": {\n    \"root\": [[0, 0.5], [1, 1]]\n  },\n  \"x\": [1,]\n}\n";
  }
  try {
    read_json(path);
    FAIL() << "a trailing comma was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":5:", 0), 0u) << e.what();
  }
  const std::string missing = (dir / "no_such_file.json").string();
  try {
    read_json(missing);
    FAIL() << "a missing file was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
}

TEST(JsonLite, ParsesTheMakeHumanFiles) {
  const std::string rigs = std::string(MRCLOTH_SHARED_DATA) + "/bodies/makehuman/rigs/";
  if (!std::filesystem::exists(rigs + "cmu_mb.mhskel") || !std::filesystem::exists(rigs + "default_weights.mhw"))
    GTEST_SKIP() << "shared data not found under " << rigs << " (set MRCLOTH_SHARED_DATA)";
  const JsonValue skeleton = read_json(rigs + "cmu_mb.mhskel");
  EXPECT_EQ(skeleton.at("bones").as_object().size(), 31u);
  EXPECT_EQ(skeleton.at("joints").as_object().size(), 62u);
  const JsonValue& hips = skeleton.at("bones").at("Hips");
  EXPECT_EQ(hips.at("head").as_string(), "Hips_head");
  EXPECT_TRUE(hips.at("parent").is_null());
  EXPECT_EQ(skeleton.at("joints").at("Hips_head").as_array().size(), 8u);
  EXPECT_EQ(skeleton.at("joints").at("Hips_head").as_array()[0].as_int(), 13622);

  const JsonValue weights = read_json(rigs + "default_weights.mhw");
  const auto& bones = weights.at("weights").as_object();
  EXPECT_EQ(bones.size(), 139u);
  const auto& breast = weights.at("weights").at("breast.L").as_array();
  ASSERT_FALSE(breast.empty());
  EXPECT_EQ(breast[0].as_array()[0].as_int(), 1399);
  EXPECT_DOUBLE_EQ(breast[0].as_array()[1].as_number(), 0.016);
  std::size_t pairs = 0;
  for (const auto& bone : bones) pairs += bone.second.as_array().size();
  EXPECT_GT(pairs, 19000u) << "every base-mesh vertex has at least one weight";
}

}  // namespace
}  // namespace mrcloth
