// OutputSet and OutputFile (apps/common/output_files.hpp): complete or absent, never mixed.
#include "output_files.hpp"

#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

TEST_F(OutputFilesTest, FilesAddedLaterJoinTheSetAndItsOwnPrefixDropsStaleOnes) {
  write_set(root_ / "out", "one\n");
  std::ofstream(root_ / "out" / "point_007.toml") << "stale";
  std::ofstream(root_ / "out" / "plot.png") << "png";
  std::string error;
  auto set = OutputSet::open((root_ / "out").string(), names_, error);
  ASSERT_TRUE(set) << error;
  set->replace_all_starting_with("point_");
  std::FILE* added = set->add("point_000.toml", error);
  ASSERT_NE(added, nullptr) << error;
  std::fputs("fresh", added);
  EXPECT_EQ(set->file(2), added);
  // A name already in the set, or one that is not a plain file name, is refused.
  EXPECT_EQ(set->add("a.csv", error), nullptr);
  EXPECT_EQ(set->add("../escape", error), nullptr);
  EXPECT_NE(error.find("not a new plain file name"), std::string::npos) << error;
  ASSERT_TRUE(set->commit(error)) << error;
  EXPECT_EQ(entries(root_ / "out"),
            (std::set<std::string>{"a.csv", "b.csv", "plot.png", "point_000.toml"}));
  EXPECT_EQ(read(root_ / "out" / "point_000.toml"), "fresh");
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
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      std::string error;
      auto set = OutputSet::open((root_ / "out").string(), names_, error);
      if (!set) ::_exit(3);
      std::fputs("partial", set->file(0));
      std::fflush(set->file(0));
      std::raise(sig);
      ::_exit(4);  // not reached: the signal ends the process after the clean-up
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << WEXITSTATUS(status);
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_TRUE(entries(root_).empty()) << "signal " << sig;
  }
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

// Two runs writing one file would both report success while one result is lost: the second is
// refused at open, naming the file; the lock file goes with the commit or the discard.
TEST_F(OutputFilesTest, ASecondWriterOfTheSameFileIsRefusedUntilTheFirstIsDone) {
  const fs::path target = root_ / "tuned.toml";
  std::string error;
  auto first = OutputFile::open(target.string(), error, "tune");
  ASSERT_TRUE(first) << error;
  EXPECT_TRUE(fs::exists(root_ / ".tuned.toml.lock"));
  auto second = OutputFile::open(target.string(), error, "tune");
  EXPECT_FALSE(second);
  EXPECT_NE(error.find("'" + target.string() + "' is being written by another process"),
            std::string::npos)
      << error;
  // A set of the same name is the same output: refused too; another file is independent.
  EXPECT_FALSE(OutputSet::open(target.string(), names_, error));
  EXPECT_TRUE(OutputFile::open((root_ / "other.toml").string(), error, "tune")) << error;
  std::fputs("first\n", first->file());
  ASSERT_TRUE(first->commit(error)) << error;
  EXPECT_EQ(entries(root_), (std::set<std::string>{"tuned.toml"}));

  auto third = OutputFile::open(target.string(), error, "tune");
  ASSERT_TRUE(third) << error;
  third->discard();
  EXPECT_EQ(entries(root_), (std::set<std::string>{"tuned.toml"}));
  EXPECT_EQ(read(target), "first\n");
}

TEST_F(OutputFilesTest, AnInterruptedFileWriteLeavesNothingBehind) {
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      std::string error;
      auto file = OutputFile::open((root_ / "ticks.csv").string(), error, "rt_loop");
      if (!file) ::_exit(3);
      std::fputs("partial", file->file());
      std::fflush(file->file());
      std::raise(sig);
      ::_exit(4);  // not reached: the signal ends the process after the clean-up
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "exit status " << WEXITSTATUS(status);
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_TRUE(entries(root_).empty()) << "signal " << sig;
  }
}

TEST_F(OutputFilesTest, OutputFileInAMissingDirectoryFailsAtOpen) {
  std::string error;
  EXPECT_FALSE(OutputFile::open((root_ / "missing" / "x.csv").string(), error));
  EXPECT_NE(error.find("x.csv"), std::string::npos) << error;
  EXPECT_FALSE(OutputFile::open(root_.string(), error));
  EXPECT_NE(error.find("folder"), std::string::npos) << error;
}

// ---------------------------------------------------------------------------------------------
// The contract of an output path (check_output_path), the same at parse time and at open.

