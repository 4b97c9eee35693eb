#pragma once
// The one place where C++ exceptions become JavaScript exceptions.
// OpenFlipper's plugins only log a failure, so a script runs on with a bad
// result; here every slot body runs inside runScriptSlot, and an exception
// becomes an Error the script can catch, or that stops it (the host then
// prints file:line and exits non-zero).
//
// Header-only because it needs Qt6::Qml, which every target including it
// (the host and the plugins) links anyway; mrcloth_plugin_core stays Qt Core only.
#include "mesh_ops/errors.h"

#include <QJSEngine>
#include <QJSValue>
#include <QObject>
#include <QString>

#include <exception>
#include <type_traits>

namespace mrcloth {

/// The JavaScript `name` of the error an exception becomes: "InputError",
/// "ArgumentError", "OutputError" for mrcloth's typed errors, else "Error".
inline QString scriptErrorName(const std::exception& error) {
  if (dynamic_cast<const InputError*>(&error)) return QStringLiteral("InputError");
  if (dynamic_cast<const ArgumentError*>(&error)) return QStringLiteral("ArgumentError");
  if (dynamic_cast<const OutputError*>(&error)) return QStringLiteral("OutputError");
  return QStringLiteral("Error");
}

/// Throws a JavaScript Error named `name` with message `message` in the engine
/// that is running `caller`'s slot. Returns false when `caller` is not exposed
/// to any engine (a C++ caller), so that the caller can rethrow instead.
inline bool throwScriptError(const QObject* caller, const QString& name, const QString& message) {
  QJSEngine* engine = qjsEngine(caller);
  if (!engine) return false;
  QJSValue error = engine->newErrorObject(QJSValue::GenericError, message);
  error.setProperty(QStringLiteral("name"), name);
  engine->throwError(error);
  return true;
}

/// Runs a slot body. An exception escaping it becomes a JavaScript error whose
/// message starts with `slotLabel` ("multirescloth.refineUniform: no object
/// with id 7"); the slot then returns a default value that the engine
/// discards. Called from C++ (no engine), the exception propagates unchanged.
template <class Body>
auto runScriptSlot(const QObject* caller, const QString& slotLabel, Body&& body) -> decltype(body()) {
  using Result = decltype(body());
  try {
    return body();
  } catch (const std::exception& error) {
    const QString message = slotLabel + QStringLiteral(": ") + QString::fromUtf8(error.what());
    if (!throwScriptError(caller, scriptErrorName(error), message)) throw;
  } catch (...) {
    if (!throwScriptError(caller, QStringLiteral("Error"), slotLabel + QStringLiteral(": unknown error"))) throw;
  }
  if constexpr (!std::is_void_v<Result>) return Result{};
}

}  // namespace mrcloth
