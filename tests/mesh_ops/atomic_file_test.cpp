// What a write replaces, and what it refuses to replace.
#include "test_meshes.h"

#include "mesh_ops/atomic_file.h"
#include "mesh_ops/errors.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace mrcloth {
namespace {

namespace fs = std::filesystem;

void write_text(const fs::path& path, const std::string& text) {
  write_file_atomically(path.string(), ".txt", [&](const std::string& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    out.close();
    return !out.fail();
  });
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// The error `write_text` gives, or "written".
std::string refusal(const fs::path& path) {
  try {
    write_text(path, "new");
  } catch (const OutputError& error) {
    return error.what();
  }
  return "written";
}

// A link to the output stays a link, and the file it leads to gets the
// bytes (the writer replaced the link with a file before).
TEST(AtomicFile, ALinkStaysALinkAndItsFileIsWritten) {
  const fs::path folder = test::fresh_folder("atomic_file", "link");
  fs::create_directory(folder / "real");
  write_text(folder / "real" / "out.txt", "old");
  fs::create_symlink(fs::path("real") / "out.txt", folder / "link.txt");
  write_text(folder / "link.txt", "new");
  EXPECT_TRUE(fs::is_symlink(folder / "link.txt"));
  EXPECT_EQ(read_text(folder / "real" / "out.txt"), "new");
  // A dangling link gets its file.
  fs::create_symlink(fs::path("real") / "made.txt", folder / "dangling.txt");
  write_text(folder / "dangling.txt", "made");
  EXPECT_TRUE(fs::is_symlink(folder / "dangling.txt"));
  EXPECT_EQ(read_text(folder / "real" / "made.txt"), "made");
  // A loop of links is refused, not followed for ever.
  fs::create_symlink("loop_b.txt", folder / "loop_a.txt");
  fs::create_symlink("loop_a.txt", folder / "loop_b.txt");
  EXPECT_NE(refusal(folder / "loop_a.txt"), "written");
}

// A chain of long relative links the system follows is followed here too
// (joining every hop's path grew past PATH_MAX and was refused).
TEST(AtomicFile, AChainOfLongLinksIsFollowed) {
  const fs::path folder = test::fresh_folder("atomic_file", "long_links");
  std::string dots;
  for (int k = 0; k < 190; ++k) dots += "./";
  write_text(folder / "final.txt", "old");
  fs::create_symlink(dots + "final.txt", folder / "l1");
  for (int k = 2; k <= 12; ++k) fs::create_symlink(dots + "l" + std::to_string(k - 1), folder / ("l" + std::to_string(k)));
  write_text(folder / "l12", "new");
  EXPECT_TRUE(fs::is_symlink(folder / "l12"));
  EXPECT_EQ(read_text(folder / "final.txt"), "new");
}

// The replaced file's permissions carry over (they were reset to the
// umask's, widening a 0640 file to 0644).
TEST(AtomicFile, AReplacedFileKeepsItsPermissions) {
  const fs::path folder = test::fresh_folder("atomic_file", "permissions");
  const fs::path file = folder / "out.txt";
  write_text(file, "old");
  fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  write_text(file, "new");
  EXPECT_EQ(read_text(file), "new");
  EXPECT_EQ(fs::status(file).permissions(), fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  // Never set-user or set-group-id onto a file written here (a 6755 file
  // came out set-uid root when root wrote it).
  constexpr fs::perms program = fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                fs::perms::others_read | fs::perms::others_exec;
  fs::permissions(file, program | fs::perms::set_uid | fs::perms::set_gid);
  write_text(file, "newer");
  EXPECT_EQ(fs::status(file).permissions(), program);
}

// As root, a replaced file keeps its owner (another user's file came out
// root's, which its owner could no longer read); a user who may not change
// a file (another's, in a folder anyone can write) is refused, where the
// rename went through before.
TEST(AtomicFile, OwnersAreKeptAndOthersFilesRefused) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to make a file of another user";
  const fs::path folder = test::fresh_folder("atomic_file", "owners");
  const fs::path file = folder / "theirs.txt";
  write_text(file, "old");
  constexpr uid_t other = 54321;
  ASSERT_EQ(chown(file.c_str(), other, other), 0);
  write_text(file, "new");
  struct stat kept {};
  ASSERT_EQ(stat(file.c_str(), &kept), 0);
  EXPECT_EQ(kept.st_uid, other);
  EXPECT_EQ(kept.st_gid, other);

  // A user of its own, in a child process, against root's file.
  const fs::path roots = folder / "roots.txt";
  write_text(roots, "root's");
  fs::permissions(folder, fs::perms::all);
  const pid_t child = fork();
  if (child == 0) {
    if (setgid(other) != 0 || setuid(other) != 0) _exit(2);
    const std::string said = refusal(roots);
    _exit(said == roots.string() + ": cannot write file (this user may not change it)" ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "the other user's write was not refused as expected";
  EXPECT_EQ(read_text(roots), "root's");
}

// A read-only file and a pipe (as a device: /dev/stdout) are refused by
// name, before any work, and left as they were (as root, a device was
// replaced by a regular file).
TEST(AtomicFile, ReadOnlyFilesAndPipesAreRefused) {
  const fs::path folder = test::fresh_folder("atomic_file", "refused");
  const fs::path locked = folder / "locked.txt";
  write_text(locked, "old");
  fs::permissions(locked, fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  EXPECT_EQ(refusal(locked), locked.string() + ": cannot write file (it is read-only; make it writable to replace it)");
  EXPECT_EQ(read_text(locked), "old");

  const fs::path pipe = folder / "pipe";
  ASSERT_EQ(mkfifo(pipe.c_str(), 0644), 0);
  EXPECT_EQ(refusal(pipe), pipe.string() + ": cannot write file (it is a device, pipe or socket, not a regular file; "
                                           "expected the path of a file to write)");
  EXPECT_TRUE(fs::is_fifo(pipe));
  // Nothing but the two files is left in the folder.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++entries;
  EXPECT_EQ(entries, 2u);
}

// A staged file stays out of sight (the earlier file in place) until its
// commit; never committed, it leaves nothing; a failed write neither.
TEST(AtomicFile, AStagedFileAppearsOnlyWhenCommitted) {
  const fs::path folder = test::fresh_folder("atomic_file", "staged");
  const fs::path file = folder / "rest.obj";
  write_text(file, "earlier");
  const auto entries = [&] {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder)) ++n;
    return n;
  };
  {
    StagedFile staged(file.string(), ".obj", [](const std::string& temporary) { std::ofstream(temporary) << "new"; });
    EXPECT_EQ(read_text(file), "earlier");
    EXPECT_EQ(entries(), 2u);
    staged.commit();
    EXPECT_EQ(read_text(file), "new");
  }
  EXPECT_EQ(entries(), 1u);
  {
    StagedFile abandoned(file.string(), ".obj", [](const std::string& temporary) { std::ofstream(temporary) << "lost"; });
  }
  EXPECT_EQ(read_text(file), "new");
  EXPECT_EQ(entries(), 1u);
  EXPECT_THROW(StagedFile(file.string(), ".obj",
                          [](const std::string& temporary) {
                            std::ofstream(temporary) << "half";
                            throw OutputError(temporary + ": disk full");
                          }),
               OutputError);
  EXPECT_EQ(read_text(file), "new");
  EXPECT_EQ(entries(), 1u);
}

}  // namespace
}  // namespace mrcloth
