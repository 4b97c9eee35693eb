#include "script_values.h"

#include "mesh_ops/errors.h"

#include <QLocale>

#include <cmath>
#include <limits>

namespace mrcloth::script {
namespace {

[[noreturn]] void fail(const QString& message) { throw ArgumentError(message.toStdString()); }

[[noreturn]] void failType(const QString& what, const QString& expected, const QVariant& value) {
  fail(QStringLiteral("%1 must be %2, got %3").arg(what, expected, describeValue(value)));
}


// JS arrays and objects reach a QVariant parameter wrapped as QJSValue. QtQml
// registers converters from QJSValue to QVariantMap/QVariantList (an array
// converts to an empty map and an object to an empty list), so this stays Qt
// Core only. An empty array and an empty object cannot be told apart this way.
bool isScriptValue(const QVariant& value) {
  return qstrcmp(value.metaType().name(), "QJSValue") == 0;
}

enum class Shape { scalar, list, map, empty_container };

Shape shapeOf(const QVariant& value, QVariantList* list = nullptr, QVariantMap* map = nullptr) {
  if (value.typeId() == QMetaType::QVariantList) {
    if (list) *list = value.toList();
    return Shape::list;
  }
  if (value.typeId() == QMetaType::QVariantMap) {
    if (map) *map = value.toMap();
    return Shape::map;
  }
  if (!isScriptValue(value)) return Shape::scalar;
  const QVariantMap as_map = value.toMap();
  if (!as_map.isEmpty()) {
    if (map) *map = as_map;
    return Shape::map;
  }
  const QVariantList as_list = value.toList();
  if (!as_list.isEmpty()) {
    if (list) *list = as_list;
    return Shape::list;
  }
  return Shape::empty_container;
}

}  // namespace

bool isNumber(const QVariant& value) {
  switch (value.typeId()) {
    case QMetaType::Int: case QMetaType::UInt: case QMetaType::LongLong: case QMetaType::ULongLong:
    case QMetaType::Double: case QMetaType::Float: case QMetaType::Short: case QMetaType::UShort:
    case QMetaType::Long: case QMetaType::ULong:
      return true;
    default:
      return false;
  }
}

QString describeValue(const QVariant& value) {
  if (!value.isValid()) return QStringLiteral("undefined");
  if (value.typeId() == QMetaType::Nullptr) return QStringLiteral("null");
  if (value.typeId() == QMetaType::Bool) return value.toBool() ? QStringLiteral("true") : QStringLiteral("false");
  if (isNumber(value)) {
    // Spelled as JavaScript prints them, so the message matches what the script passed.
    const double number = value.toDouble();
    if (std::isnan(number)) return QStringLiteral("the number NaN");
    if (std::isinf(number)) return number > 0 ? QStringLiteral("the number Infinity") : QStringLiteral("the number -Infinity");
    return QStringLiteral("the number %1").arg(QString::number(number, 'g', QLocale::FloatingPointShortest));
  }
  if (value.typeId() == QMetaType::QString) {
    QString text = value.toString();
    if (text.size() > 60) text = text.left(57) + QStringLiteral("...");
    return QStringLiteral("the string \"%1\"").arg(text);
  }
  QVariantList list;
  switch (shapeOf(value, &list)) {
    case Shape::list:
      return list.size() == 1 ? QStringLiteral("an array of 1 element")
                              : QStringLiteral("an array of %1 elements").arg(list.size());
    case Shape::map: return QStringLiteral("an object");
    case Shape::empty_container: return QStringLiteral("an empty array or object");
    case Shape::scalar: break;
  }
  return QStringLiteral("a value of type %1").arg(QString::fromLatin1(value.metaType().name()));
}

namespace {

/// The value as a whole number (a double: it may be beyond int), or the
/// type error every integer option gives.
double wholeNumber(const QVariant& value, const QString& what) {
  if (!isNumber(value)) failType(what, QStringLiteral("an integer"), value);
  const double number = value.toDouble();
  if (!std::isfinite(number) || number != std::floor(number)) failType(what, QStringLiteral("an integer"), value);
  return number;
}

}  // namespace

int toInt(const QVariant& value, const QString& what) {
  // A whole number beyond 32 bits is an integer, just too large to be one here.
  return toIntBetween(value, what, std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
}

int toIntAtLeast(const QVariant& value, const QString& what, int minimum) {
  const double number = wholeNumber(value, what);
  if (number < minimum)
    // Written out while that stays readable (-10000000000), else in
    // exponent form (-1e+300 was 301 digits).
    fail(QStringLiteral("%1 must be an integer >= %2, got %3")
             .arg(what)
             .arg(minimum)
             .arg(std::abs(number) < 1e15 ? QString::number(number, 'f', 0) : QString::number(number)));
  return toIntBetween(value, what, minimum, std::numeric_limits<int>::max());
}

int toIntBetween(const QVariant& value, const QString& what, int minimum, int maximum) {
  const double number = wholeNumber(value, what);
  if (number < minimum || number > maximum)
    fail(QStringLiteral("%1 must be an integer from %2 to %3, got %4")
             .arg(what).arg(minimum).arg(maximum).arg(describeValue(value)));
  return static_cast<int>(number);
}

double toNumber(const QVariant& value, const QString& what) {
  if (!isNumber(value)) failType(what, QStringLiteral("a finite number"), value);
  const double number = value.toDouble();
  if (!std::isfinite(number)) failType(what, QStringLiteral("a finite number"), value);
  return number;
}

bool toBool(const QVariant& value, const QString& what) {
  if (value.typeId() != QMetaType::Bool) failType(what, QStringLiteral("true or false"), value);
  return value.toBool();
}

QString toText(const QVariant& value, const QString& what) {
  if (value.typeId() != QMetaType::QString) failType(what, QStringLiteral("a string"), value);
  return value.toString();
}

QString toString(const QVariant& value, const QString& what) {
  const QString text = toText(value, what);
  if (text.isEmpty()) failType(what, QStringLiteral("a non-empty string"), value);
  return text;
}

QString toChoice(const QVariant& value, const QString& what, const QStringList& choices) {
  const QString expected = QStringLiteral("one of \"%1\"").arg(choices.join(QStringLiteral("\", \"")));
  if (value.typeId() != QMetaType::QString || !choices.contains(value.toString()))
    failType(what, expected, value);
  return value.toString();
}

QVariantList toList(const QVariant& value, const QString& what) {
  QVariantList list;
  switch (shapeOf(value, &list)) {
    case Shape::list: return list;
    case Shape::empty_container: return {};
    default: failType(what, QStringLiteral("an array"), value);
  }
}

std::vector<int> toIntList(const QVariant& value, const QString& what) {
  const QVariantList list = toList(value, what);
  std::vector<int> numbers;
  numbers.reserve(static_cast<std::size_t>(list.size()));
  for (qsizetype i = 0; i < list.size(); ++i)
    numbers.push_back(toInt(list[i], QStringLiteral("%1[%2]").arg(what).arg(i)));
  return numbers;
}

std::array<double, 3> toVec3(const QVariant& value, const QString& what) {
  QVariantList list;
  if (shapeOf(value, &list) != Shape::list || list.size() != 3)
    failType(what, QStringLiteral("an array of 3 numbers [x, y, z]"), value);
  std::array<double, 3> vector{};
  for (int i = 0; i < 3; ++i) vector[i] = toNumber(list[i], QStringLiteral("%1[%2]").arg(what).arg(i));
  return vector;
}

QVariantList toVariantList(const std::vector<std::size_t>& counts) {
  QVariantList list;
  list.reserve(static_cast<qsizetype>(counts.size()));
  for (const std::size_t count : counts) list.append(static_cast<qlonglong>(count));
  return list;
}

Options::Options(const QVariant& value, const QString& what, const QStringList& accepted)
    : accepted_(accepted) {
  if (!value.isValid() || value.typeId() == QMetaType::Nullptr) return;
  switch (shapeOf(value, nullptr, &values_)) {
    case Shape::map: break;
    case Shape::empty_container: return;
    default: failType(what, QStringLiteral("an object"), value);
  }
  for (auto it = values_.cbegin(); it != values_.cend(); ++it) {
    if (!accepted_.contains(it.key()))
      fail(QStringLiteral("unknown option '%1' in %2 (accepted: %3)")
               .arg(it.key(), what, accepted_.join(QStringLiteral(", "))));
  }
}

QString Options::label(const QString& key) const { return QStringLiteral("option '%1'").arg(key); }

bool Options::has(const QString& key) const {
  Q_ASSERT(accepted_.contains(key));
  // An explicit `undefined` counts as absent, as it would in JavaScript.
  return values_.contains(key) && values_.value(key).isValid();
}

QVariant Options::required(const QString& key) const {
  if (!has(key)) fail(QStringLiteral("missing %1 (accepted: %2)").arg(label(key), accepted_.join(QStringLiteral(", "))));
  return values_.value(key);
}

double Options::number(const QString& key, double fallback) const {
  return has(key) ? toNumber(values_.value(key), label(key)) : fallback;
}

int Options::integerAtLeast(const QString& key, int fallback, int minimum) const {
  return has(key) ? toIntAtLeast(values_.value(key), label(key), minimum) : fallback;
}

int Options::integerBetween(const QString& key, int fallback, int minimum, int maximum) const {
  return has(key) ? toIntBetween(values_.value(key), label(key), minimum, maximum) : fallback;
}

bool Options::boolean(const QString& key, bool fallback) const {
  return has(key) ? toBool(values_.value(key), label(key)) : fallback;
}

QString Options::string(const QString& key, const QString& fallback) const {
  return has(key) ? toString(values_.value(key), label(key)) : fallback;
}

QString Options::choice(const QString& key, const QString& fallback, const QStringList& choices) const {
  return has(key) ? toChoice(values_.value(key), label(key), choices) : fallback;
}

std::array<double, 3> Options::vec3(const QString& key) const { return toVec3(required(key), label(key)); }

}  // namespace mrcloth::script
