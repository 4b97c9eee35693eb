#pragma once
// Plugin objects as scripts see them.
#include <QJSValue>
#include <QString>
#include <QStringList>

class QJSEngine;
class QObject;

namespace mrcloth {

/// Makes `object` the script global `name`, its public slots callable. Qt's
/// engine drops arguments beyond a slot's parameters with only a warning
/// ("Too many arguments, ignoring 1"): `core.saveObject(id, "a.obj",
/// {units: "cm"})` then saved in metres and exited 0. Here such a call
/// throws an ArgumentError naming the slot and its parameter count.
/// The object stays C++-owned.
void exposeToScripts(QJSEngine& engine, const QString& name, QObject* object);

/// The file name of the check's own code: stack frames from it are left out
/// of error reports (an error a slot throws is the caller's line).
inline constexpr const char* kSlotGuardFile = "mrcloth-slot-guard";

/// `stack` (QJSEngine's "function:line:column:file" frames) without the
/// check's frames.
QStringList withoutSlotGuardFrames(QStringList stack);

/// A thrown value that is not an Error, as an uncaught-exception report
/// names it: an object's `name: message` when it has a string message
/// (`throw {message: "..."}` printed "[object Object]"), else its text.
QString thrownValueText(const QJSValue& value);

}  // namespace mrcloth
