#pragma once
// Strict reading of one options object (the top level of simulate's options
// or a nested one such as "material", "colliders[1]", "motion", "body"),
// shared by the plugins (simulate's options, the preview options). Errors name
// the full key: "option 'colliders[1].radius' must be a number > 0, got the
// number -1".
#include "mesh_ops/errors.h"
#include "plugin/core/script_values.h"

#include <Eigen/Core>

#include <QDir>
#include <QFileInfo>
#include <QString>
#include <QStringList>
#include <QVariant>

#include <array>

namespace mrcloth::options {

[[noreturn]] inline void fail(const QString& message) { throw ArgumentError(message.toStdString()); }

/// The output frame rates every slot takes (simulate, recordInstance,
/// renderSequence): from a frame every 1000 s to 100,000 a second. Beyond,
/// a simulated step is so long or so short that the run only turns
/// non-finite (1e-300 and 1e300 ran, to NaN), and a clip's frames over a
/// run no longer fit an int.
constexpr double kLeastFps = 1e-3;
constexpr double kMostFps = 1e5;

inline QString optionLabel(const QString& key) { return QStringLiteral("option '%1'").arg(key); }

using script::isNumber;

inline bool isObjectLike(const QVariant& value) {
  return value.typeId() == QMetaType::QVariantMap || value.typeId() == QMetaType::QVariantList ||
         qstrcmp(value.metaType().name(), "QJSValue") == 0;
}

class Fields {
 public:
  /// `path` is the key of a nested object ("material"), empty for the top
  /// level, which `topLevel` names in errors ("simulate options").
  Fields(const QVariant& value, const QString& path, const QStringList& accepted,
         const QString& topLevel = QStringLiteral("simulate options"))
      : path_(path),
        accepted_(accepted),
        options_(value, path.isEmpty() ? topLevel : optionLabel(path), accepted) {}

  QString key(const QString& name) const { return path_.isEmpty() ? name : path_ + '.' + name; }
  QString label(const QString& name) const { return optionLabel(key(name)); }
  bool has(const QString& name) const { return options_.has(name); }

  QVariant required(const QString& name) const {
    if (!has(name))
      fail(QStringLiteral("missing %1 (accepted: %2)").arg(label(name), accepted_.join(QStringLiteral(", "))));
    return options_.required(name);
  }
  double number(const QString& name, double fallback) const {
    return has(name) ? script::toNumber(required(name), label(name)) : fallback;
  }
  /// A number >= minimum (or > minimum when `strict`).
  double numberFrom(const QString& name, double fallback, double minimum, bool strict) const {
    if (!has(name)) return fallback;
    const double value = script::toNumber(required(name), label(name));
    if (strict ? !(value > minimum) : !(value >= minimum))
      fail(QStringLiteral("%1 must be a number %2 %3, got %4")
               .arg(label(name), strict ? QStringLiteral(">") : QStringLiteral(">="))
               .arg(minimum)
               .arg(script::describeValue(required(name))));
    return value;
  }
  /// A number in [minimum, maximum]; `unit` ("frames per second") follows
  /// the range in the message.
  double numberBetween(const QString& name, double fallback, double minimum, double maximum,
                       const QString& unit) const {
    if (!has(name)) return fallback;
    const double value = script::toNumber(required(name), label(name));
    if (!(value >= minimum && value <= maximum))
      fail(QStringLiteral("%1 must be from %2 to %3 %4, got %5")
               .arg(label(name))
               .arg(minimum)
               .arg(maximum)
               .arg(unit, script::describeValue(required(name))));
    return value;
  }
  int integerAtLeast(const QString& name, int fallback, int minimum) const {
    return has(name) ? script::toIntAtLeast(required(name), label(name), minimum) : fallback;
  }
  /// An integer in [minimum, maximum]: the maximum keeps one call's work
  /// within what a progress report and Ctrl-C can interrupt.
  int integerBetween(const QString& name, int fallback, int minimum, int maximum) const {
    return has(name) ? script::toIntBetween(required(name), label(name), minimum, maximum) : fallback;
  }
  bool boolean(const QString& name, bool fallback) const {
    return has(name) ? script::toBool(required(name), label(name)) : fallback;
  }
  QString string(const QString& name) const {
    return has(name) ? script::toString(required(name), label(name)) : QString();
  }
  QString choice(const QString& name, const QString& fallback, const QStringList& choices) const {
    return has(name) ? script::toChoice(required(name), label(name), choices) : fallback;
  }
  Eigen::Vector3d vec3(const QString& name) const {
    const std::array<double, 3> v = script::toVec3(required(name), label(name));
    return {v[0], v[1], v[2]};
  }
  Eigen::Vector3d vec3(const QString& name, const Eigen::Vector3d& fallback) const {
    return has(name) ? vec3(name) : fallback;
  }

 private:
  QString path_;
  QStringList accepted_;
  script::Options options_;
};

/// An input file that must exist: InputError "option 'key': <path>: no such file".
inline QString existingInputFile(const QString& path, const QString& label) {
  const QFileInfo info(path);
  if (!info.exists())
    throw InputError(QStringLiteral("%1: %2: no such file").arg(label, QDir::toNativeSeparators(path)).toStdString());
  if (!info.isFile())
    throw InputError(QStringLiteral("%1: %2: not a file").arg(label, QDir::toNativeSeparators(path)).toStdString());
  return path;
}

}  // namespace mrcloth::options
