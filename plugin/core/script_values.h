#pragma once
// Turning what a script passed to a slot into checked C++ values. Slots take
// QVariant parameters instead of int/double/QString so that a wrong type is
// an error naming the parameter, not a silent conversion ("abc" -> 0,
// 2.7 -> 2, undefined -> "undefined"). Every function throws ArgumentError
// with a message of the form "<what> must be ..., got <value>".
#include <QString>
#include <QStringList>
#include <QVariant>

#include <array>
#include <vector>

namespace mrcloth::script {

/// How a value reads in an error message: `the number 2.5`, `the string "x"`,
/// `an array`, `an object`, `undefined`, `null`, `true`.
QString describeValue(const QVariant& value);

/// True for any numeric QVariant a script can pass (int, double, ...).
bool isNumber(const QVariant& value);

/// An integral number in int range.
int toInt(const QVariant& value, const QString& what);
/// toInt, and at least `minimum`.
int toIntAtLeast(const QVariant& value, const QString& what, int minimum);
/// toInt, from `minimum` to `maximum`: a number outside (however large) is
/// refused with that range.
int toIntBetween(const QVariant& value, const QString& what, int minimum, int maximum);
/// A finite number.
double toNumber(const QVariant& value, const QString& what);
/// true or false (numbers and strings are not accepted).
bool toBool(const QVariant& value, const QString& what);
/// A non-empty string.
QString toString(const QVariant& value, const QString& what);
/// A string, empty too (a file's contents).
QString toText(const QVariant& value, const QString& what);
/// One of `choices` (case-sensitive).
QString toChoice(const QVariant& value, const QString& what, const QStringList& choices);
/// An array (a JS array, or an empty object-like value).
QVariantList toList(const QVariant& value, const QString& what);
/// An array of integers; elements are named what[i] in errors.
std::vector<int> toIntList(const QVariant& value, const QString& what);
/// An array of exactly three finite numbers.
std::array<double, 3> toVec3(const QVariant& value, const QString& what);

/// Counts per level (or per mode) as a script array; element i stays element i.
QVariantList toVariantList(const std::vector<std::size_t>& counts);

/// A JS options object: undefined or null mean "all defaults"; any key not in
/// `accepted` is an error naming it and listing the accepted ones.
class Options {
 public:
  Options(const QVariant& value, const QString& what, const QStringList& accepted);

  bool has(const QString& key) const;
  /// The value of a key that must be present ("missing option 'key'" otherwise).
  QVariant required(const QString& key) const;

  double number(const QString& key, double fallback) const;
  int integerAtLeast(const QString& key, int fallback, int minimum) const;
  int integerBetween(const QString& key, int fallback, int minimum, int maximum) const;
  bool boolean(const QString& key, bool fallback) const;
  QString string(const QString& key, const QString& fallback) const;
  QString choice(const QString& key, const QString& fallback, const QStringList& choices) const;
  std::array<double, 3> vec3(const QString& key) const;  ///< required

 private:
  QString label(const QString& key) const;  ///< "option 'key'", as errors name it
  QVariantMap values_;
  QStringList accepted_;
};

}  // namespace mrcloth::script
