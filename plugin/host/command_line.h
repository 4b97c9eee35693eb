#pragma once
// The mrcloth command line. Parsed by hand (not QCommandLineParser) because
// everything after `--` belongs to the script, and errors must name the
// offending argument before the usage text.
#include <QString>
#include <QStringList>

#include <stdexcept>

namespace mrcloth {

/// A command line that cannot be run; the host prints it with the usage and exits 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CommandLine {
  QString scriptPath;           ///< -b/--batch <file>, or the single positional argument
  QStringList scriptArguments;  ///< everything after `--`
  QString pluginFolder;         ///< --plugins <dir>; empty: next to the executable
  bool quiet = false;           ///< -q/--quiet
  bool help = false;            ///< -h/--help
  bool api = false;             ///< --api/--help-api
  bool version = false;         ///< --version
  bool pipeline = false;        ///< `mrcloth pipeline ...`: run resources/scripts/pipeline.js with scriptArguments
};

/// Parses the arguments after the program name. Throws UsageError for an
/// unknown option, an option missing its value, or more than one script.
CommandLine parseCommandLine(const QStringList& arguments);

/// The text of `mrcloth --help`.
QString usageText();

}  // namespace mrcloth
