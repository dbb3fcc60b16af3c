// YAML reader: every error names the file, the key and the allowed range.
#include "params/yaml_reader.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    YamlSection root = YamlSection::LoadString(text, "test.yaml");
    YamlSection s = root.Section("a");
    double x = 1;
    int n = 1;
    std::string mode = "ekf";
    s.Double("x", 0.0, 10.0, &x);
    s.Int("n", 1, 5, &n);
    s.String("mode", {"ekf", "inversion"}, &mode);
    s.Finish();
    root.Finish();
  } catch (const ParamError& e) {
    return e.what();
  }
  return "";
}

TEST(YamlReader, AcceptsValidFile) { EXPECT_EQ(ErrorOf("a: {x: 2.5, n: 3, mode: inversion}"), ""); }

TEST(YamlReader, OutOfRangeNamesFileKeyAndRange) {
  EXPECT_EQ(ErrorOf("a: {x: -1}"), "test.yaml: key 'a.x': value -1 is out of range (allowed: [0, 10])");
}

TEST(YamlReader, WrongTypeIsRefused) {
  EXPECT_NE(ErrorOf("a: {x: fast}").find("key 'a.x': expected a number, got 'fast'"), std::string::npos);
  EXPECT_NE(ErrorOf("a: {n: 2.5}").find("key 'a.n': expected an integer"), std::string::npos);
}

TEST(YamlReader, UnknownKeyIsRefused) {
  EXPECT_NE(ErrorOf("a: {y: 1}").find("key 'a.y': unknown key"), std::string::npos);
  EXPECT_NE(ErrorOf("b: 1").find("key 'b': unknown key"), std::string::npos);
}

TEST(YamlReader, UnknownEnumValueListsAllowed) {
  EXPECT_NE(ErrorOf("a: {mode: magic}").find("(allowed: ekf, inversion)"), std::string::npos);
}

TEST(YamlReader, MissingFileAndBadSyntax) {
  EXPECT_THROW(YamlSection::LoadFile("/nonexistent/file.yaml"), ParamError);
  EXPECT_NE(ErrorOf("a: [1, 2").find("not valid YAML"), std::string::npos);
}

}  // namespace
}  // namespace birotor
