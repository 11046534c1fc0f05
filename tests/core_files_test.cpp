// Output files written whole or not at all, and a run's hold on its folder (core/files.h).
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/files.h"
#include "test_util.h"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t entries(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

class Files : public test::TempDirTest {};

// A write that fails part-way (a full disk, an exception, an interrupted run) leaves the file that
// was there, and no temporary beside it.
TEST_F(Files, AFailedWriteLeavesTheFileThatWasThere) {
  const fs::path file = dir_ / "table.txt";
  writeTextFile(file.string(), "the good one\n");
  EXPECT_EQ(contents(file), "the good one\n");
  EXPECT_THROW(writeAtomically(file.string(),
                               [&](const std::string& temporary) {
                                 std::ofstream(temporary) << "half a fi";
                                 throw Error(file.string(), "failed part-way");
                               }),
               Error);
  EXPECT_EQ(contents(file), "the good one\n");
  EXPECT_EQ(entries(dir_), 1u) << "the temporary is removed";

  // A disk that fills (the file-size limit: writes past it fail with EFBIG): an error naming the
  // file, not an empty file.
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &old), 0);
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  try {
    writeTextFile(file.string(), std::string(100000, 'x'));
    ADD_FAILURE() << "no error for a write past the file-size limit";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + ": cannot write"), std::string::npos) << e.what();
  }
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &old), 0);
  std::signal(SIGXFSZ, SIG_DFL);
  EXPECT_EQ(contents(file), "the good one\n");
  EXPECT_EQ(entries(dir_), 1u);
  EXPECT_THROW(writeTextFile((dir_ / "no" / "such" / "x.txt").string(), "x"), Error);
}

// Ctrl-C in the middle of a write: the temporary goes, the good file stays, and the process ends
// by the signal (a child process, so the test runner's own disposition is untouched).
TEST_F(Files, AnInterruptedWriteLeavesNoTemporary) {
  const fs::path file = dir_ / "image.exr";
  writeTextFile(file.string(), "the good one\n");
  for (const int sig : {SIGINT, SIGTERM}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      installInterruptCleanup();
      writeAtomically(file.string(), [&](const std::string& temporary) {
        std::ofstream(temporary) << "half a fi";
        std::raise(sig);
      });
      std::_Exit(0);  // not reached: the signal ends the child
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << "status " << status;
    EXPECT_EQ(contents(file), "the good one\n");
    EXPECT_EQ(entries(dir_), 1u) << "the .partial- temporary is removed";
  }
}

// One run at a time in a folder: the second is refused naming the folder; the hold ends with the
// first run.
TEST_F(Files, ASecondRunIntoTheSameFolderIsRefused) {
  {
    const FolderLock first(dir_.string());
    try {
      const FolderLock second(dir_.string());
      ADD_FAILURE() << "a second lock on the same folder";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(dir_.string() + ": another penumbra run is writing into this folder"),
                std::string::npos)
          << e.what();
    }
  }
  const FolderLock again(dir_.string());  // released with the first
}

}  // namespace
}  // namespace penumbra
