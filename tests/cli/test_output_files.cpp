// OutputSet and OutputFile (apps/common/output_files.hpp): complete or absent, never mixed.
#include "output_files.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace fuzzypid::cli {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, removed afterwards.
class OutputFilesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = ::testing::TempDir() + "fuzzypid_output_XXXXXX";
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    root_ = pattern;
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }
  // Names in root_ (hidden ones included).
  std::set<std::string> entries(const fs::path& dir) const {
    std::set<std::string> out;
    for (const auto& e : fs::directory_iterator(dir))
      out.insert(e.path().filename().string());
    return out;
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // Writes `text` into every file of a new set for `dir` and commits it.
  void write_set(const fs::path& dir, const std::string& text) {
    std::string error;
    auto set = OutputSet::open(dir.string(), names_, error);
    ASSERT_TRUE(set) << error;
    for (std::size_t k = 0; k < names_.size(); ++k)
      std::fputs(text.c_str(), set->file(k));
    ASSERT_TRUE(set->commit(error)) << error;
  }

  fs::path root_;
  std::vector<std::string> names_ = {"a.csv", "b.csv"};
};

TEST_F(OutputFilesTest, CommitCreatesTheWholeSetAndLeavesNoTemporaryOrLock) {
  write_set(root_ / "out", "one\n");
  EXPECT_EQ(entries(root_), (std::set<std::string>{"out"}));
  EXPECT_EQ(entries(root_ / "out"), (std::set<std::string>{"a.csv", "b.csv"}));
  EXPECT_EQ(read(root_ / "out" / "b.csv"), "one\n");
}

TEST_F(OutputFilesTest, CommitReplacesThePreviousSetAndKeepsOtherRegularFiles) {
  write_set(root_ / "out", "one\n");
  std::ofstream(root_ / "out" / "plot.png") << "png";
  write_set(root_ / "out", "two\n");
  EXPECT_EQ(entries(root_ / "out"), (std::set<std::string>{"a.csv", "b.csv", "plot.png"}));
  EXPECT_EQ(read(root_ / "out" / "a.csv"), "two\n");
  EXPECT_EQ(read(root_ / "out" / "plot.png"), "png");
  EXPECT_EQ(entries(root_), (std::set<std::string>{"out"}));
}

TEST_F(OutputFilesTest, DiscardedSetLeavesThePreviousOneUntouched) {
  write_set(root_ / "out", "one\n");
  std::string error;
  {
    auto set = OutputSet::open((root_ / "out").string(), names_, error);
    ASSERT_TRUE(set) << error;
    std::fputs("half", set->file(0));
    set->discard();
  }
  {
    auto set = OutputSet::open((root_ / "out").string(), names_, error);
    ASSERT_TRUE(set) << error;
    std::fputs("half", set->file(0));
  }  // destroyed without commit: discarded
  EXPECT_EQ(read(root_ / "out" / "a.csv"), "one\n");
  EXPECT_EQ(entries(root_), (std::set<std::string>{"out"}));
}

TEST_F(OutputFilesTest, ASecondWriterOfTheSameDirectoryIsRefused) {
  std::string error;
  auto first = OutputSet::open((root_ / "out").string(), names_, error);
  ASSERT_TRUE(first) << error;
  auto second = OutputSet::open((root_ / "out").string(), names_, error);
  EXPECT_FALSE(second);
  EXPECT_NE(error.find("is being written by another process"), std::string::npos) << error;
  // Another directory beside it is independent.
  auto other = OutputSet::open((root_ / "other").string(), names_, error);
  EXPECT_TRUE(other) << error;
  ASSERT_TRUE(first->commit(error)) << error;
  auto third = OutputSet::open((root_ / "out").string(), names_, error);
  EXPECT_TRUE(third) << error;
}

TEST_F(OutputFilesTest, TwoSetsWriteToDistinctTemporaryDirectories) {
  std::string error;
  auto a = OutputSet::open((root_ / "a").string(), names_, error);
  auto b = OutputSet::open((root_ / "b").string(), names_, error);
  ASSERT_TRUE(a && b) << error;
  EXPECT_NE(a->temporary_dir(), b->temporary_dir());
}

TEST_F(OutputFilesTest, DirectoriesHoldingMoreThanFilesAreRefused) {
  fs::create_directories(root_ / "out" / "sub");
  std::string error;
  EXPECT_FALSE(OutputSet::open((root_ / "out").string(), names_, error));
  EXPECT_NE(error.find("sub"), std::string::npos) << error;
  std::ofstream(root_ / "file") << "x";
  EXPECT_FALSE(OutputSet::open((root_ / "file").string(), names_, error));
  EXPECT_NE(error.find("not a directory"), std::string::npos) << error;
  EXPECT_FALSE(OutputSet::open(".", names_, error));
}

TEST_F(OutputFilesTest, TemporariesOfAKilledRunAreRemovedByTheNextRun) {
  fs::create_directories(root_ / ".out.tmp-dead01");
  std::ofstream(root_ / ".out.tmp-dead01" / "a.csv") << "partial";
  write_set(root_ / "out", "one\n");
  EXPECT_EQ(entries(root_), (std::set<std::string>{"out"}));
}

TEST_F(OutputFilesTest, AnInterruptedRunLeavesNothingBehind) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::string error;
    auto set = OutputSet::open((root_ / "out").string(), names_, error);
    if (!set) ::_exit(3);
    std::fputs("partial", set->file(0));
    std::fflush(set->file(0));
    std::raise(SIGINT);
    ::_exit(4);  // not reached: SIGINT ends the process after the clean-up
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_TRUE(entries(root_).empty());
}

TEST_F(OutputFilesTest, OutputFileAppearsOnlyOnCommit) {
  const fs::path target = root_ / "ticks.csv";
  std::string error;
  auto file = OutputFile::open(target.string(), error);
  ASSERT_TRUE(file) << error;
  std::fputs("tick\n0\n", file->file());
  EXPECT_FALSE(fs::exists(target));
  ASSERT_TRUE(file->commit(error)) << error;
  EXPECT_EQ(read(target), "tick\n0\n");
  EXPECT_EQ(entries(root_), (std::set<std::string>{"ticks.csv"}));

  auto again = OutputFile::open(target.string(), error);
  ASSERT_TRUE(again) << error;
  std::fputs("half", again->file());
  again->discard();
  EXPECT_EQ(read(target), "tick\n0\n");
  EXPECT_EQ(entries(root_), (std::set<std::string>{"ticks.csv"}));
}

TEST_F(OutputFilesTest, OutputFileInAMissingDirectoryFailsAtOpen) {
  std::string error;
  EXPECT_FALSE(OutputFile::open((root_ / "missing" / "x.csv").string(), error));
  EXPECT_NE(error.find("x.csv"), std::string::npos) << error;
  EXPECT_FALSE(OutputFile::open(root_.string(), error));
  EXPECT_NE(error.find("directory"), std::string::npos) << error;
}

}  // namespace
}  // namespace fuzzypid::cli
