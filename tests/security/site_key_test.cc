// SiteKey::Load (security/site_key.h): 32 raw bytes from a regular file that
// only its owner may write; anything else is refused with the file's name and
// the reason.
#include "security/site_key.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace birotor {
namespace {

std::string TempKeyPath(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "_" + std::to_string(getpid()) + ".key";
}

// A key file of size bytes 0xa5 with the given mode.
std::string WriteKeyFile(const std::string& name, size_t size, mode_t mode) {
  const std::string path = TempKeyPath(name);
  std::ofstream(path, std::ios::binary) << std::string(size, '\xa5');
  chmod(path.c_str(), mode);
  return path;
}

TEST(SiteKeyTest, LoadsThe32RawBytesOfAnOwnerOnlyFile) {
  const std::string path = WriteKeyFile("good", 32, 0640);
  SiteKey key(SiteKey::Bytes{});
  std::string error;
  ASSERT_TRUE(SiteKey::Load(path, &key, &error)) << error;
  for (uint8_t byte : key.bytes()) EXPECT_EQ(byte, 0xa5);
  unlink(path.c_str());
}

TEST(SiteKeyTest, RefusesAWorldWritableFileNamingItAndTheMode) {
  const std::string path = WriteKeyFile("world_writable", 32, 0666);
  SiteKey key(SiteKey::Bytes{});
  std::string error;
  EXPECT_FALSE(SiteKey::Load(path, &key, &error));
  EXPECT_EQ(error,
            "site key " + path + ": writable by its group or by others (mode 0666; chmod 0640 or stricter): refused");
  EXPECT_EQ(key.bytes()[0], 0);  // unchanged
  chmod(path.c_str(), 0620);     // group-writable is refused as well
  EXPECT_FALSE(SiteKey::Load(path, &key, &error));
  EXPECT_NE(error.find("mode 0620"), std::string::npos) << error;
  unlink(path.c_str());
}

TEST(SiteKeyTest, RefusesAWrongSizeALinkAFolderAndAMissingFile) {
  SiteKey key(SiteKey::Bytes{});
  std::string error;
  const std::string hex = WriteKeyFile("hex", 65, 0600);  // 64 hex digits and a newline: not the format
  EXPECT_FALSE(SiteKey::Load(hex, &key, &error));
  EXPECT_EQ(error, "site key " + hex + ": is 65 bytes, a site key is exactly 32 raw bytes: refused");
  const std::string good = WriteKeyFile("link_target", 32, 0600);
  const std::string link = TempKeyPath("link");
  unlink(link.c_str());
  ASSERT_EQ(symlink(good.c_str(), link.c_str()), 0);
  EXPECT_FALSE(SiteKey::Load(link, &key, &error));
  EXPECT_EQ(error, "site key " + link + ": a symbolic link, not a regular file");
  EXPECT_FALSE(SiteKey::Load(::testing::TempDir(), &key, &error));
  EXPECT_NE(error.find("not a regular file"), std::string::npos) << error;
  EXPECT_FALSE(SiteKey::Load(good + ".absent", &key, &error));
  EXPECT_EQ(error, "site key " + good + ".absent: No such file or directory");
  for (const std::string& path : {hex, good, link}) unlink(path.c_str());
}

}  // namespace
}  // namespace birotor
