#pragma once
// A line of the log worded away from the plugin (run_checks.h, run_report.h,
// mode_report.h): the plugin emits it, warnings through its warn() where a
// run keeps them for its report.
#include "plugin/interfaces/logging_interface.h"

#include <QString>

namespace mrcloth {

/// A line for the log, kept until the slot emits it.
struct LogLine {
  Logtype type;
  QString text;
};

}  // namespace mrcloth
