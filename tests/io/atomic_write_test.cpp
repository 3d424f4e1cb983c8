// write_file_atomically: writes, replaces, refuses to overwrite the input, and never
// leaves a temporary file behind.
#include "io/native_json.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>

namespace kintsugi::io {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, removed afterwards.
class AtomicWrite : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("kintsugi_io_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string contents(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::vector<std::string> files() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir_)) out.push_back(e.path().filename().string());
    std::sort(out.begin(), out.end());
    return out;
  }

  fs::path dir_;
};

TEST_F(AtomicWrite, WritesANewFile) {
  std::string error;
  ASSERT_TRUE(write_file_atomically(path("out.json"), "hello\n", &error)) << error;
  EXPECT_EQ(contents(path("out.json")), "hello\n");
  EXPECT_EQ(files(), std::vector<std::string>{"out.json"});
}

TEST_F(AtomicWrite, ReplacesAnExistingFile) {
  std::string error;
  ASSERT_TRUE(write_file_atomically(path("out.json"), std::string(100000, 'a'), &error)) << error;
  ASSERT_TRUE(write_file_atomically(path("out.json"), "short", &error)) << error;
  EXPECT_EQ(contents(path("out.json")), "short");
  EXPECT_EQ(files(), std::vector<std::string>{"out.json"});
}

TEST_F(AtomicWrite, WritesEmptyContents) {
  std::string error;
  ASSERT_TRUE(write_file_atomically(path("empty"), "", &error)) << error;
  EXPECT_TRUE(fs::exists(path("empty")));
  EXPECT_EQ(fs::file_size(path("empty")), 0u);
}

TEST_F(AtomicWrite, RefusesToOverwriteTheInput) {
  std::string error;
  ASSERT_TRUE(write_file_atomically(path("in.json"), "input", &error)) << error;
  EXPECT_FALSE(write_file_atomically(path("in.json"), "output", &error, path("in.json")));
  EXPECT_NE(error.find("refusing to overwrite the input file"), std::string::npos) << error;
  EXPECT_EQ(contents(path("in.json")), "input");
  // The same file under another name: found through its identity, not its spelling.
  EXPECT_FALSE(write_file_atomically(path("./in.json"), "output", &error, (dir_ / ".." / dir_.filename() / "in.json").string()));
  fs::create_hard_link(path("in.json"), path("link.json"));
  EXPECT_FALSE(write_file_atomically(path("link.json"), "output", &error, path("in.json")));
  fs::create_symlink(path("in.json"), path("sym.json"));
  EXPECT_FALSE(write_file_atomically(path("sym.json"), "output", &error, path("in.json")));
  EXPECT_EQ(contents(path("in.json")), "input");
  // A different file, or an input that does not exist, is no obstacle.
  EXPECT_TRUE(write_file_atomically(path("out.json"), "output", &error, path("in.json"))) << error;
  EXPECT_TRUE(write_file_atomically(path("out2.json"), "output", &error, path("missing.json"))) << error;
  EXPECT_EQ(files(), (std::vector<std::string>{"in.json", "link.json", "out.json", "out2.json", "sym.json"}));
}

TEST_F(AtomicWrite, FailsCleanlyWhenTheDirectoryDoesNotExist) {
  std::string error;
  EXPECT_FALSE(write_file_atomically(path("no/such/dir/out.json"), "x", &error));
  EXPECT_NE(error.find("cannot create a temporary file"), std::string::npos) << error;
  EXPECT_NE(error.find("no/such/dir/out.json"), std::string::npos) << error;
  EXPECT_TRUE(files().empty());
}

TEST_F(AtomicWrite, FailsCleanlyWhenTheTargetIsADirectory) {
  fs::create_directory(path("sub"));
  std::string error;
  EXPECT_FALSE(write_file_atomically(path("sub"), "x", &error));
  EXPECT_NE(error.find("cannot rename"), std::string::npos) << error;
  EXPECT_EQ(files(), std::vector<std::string>{"sub"});  // the temporary file is gone
}

TEST_F(AtomicWrite, RefusesAPathWithoutAFileName) {
  std::string error;
  EXPECT_FALSE(write_file_atomically("", "x", &error));
  EXPECT_NE(error.find("is not a file name"), std::string::npos) << error;
  EXPECT_FALSE(write_file_atomically(dir_.string() + "/", "x", &error));
  EXPECT_TRUE(files().empty());
}

// The failures below are ones root cannot bypass (CI runs as root, which ignores
// directory permissions): a parent that is a regular file, and a file-size limit.

TEST_F(AtomicWrite, FailsCleanlyWhenTheDirectoryIsAFile) {
  std::string error;
  ASSERT_TRUE(write_file_atomically(path("plain"), "old", &error)) << error;
  EXPECT_FALSE(write_file_atomically(path("plain/out.json"), "new", &error));
  EXPECT_NE(error.find("cannot create a temporary file"), std::string::npos) << error;
  EXPECT_NE(error.find("Not a directory"), std::string::npos) << error;
  EXPECT_EQ(contents(path("plain")), "old");
  EXPECT_EQ(files(), std::vector<std::string>{"plain"});
}

// RLIMIT_FSIZE applies to root too: the write of the temporary file fails half-way
// (EFBIG), and the existing target must keep its old contents with no temporary left.
TEST_F(AtomicWrite, FailsCleanlyWhenTheWriteFails) {
  std::string error;
  ASSERT_TRUE(write_file_atomically(path("out.json"), "old", &error)) << error;
  struct rlimit saved;
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &saved), 0);
  void (*saved_handler)(int) = std::signal(SIGXFSZ, SIG_IGN);  // else the process is killed
  struct rlimit small = saved;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const bool written = write_file_atomically(path("out.json"), std::string(1 << 20, 'x'), &error);
  ::setrlimit(RLIMIT_FSIZE, &saved);
  std::signal(SIGXFSZ, saved_handler);
  EXPECT_FALSE(written);
  EXPECT_NE(error.find("cannot write"), std::string::npos) << error;
  EXPECT_EQ(contents(path("out.json")), "old");
  EXPECT_EQ(files(), std::vector<std::string>{"out.json"});
}

TEST_F(AtomicWrite, WrittenDocumentReadsBack) {
  std::string error;
  ASSERT_TRUE(write_file_atomically(path("b.json"), write_native(Body{}, {{"tolerance", 0.5}}), &error)) << error;
  auto doc = read_native_file(path("b.json"), &error);
  ASSERT_TRUE(doc) << error;
  EXPECT_EQ(doc->meta["tolerance"], 0.5);
}

}  // namespace
}  // namespace kintsugi::io
