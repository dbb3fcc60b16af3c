// Reading and replacing small files (params/regular_file.h): only regular
// files are read or replaced, never through a link, never waiting on a FIFO.
#include "params/regular_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace birotor {
namespace {

class RegularFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = ::testing::TempDir() + "/regular_file_XXXXXX";
    ASSERT_NE(mkdtemp(folder_.data()), nullptr);
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }
  std::string Slurp(const std::string& path) {
    std::ifstream in(path);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
  }
  std::string folder_;
};

TEST_F(RegularFileTest, ReadsARegularFileAndFollowsALinkOnlyWhenAllowed) {
  const std::string path = folder_ + "/a.yaml";
  std::ofstream(path) << "abc";
  const std::string link = folder_ + "/link.yaml";
  ASSERT_EQ(symlink(path.c_str(), link.c_str()), 0);
  std::string text, error;
  ASSERT_TRUE(ReadRegularFile(path, 3, LinkPolicy::kRefuse, &text, &error)) << error;
  EXPECT_EQ(text, "abc");
  EXPECT_TRUE(ReadRegularFile(link, 3, LinkPolicy::kFollow, &text, &error)) << error;
  EXPECT_FALSE(ReadRegularFile(link, 3, LinkPolicy::kRefuse, &text, &error));
  EXPECT_EQ(error, link + ": a symbolic link (refused)");
  EXPECT_FALSE(ReadRegularFile(path, 2, LinkPolicy::kRefuse, &text, &error));  // one byte over the cap
  EXPECT_EQ(error, path + ": larger than 2 bytes (3 bytes, refused)");
}

TEST_F(RegularFileTest, SpecialFilesAreRefusedByTypeAtOnce) {
  const std::string fifo = folder_ + "/fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string text, error;
  EXPECT_FALSE(ReadRegularFile(fifo, 4096, LinkPolicy::kFollow, &text, &error));  // no writer: would block
  EXPECT_EQ(error, fifo + ": a FIFO, not a regular file (refused)");
  EXPECT_FALSE(ReadRegularFile("/dev/zero", 4096, LinkPolicy::kFollow, &text, &error));
  EXPECT_EQ(error, "/dev/zero: a character device, not a regular file (refused)");
  EXPECT_FALSE(ReadRegularFile(folder_, 4096, LinkPolicy::kFollow, &text, &error));
  EXPECT_EQ(error, folder_ + ": a folder, not a regular file (refused)");
}

TEST_F(RegularFileTest, ReplaceWritesOnlyRegularFilesWithTheGivenMode) {
  const std::string path = folder_ + "/out";
  FileAttributes attributes;
  attributes.mode = 0640;
  std::string error;
  ASSERT_TRUE(ReplaceRegularFile(path, "one", attributes, &error)) << error;
  ASSERT_TRUE(ReplaceRegularFile(path, "two", attributes, &error)) << error;
  EXPECT_EQ(Slurp(path), "two");
  FileAttributes read;
  EXPECT_EQ(InspectPath(path, &read, nullptr), PathKind::kRegular);
  EXPECT_EQ(read.mode, 0640u);
  EXPECT_EQ(read.uid, geteuid());
  const std::string victim = folder_ + "/victim";
  std::ofstream(victim) << "precious";
  const std::string link = folder_ + "/link";
  ASSERT_EQ(symlink(victim.c_str(), link.c_str()), 0);
  EXPECT_FALSE(ReplaceRegularFile(link, "evil", attributes, &error));
  EXPECT_EQ(error, link + ": exists and is a symbolic link; only a regular file is replaced (refused, left alone)");
  EXPECT_EQ(Slurp(victim), "precious");
  EXPECT_EQ(InspectPath(folder_ + "/absent", nullptr, nullptr), PathKind::kAbsent);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder_), {}), 3);  // out, victim, link
}

TEST_F(RegularFileTest, AFailedReplacementLeavesTheTargetAndNoTemporary) {
  std::string error;
  EXPECT_FALSE(ReplaceRegularFile(folder_ + "/absent_folder/out", "x", FileAttributes(), &error));
  EXPECT_NE(error.find("cannot create a temporary file in " + folder_ + "/absent_folder"), std::string::npos) << error;
  if (geteuid() != 0) {
    const std::string path = folder_ + "/out";
    FileAttributes other_owner;
    other_owner.set_owner = true;
    other_owner.uid = 0;  // not ours: fchown fails without privilege
    EXPECT_FALSE(ReplaceRegularFile(path, "x", other_owner, &error));
    EXPECT_NE(error.find("cannot keep owner 0:0"), std::string::npos) << error;
    EXPECT_EQ(InspectPath(path, nullptr, nullptr), PathKind::kAbsent);
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder_), {}), 0);
}

}  // namespace
}  // namespace birotor
