#include "plugin/host/command_line.h"

#include <gtest/gtest.h>

namespace mrcloth {
namespace {

TEST(CommandLine, BatchScriptAndItsArguments) {
  const CommandLine command =
      parseCommandLine({"-q", "-b", "job.js", "--", "out", "--not-ours", "-b", "two words"});
  EXPECT_EQ(command.scriptPath, QStringLiteral("job.js"));
  EXPECT_TRUE(command.quiet);
  EXPECT_EQ(command.scriptArguments, (QStringList{"out", "--not-ours", "-b", "two words"}));
}

TEST(CommandLine, LongFormsWithEqualsAndPositionalScript) {
  CommandLine command = parseCommandLine({"--batch=job.js", "--plugins=/p"});
  EXPECT_EQ(command.scriptPath, QStringLiteral("job.js"));
  EXPECT_EQ(command.pluginFolder, QStringLiteral("/p"));
  command = parseCommandLine({"job.js", "--plugins", "/q", "--quiet"});
  EXPECT_EQ(command.scriptPath, QStringLiteral("job.js"));
  EXPECT_EQ(command.pluginFolder, QStringLiteral("/q"));
  EXPECT_TRUE(parseCommandLine({"--help-api"}).api);
  EXPECT_TRUE(parseCommandLine({"--api"}).api);
  EXPECT_TRUE(parseCommandLine({"-h"}).help);
  EXPECT_TRUE(parseCommandLine({"--version"}).version);
  EXPECT_TRUE(parseCommandLine({}).scriptPath.isEmpty());
}

TEST(CommandLine, ErrorsNameTheArgument) {
  auto messageOf = [](const QStringList& arguments) -> std::string {
    try {
      parseCommandLine(arguments);
    } catch (const UsageError& error) {
      return error.what();
    }
    return "";
  };
  EXPECT_EQ(messageOf({"--frobnicate"}), "unknown option '--frobnicate'");
  EXPECT_EQ(messageOf({"--frobnicate=3"}), "unknown option '--frobnicate'");
  EXPECT_EQ(messageOf({"-x"}), "unknown option '-x'");
  EXPECT_EQ(messageOf({"-b"}), "option '-b' needs a value");
  EXPECT_EQ(messageOf({"--plugins"}), "option '--plugins' needs a value");
  EXPECT_EQ(messageOf({"--quiet=yes"}), "option '--quiet' takes no value");
  EXPECT_EQ(messageOf({"a.js", "b.js"}), "more than one script given ('a.js' and 'b.js')");
  EXPECT_EQ(messageOf({"-b", "a.js", "b.js"}), "more than one script given ('a.js' and 'b.js')");
  // A garment or clip in the script's place is named as such, not run as JavaScript.
  EXPECT_EQ(messageOf({"skirt.OBJ"}).rfind("'skirt.OBJ' is a .obj file, not a script; expected a JavaScript file (.js)", 0), 0u)
      << messageOf({"skirt.OBJ"});
  EXPECT_NE(messageOf({"-b", "walk.bvh"}).find("is a .bvh file, not a script"), std::string::npos);
  EXPECT_EQ(messageOf({"job.mrcloth"}), "") << "any other name may be a script";
  EXPECT_EQ(messageOf({"job"}), "");
}

}  // namespace
}  // namespace mrcloth

namespace mrcloth {
namespace {

TEST(CommandLine, PipelineTakesTheHostsOptionsAndForwardsTheRest) {
  const CommandLine command = parseCommandLine(
      {QStringLiteral("pipeline"), QStringLiteral("--levels"), QStringLiteral("1"), QStringLiteral("-q"),
       QStringLiteral("--plugins"), QStringLiteral("p"), QStringLiteral("--out"), QStringLiteral("o"),
       QStringLiteral("--help")});
  EXPECT_TRUE(command.pipeline);
  EXPECT_TRUE(command.quiet);
  EXPECT_FALSE(command.help);  // the pipeline's own --help
  EXPECT_EQ(command.pluginFolder, QStringLiteral("p"));
  EXPECT_EQ(command.scriptArguments, (QStringList{QStringLiteral("--levels"), QStringLiteral("1"),
                                                  QStringLiteral("--out"), QStringLiteral("o"),
                                                  QStringLiteral("--help")}));
  EXPECT_TRUE(command.scriptPath.isEmpty());
  EXPECT_THROW(parseCommandLine({QStringLiteral("pipeline"), QStringLiteral("--plugins")}), UsageError);
  // Host options may also come first; a script named "pipeline" needs -b.
  const CommandLine after = parseCommandLine({QStringLiteral("-q"), QStringLiteral("pipeline"), QStringLiteral("--levels")});
  EXPECT_TRUE(after.pipeline);
  EXPECT_TRUE(after.quiet);
  EXPECT_EQ(after.scriptArguments, QStringList{QStringLiteral("--levels")});
  EXPECT_FALSE(parseCommandLine({QStringLiteral("-b"), QStringLiteral("pipeline")}).pipeline);
}

}  // namespace
}  // namespace mrcloth
