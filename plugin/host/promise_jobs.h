#pragma once
// Promises in batch scripts. QJSEngine (Qt 6.4) runs a promise's reactions
// (then / catch callbacks) as events posted to the application, and drops a
// rejection nobody handles without a word. A batch script runs no event
// loop, so its callbacks never ran and an error thrown in one exited 0.
#include <QJSValue>
#include <QList>

#include <functional>

class QJSEngine;

namespace mrcloth {

class PromiseJobs {
 public:
  /// Replaces the engine's global `Promise` with a subclass that records
  /// every rejected promise no handler was attached to (its static methods
  /// and `then`'s results are of the subclass too, so they are recorded).
  /// Call before the script is evaluated.
  explicit PromiseJobs(QJSEngine& engine);

  /// The file name the tracking's frames carry in a stack.
  static constexpr const char* kTrackingFile = "mrcloth-promise-tracking";

  /// Runs the pending reactions, and the ones they queue, until none is
  /// left or `stop()` returns true (checked between reactions: Ctrl-C, or
  /// core.exitApplication). A script that queues reactions forever runs
  /// until it is stopped, as an endless loop would.
  void drain(const std::function<bool()>& stop) const;

  /// The reasons of the promises rejected with no handler attached (still
  /// none after drain), oldest first.
  QList<QJSValue> unhandled() const;

 private:
  QJSValue unhandled_;  ///< a script function returning those reasons as an array
};

}  // namespace mrcloth