TEST_F(OutputFilesTest, ANameThatIsNoFileOrWhoseFolderIsMissingIsRefused) {
  const std::string dir = root_.string();
  EXPECT_NE(check_output_path("", {}).find("not a file name"), std::string::npos);
  EXPECT_NE(check_output_path(dir + "/", {}).find("not a file name"), std::string::npos);
  EXPECT_NE(check_output_path(dir + "/.", {}).find("not a file name"), std::string::npos);
  EXPECT_NE(check_output_path(dir + "/..", {}).find("not a file name"), std::string::npos);
  EXPECT_NE(check_output_path(dir, {}).find("is a folder"), std::string::npos);
  const std::string missing = check_output_path(dir + "/missing/x.toml", {});
  EXPECT_NE(missing.find("No such file or directory"), std::string::npos) << missing;
  std::ofstream(root_ / "file") << "x";
  const std::string under_file = check_output_path(dir + "/file/x.toml", {});
  EXPECT_NE(under_file.find("Not a directory"), std::string::npos) << under_file;
  EXPECT_EQ(check_output_path(dir + "/new.toml", {}), "");
  EXPECT_EQ(check_output_path(dir + "/file", {}), "");
}

TEST_F(OutputFilesTest, ReadOnlyFoldersAndFilesAreRefusedEvenForRoot) {
  fs::create_directory(root_ / "ro");
  fs::permissions(root_ / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  const std::string folder = check_output_path((root_ / "ro" / "x.toml").string(), {});
  // Root is refused by the mode bits ("read-only"), anyone else by access(2) ("Permission").
  EXPECT_TRUE(folder.find("read-only") != std::string::npos ||
              folder.find(std::strerror(EACCES)) != std::string::npos)
      << folder;
  std::ofstream(root_ / "locked.toml") << "keep";
  fs::permissions(root_ / "locked.toml", fs::perms::owner_read);
  const std::string file = check_output_path((root_ / "locked.toml").string(), {});
  EXPECT_NE(file.find("read-only"), std::string::npos) << file;
  std::string error;
  EXPECT_FALSE(OutputFile::open((root_ / "locked.toml").string(), error));
  EXPECT_EQ(read(root_ / "locked.toml"), "keep");
  fs::permissions(root_ / "ro", fs::perms::owner_all);
}

// Device nodes, FIFOs and sockets are refused and never replaced (private nodes, never the
// system's: a character device 1,7 is what /dev/full is).
TEST_F(OutputFilesTest, DevicesFifosAndSocketsAreRefusedAndLeftAsTheyAre) {
  std::vector<std::pair<fs::path, const char*>> nodes;
  if (::mknod((root_ / "full").c_str(), S_IFCHR | 0666, makedev(1, 7)) == 0)
    nodes.emplace_back(root_ / "full", "character device");
  else
    std::printf("note: mknod refused (%s): the device case is not checked\n", std::strerror(errno));
  ASSERT_EQ(::mkfifo((root_ / "fifo").c_str(), 0666), 0);
  nodes.emplace_back(root_ / "fifo", "FIFO");
  const int sock = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(sock, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  const std::string sock_path = (root_ / "sock").string();
  ASSERT_LT(sock_path.size(), sizeof addr.sun_path);
  std::memcpy(addr.sun_path, sock_path.c_str(), sock_path.size() + 1);
  ASSERT_EQ(::bind(sock, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
  nodes.emplace_back(root_ / "sock", "socket");
  fs::create_symlink(root_ / "fifo", root_ / "link_to_fifo");
  nodes.emplace_back(root_ / "link_to_fifo", "FIFO");
  for (const auto& [node, kind] : nodes) {
    const std::string bad = check_output_path(node.string(), {});
    EXPECT_NE(bad.find(kind), std::string::npos) << bad;
    std::string error;
    EXPECT_FALSE(OutputFile::open(node.string(), error)) << node;
    EXPECT_EQ(write_output_file(node.string(), "text", "test").find("'" + node.string() + "'"), 0u);
    struct stat st {};
    ASSERT_EQ(::lstat(node.c_str(), &st), 0);
    EXPECT_FALSE(S_ISREG(st.st_mode)) << node << " became a regular file";
  }
  ::close(sock);
  for (const std::string& e : entries(root_))  // no temporary left
    EXPECT_EQ(e.find(".tmp"), std::string::npos) << e;
}

TEST_F(OutputFilesTest, AnInputIsRefusedAsOutputUnderAnySpelling) {
  const fs::path input = root_ / "in.toml";
  std::ofstream(input) << "input";
  fs::create_symlink(input, root_ / "link.toml");
  fs::create_hard_link(input, root_ / "hard.toml");
  fs::create_directory(root_ / "sub");
  const std::vector<std::string> inputs = {"", (root_ / "missing.toml").string(), input.string()};
  for (const fs::path& spelling : {input, root_ / "link.toml", root_ / "hard.toml",
                                   root_ / "sub" / ".." / "in.toml", root_ / "." / "in.toml"}) {
    const std::string bad = check_output_path(spelling.string(), inputs);
    EXPECT_NE(bad.find("same file as the input"), std::string::npos) << spelling << ": " << bad;
  }
  // A file that does not exist yet cannot be an input.
  EXPECT_EQ(check_output_path((root_ / "missing.toml").string(), inputs), "");
  EXPECT_EQ(check_output_path((root_ / "other.toml").string(), inputs), "");
  EXPECT_EQ(read(input), "input");
}

TEST_F(OutputFilesTest, ASymbolicLinkIsFollowedAndStaysALink) {
  std::ofstream(root_ / "real.csv") << "old";
  fs::create_symlink("real.csv", root_ / "link.csv");
  ASSERT_EQ(write_output_file((root_ / "link.csv").string(), "new", "test"), "");
  EXPECT_TRUE(fs::is_symlink(root_ / "link.csv"));
  EXPECT_EQ(read(root_ / "real.csv"), "new");
  // A dangling link is refused (it names no file to replace).
  fs::create_symlink(root_ / "nowhere" / "x", root_ / "dangling.csv");
  EXPECT_NE(check_output_path((root_ / "dangling.csv").string(), {}).find("symbolic link"),
            std::string::npos);
}

TEST_F(OutputFilesTest, TheReplacedFileKeepsItsMode) {
  std::ofstream(root_ / "x.csv") << "old";
  fs::permissions(root_ / "x.csv",
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  ASSERT_EQ(write_output_file((root_ / "x.csv").string(), "new", "test"), "");
  EXPECT_EQ(fs::status(root_ / "x.csv").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

// A write that fails (here: the file size limit, EFBIG, as a full disk gives ENOSPC) leaves the
// previous file intact and no temporary, and says why.
TEST_F(OutputFilesTest, AFailedWriteLeavesThePreviousFileIntact) {
  const fs::path target = root_ / "big.hpp";
  std::ofstream(target) << "previous";
  rlimit old{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);
  rlimit small = old;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string error = write_output_file(target.string(), std::string(100000, 'x'), "test");
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_NE(error.find(std::strerror(EFBIG)), std::string::npos) << error;
  EXPECT_EQ(read(target), "previous");
  EXPECT_EQ(entries(root_), (std::set<std::string>{"big.hpp"}));
}

TEST_F(OutputFilesTest, ATargetThatBecameAFifoBeforeCommitIsLeftAlone) {
  const fs::path target = root_ / "x.csv";
  std::string error;
  auto file = OutputFile::open(target.string(), error, "test");
  ASSERT_TRUE(file) << error;
  std::fputs("data", file->file());
  ASSERT_EQ(::mkfifo(target.c_str(), 0666), 0);
  EXPECT_FALSE(file->commit(error));
  EXPECT_NE(error.find("FIFO"), std::string::npos) << error;
  struct stat st {};
  ASSERT_EQ(::lstat(target.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_EQ(entries(root_), (std::set<std::string>{"x.csv"}));
}

TEST_F(OutputFilesTest, TemporariesOfDeadProcessesAreRemovedOthersKept) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) ::_exit(0);
  ASSERT_EQ(::waitpid(child, nullptr, 0), child);  // `child` is now a pid no process has
  const std::string dead = ".ticks.csv.rt_loop." + std::to_string(child) + ".tmp";
  const std::string alive = ".ticks.csv.rt_loop." + std::to_string(::getppid()) + ".tmp";
  const std::string other_tool = ".ticks.csv.tune." + std::to_string(child) + ".tmp";
  for (const std::string& name : {dead, alive, other_tool})
    std::ofstream(root_ / name) << "";
  std::string error;
  auto file = OutputFile::open((root_ / "ticks.csv").string(), error, "rt_loop");
  ASSERT_TRUE(file) << error;
  EXPECT_EQ(file->temporary_path(),
            (root_ / (".ticks.csv.rt_loop." + std::to_string(::getpid()) + ".tmp")).string());
  ASSERT_TRUE(file->commit(error)) << error;
  EXPECT_EQ(entries(root_), (std::set<std::string>{"ticks.csv", alive, other_tool}));
}

TEST_F(OutputFilesTest, AnOutputFolderIsCheckedBeforeTheRun) {
  const std::vector<std::string> names = {"metrics.csv"};
  EXPECT_NE(check_output_dir("", names, {}).find("not a folder name"), std::string::npos);
  std::ofstream(root_ / "file") << "x";
  EXPECT_NE(check_output_dir((root_ / "file").string(), names, {}).find("not an output folder"),
            std::string::npos);
  EXPECT_EQ(check_output_dir((root_ / "new" / "deeper").string(), names, {}), "");
  fs::create_directory(root_ / "out");
  std::ofstream(root_ / "out" / "metrics.csv") << "input";
  const std::string input = (root_ / "out" / "metrics.csv").string();
  EXPECT_NE(check_output_dir((root_ / "out").string(), names, {input}).find("same file"),
            std::string::npos);
  EXPECT_EQ(check_output_dir((root_ / "out").string(), {"other.csv"}, {input}), "");
  fs::create_directory(root_ / "ro");
  fs::permissions(root_ / "ro", fs::perms::owner_read | fs::perms::owner_exec);
  const std::string ro = check_output_dir((root_ / "ro" / "out").string(), names, {});
  EXPECT_TRUE(ro.find("read-only") != std::string::npos ||
              ro.find(std::strerror(EACCES)) != std::string::npos)
      << ro;
  fs::permissions(root_ / "ro", fs::perms::owner_all);
}

}  // namespace
}  // namespace fuzzypid::cli
