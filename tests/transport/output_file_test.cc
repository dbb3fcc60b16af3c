// Tests of transport/output_file.h: temporary file + rename, no partial file
// on failure, output == input refused (links included), special files in place.
#include "transport/output_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/transport/test_files.h"

namespace birotor {
namespace {

class OutputFileTest : public test_files::TempDirTest {};

using test_files::ReadText;

TEST_F(OutputFileTest, CommitReplacesTheTargetAndLeavesNoTemporary) {
  const std::string path = Path("out.txt");
  std::string error;
  ASSERT_TRUE(WriteFileAtomically(path, "old\n", &error)) << error;
  OutputFile file;
  ASSERT_TRUE(file.Open(path, &error)) << error;
  EXPECT_NE(file.write_path(), path);
  EXPECT_EQ(file.write_path().rfind(path + ".tmp.", 0), 0u);
  ASSERT_TRUE(file.Write("new\n"));
  EXPECT_EQ(ReadText(path), "old\n");  // untouched until Commit
  ASSERT_TRUE(file.Commit(&error)) << error;
  EXPECT_EQ(ReadText(path), "new\n");
  EXPECT_EQ(FilesInDirectory(), 1);
}

TEST_F(OutputFileTest, AbandonKeepsTheOldContent) {
  const std::string path = Path("keep.txt");
  std::string error;
  ASSERT_TRUE(WriteFileAtomically(path, "old\n", &error)) << error;
  {
    OutputFile file;
    ASSERT_TRUE(file.Open(path, &error)) << error;
    file.Write("half");
  }  // destroyed without Commit: a program that failed half-way
  EXPECT_EQ(ReadText(path), "old\n");
  EXPECT_EQ(FilesInDirectory(), 1);
}

TEST_F(OutputFileTest, DevFullFailsOnCommitWithTheReason) {
  if (access("/dev/full", W_OK) != 0) GTEST_SKIP() << "no /dev/full";
  OutputFile file;
  std::string error;
  ASSERT_TRUE(file.Open("/dev/full", &error)) << error;  // a device: written in place
  EXPECT_EQ(file.write_path(), "/dev/full");
  file.Write(std::string(100000, 'x'));
  EXPECT_FALSE(file.Commit(&error));
  EXPECT_NE(error.find("/dev/full"), std::string::npos) << error;
  EXPECT_NE(error.find("No space left on device"), std::string::npos) << error;
  struct stat info;
  ASSERT_EQ(stat("/dev/full", &info), 0);
  EXPECT_TRUE(S_ISCHR(info.st_mode));  // still the device, not a renamed file
}

TEST_F(OutputFileTest, DevNullIsWrittenInPlace) {
  std::string error;
  EXPECT_TRUE(WriteFileAtomically("/dev/null", "anything", &error)) << error;
}

TEST_F(OutputFileTest, MissingFolderAndFolderTargetsAreErrors) {
  std::string error;
  EXPECT_FALSE(WriteFileAtomically(Path("missing/out.txt"), "x", &error));
  EXPECT_NE(error.find("missing/out.txt"), std::string::npos) << error;
  EXPECT_FALSE(WriteFileAtomically(directory_.string(), "x", &error));
  EXPECT_NE(error.find("folder"), std::string::npos) << error;
}

TEST_F(OutputFileTest, OutputThatIsAnInputIsRefusedThroughLinks) {
  const std::string input = Path("input.lcm");
  std::string error;
  ASSERT_TRUE(WriteFileAtomically(input, "log bytes", &error)) << error;
  const std::string hard = Path("hard.lcm");
  const std::string soft = Path("soft.lcm");
  ASSERT_EQ(link(input.c_str(), hard.c_str()), 0);
  ASSERT_EQ(symlink(input.c_str(), soft.c_str()), 0);
  for (const std::string& output : {input, hard, soft, directory_.string() + "/./input.lcm"}) {
    EXPECT_FALSE(CheckOutputIsNotInput(output, {Path("other.lcm"), input}, &error)) << output;
    EXPECT_NE(error.find("is the input"), std::string::npos) << error;
  }
  EXPECT_TRUE(CheckOutputIsNotInput(Path("new.lcm"), {input}, &error));
  ASSERT_TRUE(WriteFileAtomically(Path("copy.lcm"), "log bytes", &error)) << error;
  EXPECT_TRUE(CheckOutputIsNotInput(Path("copy.lcm"), {input}, &error));  // same bytes, other file
}

}  // namespace
}  // namespace birotor
