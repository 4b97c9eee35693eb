#include "command_line.h"

namespace mrcloth {
namespace {

[[noreturn]] void fail(const QString& message) { throw UsageError(message.toStdString()); }

void setScript(CommandLine& command, const QString& path) {
  if (!command.scriptPath.isEmpty())
    fail(QStringLiteral("more than one script given ('%1' and '%2')").arg(command.scriptPath, path));
  if (path.isEmpty()) fail(QStringLiteral("empty script path"));
  // A garment or clip given as the script would fail as a JavaScript
  // syntax error on its first line, which says nothing of the mistake.
  const QString suffix = path.section(QLatin1Char('.'), -1).toLower();
  static const QStringList data_suffixes{QStringLiteral("obj"), QStringLiteral("om"),  QStringLiteral("off"),
                                         QStringLiteral("ply"), QStringLiteral("bvh"), QStringLiteral("pc2"),
                                         QStringLiteral("csv"), QStringLiteral("mhw"), QStringLiteral("mhskel"),
                                         QStringLiteral("png"), QStringLiteral("json")};
  if (path.contains(QLatin1Char('.')) && data_suffixes.contains(suffix))
    fail(QStringLiteral("'%1' is a .%2 file, not a script; expected a JavaScript file (.js) to run, or "
                        "'mrcloth pipeline --garment FILE --instance CLIP.bvh ...' for the main job "
                        "(mrcloth pipeline --help)")
             .arg(path, suffix));
  command.scriptPath = path;
}

/// `mrcloth [host options] pipeline [options]`: the host's own -q/--quiet and
/// --plugins may also come among the pipeline's; everything else is the
/// pipeline script's to check.
void parsePipelineArguments(CommandLine& command, const QStringList& arguments) {
  command.pipeline = true;
  for (qsizetype i = 0; i < arguments.size(); ++i) {
    const QString& argument = arguments[i];
    if (argument == QLatin1String("-q") || argument == QLatin1String("--quiet")) {
      command.quiet = true;
    } else if (argument == QLatin1String("--plugins")) {
      if (i + 1 >= arguments.size() || arguments[i + 1].isEmpty()) fail(QStringLiteral("option '--plugins' needs a value"));
      command.pluginFolder = arguments[++i];
    } else {
      command.scriptArguments << argument;
    }
  }
}

}  // namespace

CommandLine parseCommandLine(const QStringList& arguments) {
  CommandLine command;
  for (qsizetype i = 0; i < arguments.size(); ++i) {
    const QString& argument = arguments[i];
    // "--name=value" and "--name value" are both accepted for options with a value.
    const qsizetype equals = argument.startsWith(QLatin1String("--")) ? argument.indexOf(QLatin1Char('=')) : -1;
    const QString option = equals < 0 ? argument : argument.left(equals);
    auto value = [&]() -> QString {
      if (equals >= 0) return argument.mid(equals + 1);
      if (i + 1 >= arguments.size()) fail(QStringLiteral("option '%1' needs a value").arg(option));
      return arguments[++i];
    };
    auto noValue = [&] {
      if (equals >= 0) fail(QStringLiteral("option '%1' takes no value").arg(option));
    };

    if (argument == QLatin1String("--")) {
      command.scriptArguments = arguments.mid(i + 1);
      break;
    } else if (option == QLatin1String("-b") || option == QLatin1String("--batch")) {
      setScript(command, value());
    } else if (option == QLatin1String("--plugins")) {
      command.pluginFolder = value();
      if (command.pluginFolder.isEmpty()) fail(QStringLiteral("empty plugin folder"));
    } else if (option == QLatin1String("-q") || option == QLatin1String("--quiet")) {
      noValue();
      command.quiet = true;
    } else if (option == QLatin1String("-h") || option == QLatin1String("--help")) {
      noValue();
      command.help = true;
    } else if (option == QLatin1String("--api") || option == QLatin1String("--help-api")) {
      noValue();
      command.api = true;
    } else if (option == QLatin1String("--version")) {
      noValue();
      command.version = true;
    } else if (argument.startsWith(QLatin1Char('-')) && argument.size() > 1) {
      fail(QStringLiteral("unknown option '%1'").arg(option));
    } else if (argument == QLatin1String("pipeline") && command.scriptPath.isEmpty()) {
      parsePipelineArguments(command, arguments.mid(i + 1));
      break;
    } else {
      setScript(command, argument);
    }
  }
  return command;
}

QString usageText() {
  return QStringLiteral(
      "Usage: mrcloth [options] -b <script.js> [-- <script arguments>...]\n"
      "       mrcloth pipeline [-q] [pipeline options]   (mrcloth pipeline --help lists them)\n"
      "       mrcloth --api\n"
      "\n"
      "Runs mrcloth scripts headless: garments as multi-resolution quad meshes whose\n"
      "refinement is driven by deformation modes. The script sees the object `core`\n"
      "and one object per plugin (\"Multires Cloth\" as `multirescloth`); see --api.\n"
      "`mrcloth pipeline` runs the whole method (scripts/pipeline.js of the resources): from a\n"
      "coarse garment and motions to multi-resolution meshes, caches, previews and a report.\n"
      "\n"
      "Options:\n"
      "  -b, --batch <script.js>  run the script and exit: 0 when it runs to the end,\n"
      "                           1 on an uncaught error (printed as file:line: message),\n"
      "                           or the code given to core.exitApplication(code).\n"
      "                           A lone positional argument is taken as the script too.\n"
      "  --api, --help-api        print the scripting API of core and every plugin\n"
      "  --plugins <dir>          load plugins from <dir> (default: the plugin folder\n"
      "                           of the build/installation, found from the executable)\n"
      "  -q, --quiet              hide [info] and [job] lines (warnings and errors stay)\n"
      "  -h, --help               print this help\n"
      "  --version                print the version\n"
      "  --                       pass the remaining arguments to the script\n"
      "                           (core.scriptArguments())\n"
      "\n"
      "Output: print(), console.log() and core.print() go to stdout; [info], [job],\n"
      "[warn] and [error] lines go to stderr.\n"
      "\n"
      "Environment:\n"
      "  MRCLOTH_RESOURCES        overrides core.resourcePath(), the resources folder (default:\n"
      "                           share/mrcloth beside an installed host, else the checkout's\n"
      "                           resources/ the host was built from)\n"
      "\n"
      "Exit codes: 0 success, 1 script error (or a script that cannot be read), 2 bad command line,\n"
      "other: exitApplication.\n");
}

}  // namespace mrcloth
