#include "plugin/core/script_values.h"

#include "mesh_ops/errors.h"

#include <gtest/gtest.h>

#include <limits>

namespace mrcloth::script {
namespace {

/// The message of the ArgumentError `call` throws, or "" if it throws none.
template <class Call>
std::string errorOf(Call&& call) {
  try {
    call();
  } catch (const ArgumentError& error) {
    return error.what();
  }
  return "";
}

TEST(ScriptValues, IntegersAcceptIntegralNumbersOnly) {
  EXPECT_EQ(toInt(QVariant(7), "n"), 7);
  EXPECT_EQ(toInt(QVariant(7.0), "n"), 7);
  EXPECT_EQ(toInt(QVariant(qlonglong(-3)), "n"), -3);
  EXPECT_EQ(errorOf([] { toInt(QVariant(2.5), "levels"); }), "levels must be an integer, got the number 2.5");
  EXPECT_EQ(errorOf([] { toInt(QVariant(QStringLiteral("2")), "levels"); }),
            "levels must be an integer, got the string \"2\"");
  EXPECT_EQ(errorOf([] { toInt(QVariant(), "id"); }), "id must be an integer, got undefined");
  EXPECT_EQ(errorOf([] { toInt(QVariant::fromValue(nullptr), "id"); }), "id must be an integer, got null");
  EXPECT_EQ(errorOf([] { toInt(QVariant(true), "id"); }), "id must be an integer, got true");
  EXPECT_EQ(errorOf([] { toInt(QVariant(12345678901.0), "seed"); }),
            "seed must be an integer from -2147483648 to 2147483647, got the number 12345678901")
      << "a whole number out of range is named as such, not as 'not an integer'";
  EXPECT_EQ(errorOf([] { toInt(QVariant(-1e10), "frame"); }),
            "frame must be an integer from -2147483648 to 2147483647, got the number -1e+10");
  EXPECT_EQ(errorOf([] { toIntAtLeast(QVariant(-1), "levels", 0); }), "levels must be an integer >= 0, got -1");
  EXPECT_EQ(toIntAtLeast(QVariant(0), "levels", 0), 0);
  // Beyond int, a bounded integer names its own bounds, not int's.
  EXPECT_EQ(errorOf([] { toIntAtLeast(QVariant(1e10), "option 'frames'", 1); }),
            "option 'frames' must be an integer from 1 to 2147483647, got the number 1e+10");
  EXPECT_EQ(errorOf([] { toIntAtLeast(QVariant(-1e10), "option 'frames'", 1); }),
            "option 'frames' must be an integer >= 1, got -10000000000");
  EXPECT_EQ(errorOf([] { toIntAtLeast(QVariant(-1e300), "option 'frames'", 1); }),
            "option 'frames' must be an integer >= 1, got -1e+300");
  EXPECT_EQ(errorOf([] { toIntBetween(QVariant(1e10), "mode", 0, 1000); }),
            "mode must be an integer from 0 to 1000, got the number 1e+10");
  EXPECT_EQ(errorOf([] { toIntBetween(QVariant(-1), "mode", 0, 1000); }), "mode must be an integer from 0 to 1000, got the number -1");
  EXPECT_EQ(errorOf([] { toIntBetween(QVariant(0.5), "mode", 0, 1000); }), "mode must be an integer, got the number 0.5");
  EXPECT_EQ(toIntBetween(QVariant(1000), "mode", 0, 1000), 1000);
}

TEST(ScriptValues, NumbersMustBeFinite) {
  EXPECT_DOUBLE_EQ(toNumber(QVariant(0.25), "x"), 0.25);
  EXPECT_DOUBLE_EQ(toNumber(QVariant(3), "x"), 3.0);
  EXPECT_NE(errorOf([] { toNumber(QVariant(std::numeric_limits<double>::quiet_NaN()), "delta"); }), "");
  EXPECT_NE(errorOf([] { toNumber(QVariant(std::numeric_limits<double>::infinity()), "delta"); }), "");
  EXPECT_EQ(errorOf([] { toNumber(QVariant(QStringLiteral("8")), "delta"); }),
            "delta must be a finite number, got the string \"8\"");
}

TEST(ScriptValues, BoolsStringsAndChoicesAreStrict) {
  EXPECT_TRUE(toBool(QVariant(true), "b"));
  EXPECT_EQ(errorOf([] { toBool(QVariant(1), "balance"); }), "balance must be true or false, got the number 1");
  EXPECT_EQ(toString(QVariant(QStringLiteral("a.obj")), "path"), QStringLiteral("a.obj"));
  EXPECT_EQ(errorOf([] { toString(QVariant(QString()), "path"); }),
            "path must be a non-empty string, got the string \"\"");
  EXPECT_EQ(errorOf([] { toString(QVariant(3), "path"); }), "path must be a string, got the number 3");
  const QStringList choices{QStringLiteral("level"), QStringLiteral("mode")};
  EXPECT_EQ(toChoice(QVariant(QStringLiteral("mode")), "colorBy", choices), QStringLiteral("mode"));
  EXPECT_EQ(errorOf([&] { toChoice(QVariant(QStringLiteral("Mode")), "colorBy", choices); }),
            "colorBy must be one of \"level\", \"mode\", got the string \"Mode\"");
}

TEST(ScriptValues, ListsAndVectors) {
  const QVariantList ids{1, 2.0, 3};
  EXPECT_EQ(toIntList(QVariant(ids), "vertexIds"), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(errorOf([] { toIntList(QVariant(QVariantList{1, QStringLiteral("x")}), "vertexIds"); }),
            "vertexIds[1] must be an integer, got the string \"x\"");
  EXPECT_EQ(errorOf([] { toList(QVariant(QStringLiteral("abc")), "vertexIds"); }),
            "vertexIds must be an array, got the string \"abc\"");
  const auto center = toVec3(QVariant(QVariantList{1, 2.5, -3}), "center");
  EXPECT_EQ(center, (std::array<double, 3>{1, 2.5, -3}));
  EXPECT_EQ(errorOf([] { toVec3(QVariant(QVariantList{1, 2}), "center"); }),
            "center must be an array of 3 numbers [x, y, z], got an array of 2 elements");
  EXPECT_EQ(errorOf([] { toVec3(QVariant(QVariantList{1, 2, QStringLiteral("z")}), "center"); }),
            "center[2] must be a finite number, got the string \"z\"");
}

TEST(ScriptValues, OptionsRejectUnknownKeysNamingTheAcceptedOnes) {
  const QStringList accepted{QStringLiteral("delta"), QStringLiteral("maxLevel"), QStringLiteral("balance")};
  const QVariantMap given{{QStringLiteral("delta"), 6}, {QStringLiteral("balance"), false}};
  const Options options(QVariant(given), "refineAdaptive options", accepted);
  EXPECT_DOUBLE_EQ(options.number("delta", 8), 6);
  EXPECT_EQ(options.integerAtLeast("maxLevel", 3, 1), 3) << "absent key: the default";
  EXPECT_FALSE(options.boolean("balance", true));
  EXPECT_EQ(errorOf([&] { options.required("maxLevel"); }), "missing option 'maxLevel' (accepted: delta, maxLevel, balance)");

  EXPECT_EQ(errorOf([&] { Options(QVariant(QVariantMap{{QStringLiteral("detla"), 6}}), "refineAdaptive options", accepted); }),
            "unknown option 'detla' in refineAdaptive options (accepted: delta, maxLevel, balance)");
  EXPECT_EQ(errorOf([&] { Options(QVariant(5), "refineAdaptive options", accepted); }),
            "refineAdaptive options must be an object, got the number 5");
  EXPECT_EQ(errorOf([&] {
              Options(QVariant(QVariantMap{{QStringLiteral("delta"), QStringLiteral("x")}}), "o", accepted).number("delta", 8);
            }),
            "option 'delta' must be a finite number, got the string \"x\"");
  // undefined and null mean "no options".
  EXPECT_FALSE(Options(QVariant(), "o", accepted).has("delta"));
  EXPECT_FALSE(Options(QVariant::fromValue(nullptr), "o", accepted).has("delta"));
}

TEST(ScriptValues, CountsBecomeAScriptArray) {
  const QVariantList list = toVariantList({0, 4, 16});
  ASSERT_EQ(list.size(), 3);
  EXPECT_EQ(list[2].toLongLong(), 16);
}

}  // namespace
}  // namespace mrcloth::script
