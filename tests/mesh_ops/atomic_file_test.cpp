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
