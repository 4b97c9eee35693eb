#include "promise_jobs.h"

#include <QCoreApplication>
#include <QEvent>
#include <QJSEngine>
#include <QObject>

namespace mrcloth {
namespace {

// A rejection is handled once `then` (which `catch` calls) is called on its
// promise: the derived promise carries it on. A promise rejected before its
// constructor returns (a synchronous reject, a throwing executor) is
// recorded right after. One resolved with another promise (a callback
// returning Promise.reject(...)) takes that one's rejection without a call
// to its reject function: it is watched, and recorded if it rejects.
const char kTracker[] = R"JS(
(function (global) {
  "use strict";
  const Native = global.Promise;
  const unhandled = [];  // {promise, reason}
  // A hidden own property, not a WeakSet: Qt 6.4's WeakSet crashes.
  const handled = Symbol("handled");
  const note = (promise, reason) => { if (!promise[handled]) unhandled.push({promise: promise, reason: reason}); };
  class Promise extends Native {
    constructor(executor) {
      let self = null, early = null, settled = false;
      super((resolve, reject) => {
        const rejected = (reason) => {
          if (self) note(self, reason);
          else early = {reason: reason};
          reject(reason);
        };
        // A value's resolution, as the language's resolve function does it,
        // but a thenable's `then` is called here: Qt 6.4 crashed (SIGSEGV)
        // when one threw, and missed its rejection as unhandled.
        function adopt(value) {
          if (value instanceof Native) {
            Native.prototype.then.call(value, undefined, (reason) => note(self, reason));
            resolve(value);
            return;
          }
          let then;
          try {
            then = value !== null && (typeof value === "object" || typeof value === "function") ? value.then : undefined;
          } catch (error) {
            rejected(error);
            return;
          }
          if (typeof then !== "function") {
            resolve(value);
            return;
          }
          // In a job of its own, as the language calls it.
          Native.prototype.then.call(Native.resolve(), () => {
            let called = false;
            const once = (settle) => (outcome) => {
              if (!called) {
                called = true;
                settle(outcome);
              }
            };
            try {
              then.call(value, once(adopt), once(rejected));
            } catch (error) {
              once(rejected)(error);
            }
          });
        }
        const fulfil = (value) => {
          if (settled) return;
          settled = true;
          adopt(value);
        };
        // The first of the two calls wins, as the language's functions do
        // (a reject after resolving with a thenable must not reject).
        const fail = (reason) => {
          if (settled) return;
          settled = true;
          rejected(reason);
        };
        try {
          executor(fulfil, fail);
        } catch (error) {
          fail(error);
        }
      });
      self = this;
      if (early) note(this, early.reason);
    }
    then(onFulfilled, onRejected) {
      if (!this[handled]) {
        Object.defineProperty(this, handled, {value: true});
        for (let k = unhandled.length; k-- > 0;)
          if (unhandled[k].promise === this) unhandled.splice(k, 1);
      }
      return super.then(onFulfilled, onRejected);
    }
  }
  global.Promise = Promise;
  return () => unhandled.map((entry) => entry.reason);
})
)JS";

/// Counts the events delivered anywhere in the application: a pass of
/// sendPostedEvents that delivers none found the queue empty.
class EventCounter : public QObject {
 public:
  long long count = 0;
  bool eventFilter(QObject*, QEvent*) override {
    ++count;
    return false;
  }
};

}  // namespace

PromiseJobs::PromiseJobs(QJSEngine& engine) {
  const QJSValue install = engine.evaluate(QString::fromUtf8(kTracker), QString::fromLatin1(kTrackingFile));
  unhandled_ = install.call({engine.globalObject()});
}

void PromiseJobs::drain(const std::function<bool()>& stop) const {
  QCoreApplication* app = QCoreApplication::instance();
  if (!app) return;
  EventCounter counter;
  app->installEventFilter(&counter);
  // sendPostedEvents delivers the events queued when it starts; reactions
  // queued by those wait for the next pass.
  for (long long before = -1; counter.count != before && !stop();) {
    before = counter.count;
    QCoreApplication::sendPostedEvents();
  }
  app->removeEventFilter(&counter);
}

QList<QJSValue> PromiseJobs::unhandled() const {
  QList<QJSValue> reasons;
  if (!unhandled_.isCallable()) return reasons;
  const QJSValue list = unhandled_.call();
  const int length = list.property(QStringLiteral("length")).toInt();
  for (int k = 0; k < length; ++k) reasons << list.property(static_cast<quint32>(k));
  return reasons;
}

}  // namespace mrcloth
