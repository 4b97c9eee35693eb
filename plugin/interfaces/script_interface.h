#pragma once
// OpenFlipper vocabulary: a plugin's public slots are its scripting API. The
// host exposes the plugin object to the script engine and prints the API
// from the slot descriptions (OpenFlipper's setSlotDescription, as a list the
// plugin returns). Slots report failures by throwing a JavaScript exception
// (see plugin/core/script_errors.h), never only by logging.
#include <QList>
#include <QString>
#include <QStringList>
#include <QVariantMap>
#include <QtPlugin>

namespace mrcloth {

/// How a script author calls one slot.
struct SlotDescription {
  QString signature;                  ///< e.g. "refineUniform(int id, int levels) -> int"
  QString description;                ///< one line: what it does and returns
  QStringList parameterNames;         ///< in signature order
  QStringList parameterDescriptions;  ///< parallel to parameterNames: meaning, units, defaults

  /// The slot's name: the signature up to '('.
  QString slotName() const;
};

class ScriptInterface {
 public:
  virtual ~ScriptInterface() = default;

  /// One description per public slot.
  virtual QList<SlotDescription> slotDescriptions() const = 0;
};

/// The descriptions with each `@name@` in their texts replaced by the bounds
/// of `limits` (name -> [least, most], a plugin's limits() table) as
/// "least..most", so the help prints the bounds the calls check; an unknown
/// name is left visible as "@unknown limit name@".
QList<SlotDescription> withLimits(QList<SlotDescription> descriptions, const QVariantMap& limits);

/// Name under which the script engine sees an object: the display name
/// lower-cased without spaces ("Multires Cloth" -> "multirescloth").
QString scriptObjectName(const QString& displayName);

}  // namespace mrcloth

Q_DECLARE_INTERFACE(mrcloth::ScriptInterface, "mrcloth.ScriptInterface/1.0")
