#include "script_exposure.h"

#include <QJSEngine>
#include <QJSValue>
#include <QMetaMethod>
#include <QMetaObject>
#include <QObject>

#include <algorithm>

namespace mrcloth {

namespace {

/// Per slot or invokable name of the object's own class (not QObject's),
/// the most parameters any of its overloads takes (a slot with defaulted
/// parameters is several overloads to moc).
QJSValue parameterLimits(QJSEngine& engine, const QObject& object) {
  QJSValue limits = engine.newObject();
  const QMetaObject& meta = *object.metaObject();
  for (int k = QObject::staticMetaObject.methodCount(); k < meta.methodCount(); ++k) {
    const QMetaMethod method = meta.method(k);
    if (method.access() != QMetaMethod::Public || method.methodType() == QMetaMethod::Signal) continue;
    const QString name = QString::fromLatin1(method.name());
    const QJSValue known = limits.property(name);
    const int most = known.isNumber() ? std::max(known.toInt(), method.parameterCount()) : method.parameterCount();
    limits.setProperty(name, most);
  }
  return limits;
}

/// The names of the object's signals, QObject's included (the host's to
/// listen to, not a script's to call).
QJSValue signalNames(QJSEngine& engine, const QObject& object) {
  QJSValue names = engine.newObject();
  const QMetaObject& meta = *object.metaObject();
  for (int k = 0; k < meta.methodCount(); ++k)
    if (meta.method(k).methodType() == QMetaMethod::Signal)
      names.setProperty(QString::fromLatin1(meta.method(k).name()), true);
  return names;
}

}  // namespace

void exposeToScripts(QJSEngine& engine, const QString& name, QObject* object) {
  // The engine must not delete it: core lives on main's stack and plugins
  // belong to their loaders.
  QJSEngine::setObjectOwnership(object, QJSEngine::CppOwnership);
  // A proxy: its slots checked for extra arguments; its signals (log,
  // startJob, ...: the host's to listen to) hidden, since a script calling
  // them wrote fake log lines or left a job never finished; properties read through.
  static const char* const kGuard = R"JS(
(function (target, limits, signals, objectName, guardFile) {
  const own = (table, key) => typeof key === "string" && Object.prototype.hasOwnProperty.call(table, key);
  // An error made in this file (by the check, or by the slot it calls) is
  // the caller's: its file and line become the caller's. (Its stack keeps
  // this frame: V4's is fixed; the host's reports leave it out.)
  function atCaller(error) {
    if (error instanceof Error && typeof error.stack === "string") {
      const frames = error.stack.split("\n").filter((frame) => frame.indexOf(guardFile) < 0);
      const caller = /^[^@]*@(.*):(\d+)$/.exec(frames[0] || "");
      if (caller) {
        error.fileName = caller[1];
        error.lineNumber = Number(caller[2]);
      }
    }
    return error;
  }
  return new Proxy(target, {
    // Hidden from `in`, for...in and Object.keys too, not only from calls.
    has(object, key) {
      return !own(signals, key) && key in object;
    },
    ownKeys(object) {
      return Reflect.ownKeys(object).filter((key) => !own(signals, key));
    },
    getOwnPropertyDescriptor(object, key) {
      return own(signals, key) ? undefined : Reflect.getOwnPropertyDescriptor(object, key);
    },
    get(object, key) {
      const value = object[key];
      if (typeof value !== "function") return value;
      if (own(signals, key)) return undefined;
      if (!own(limits, key)) return value;
      const most = limits[key];
      return function (...args) {
        if (args.length > most) {
          const error = new Error(objectName + "." + key + ": takes at most " + most + " argument" +
                                  (most === 1 ? "" : "s") + ", got " + args.length + " (see mrcloth --api)");
          error.name = "ArgumentError";
          throw atCaller(error);
        }
        try {
          return value.apply(object, args);
        } catch (error) {
          throw atCaller(error);
        }
      };
    }
  });
}))JS";
  const QJSValue guard = engine.evaluate(QString::fromLatin1(kGuard), QString::fromLatin1(kSlotGuardFile));
  const QJSValue proxy = guard.call({engine.newQObject(object), parameterLimits(engine, *object),
                                     signalNames(engine, *object), name, QString::fromLatin1(kSlotGuardFile)});
  engine.globalObject().setProperty(name, proxy.isError() ? engine.newQObject(object) : proxy);
}

QString thrownValueText(const QJSValue& value) {
  if (value.isObject() && !value.isCallable()) {
    const QJSValue message = value.property(QStringLiteral("message"));
    const QJSValue name = value.property(QStringLiteral("name"));
    if (message.isString())
      return (name.isString() && !name.toString().isEmpty() ? name.toString() + QStringLiteral(": ") : QString()) +
             message.toString();
    // Object.create(null) has no toString: its text was the conversion's own TypeError.
    if (value.prototype().isNull()) return QStringLiteral("an object without a prototype or message");
  }
  return value.toString();
}

QStringList withoutSlotGuardFrames(QStringList stack) {
  stack.removeIf([](const QString& frame) { return frame.contains(QLatin1String(kSlotGuardFile)); });
  return stack;
}

}  // namespace mrcloth
