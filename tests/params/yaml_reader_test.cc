// YAML reader: every error names the file, the key and the allowed range.
#include "params/yaml_reader.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <vector>

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

// The schema of ErrorOf with one key of section a.
std::string WithoutKey(const std::string& key) {
  std::string text = "a: {";
  for (const std::string item : {"x: 2.5", "n: 3", "mode: ekf"}) {
    if (item.rfind(key + ":", 0) != 0) text += item + ", ";
  }
  return text + "}";
}

TEST(YamlReader, EveryMissingKeyIsNamedInOneLine) {
  EXPECT_EQ(ErrorOf(WithoutKey("n")),
            "test.yaml: missing key: a.n (every key is required; the shipped reference files have them all)");
  EXPECT_EQ(ErrorOf("a: {x: 1}"),
            "test.yaml: missing 2 keys: a.n, a.mode (every key is required; the shipped reference files have them "
            "all)");
  // An absent section is one missing key, not one per key inside it.
  EXPECT_EQ(ErrorOf(""),
            "test.yaml: missing key: a (every key is required; the shipped reference files have them all)");
  // A key with no value is missing too.
  EXPECT_NE(ErrorOf("a: {x: , n: 3, mode: ekf}").find("missing key: a.x"), std::string::npos);
}

TEST(YamlReader, DuplicateKeysAreRefusedAnywhere) {
  EXPECT_EQ(ErrorOf("a: {x: 1, n: 3, mode: ekf, x: 2}"),
            "test.yaml: key 'a.x': appears twice (each key may be given once)");
  EXPECT_EQ(ErrorOf("a: {x: 1, n: 3, mode: ekf}\na: {x: 1, n: 3, mode: ekf}\n"),
            "test.yaml: key 'a': appears twice (each key may be given once)");
}

TEST(YamlReader, KeyThatIsAListIsRefusedNamingTheFile) {
  // Issue 16 item 7: `? [a, b] : 1` aborted three programs with an uncaught
  // YAML::TypedBadConversion.
  EXPECT_EQ(ErrorOf("? [a, b] : 1\n"),
            "test.yaml: the top level has a key that is not a plain name (a list or a mapping used as a key)");
  EXPECT_EQ(ErrorOf("a: {? {x: 1} : 2}"),
            "test.yaml: key 'a' has a key that is not a plain name (a list or a mapping used as a key)");
}

TEST(YamlReader, LongValuesAndKeysAreQuotedWithAtMost80Characters) {
  // Issue 16 item 9: a 100 MB scalar was echoed back whole.
  const std::string long_value(100000, '7');
  const std::string error = ErrorOf("a: {x: '" + long_value + "z', n: 3, mode: ekf}");
  EXPECT_EQ(error, "test.yaml: key 'a.x': expected a number, got '" + std::string(80, '7') +
                       "...' (100001 characters) (allowed: [0, 10])");
  const std::string long_key(1000, 'k');  // YAML allows implicit keys up to 1024 characters
  const std::string key_error = ErrorOf("a: {x: 1, n: 3, mode: ekf, " + long_key + ": 1}");
  EXPECT_LT(key_error.size(), 300u) << key_error.substr(0, 300);
  EXPECT_NE(key_error.find("unknown key (allowed: mode, n, x)"), std::string::npos) << key_error.substr(0, 300);
  EXPECT_EQ(Quoted(std::string(80, 'q')), "'" + std::string(80, 'q') + "'");
}

TEST(YamlReader, ControlCharactersAreEscapedSoEveryMessageIsOneLine) {
  // libFuzzer (param_file_fuzzer, fuzz/corpus/param_file_fuzzer/
  // escape_in_syntax_error.yaml): yaml-cpp's "unknown escape character"
  // message carried the raw byte, a line break, into ParamError.
  EXPECT_EQ(Quoted("a\nb\tc\x7f"), "'a\\nb\\x09c\\x7f'");
  const std::string value_error = ErrorOf("a: {x: 1, n: 3, mode: \"ek\\nf\"}");
  EXPECT_EQ(value_error.find('\n'), std::string::npos) << value_error;
  EXPECT_NE(value_error.find("'ek\\nf'"), std::string::npos) << value_error;
}

TEST(YamlReader, FilesAboveOneMegabyteAreRefusedBeforeParsing) {
  const std::string path = ::testing::TempDir() + "/yaml_reader_big_" + std::to_string(::getpid()) + ".yaml";
  {
    std::ofstream out(path);
    out << "a: {x: 1, n: 3, mode: ekf}\n#";
    out << std::string(kMaxParameterFileBytes, ' ') << "\n";
  }
  try {
    YamlSection::LoadFile(path);
    ADD_FAILURE() << "accepted a file above 1 MB";
  } catch (const ParamError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": larger than 1048576 bytes (", 0), 0u) << e.what();
  }
  std::remove(path.c_str());
  // A special file that never ends is refused by its type, at once; so is a
  // FIFO (which would wait for a writer): issue 23 item 7.
  try {
    YamlSection::LoadFile("/dev/zero");
    ADD_FAILURE() << "accepted /dev/zero";
  } catch (const ParamError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/dev/zero: a character device, not a regular file (refused); a parameter or scenario file is a "
              "regular file of a few kB");
  }
  const std::string fifo = ::testing::TempDir() + "/yaml_reader_fifo_" + std::to_string(::getpid()) + ".yaml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(YamlSection::LoadFile(fifo), ParamError);
  std::remove(fifo.c_str());
}

TEST(YamlReader, AnyExceptionOfAReaderIsNamedWithTheFile) {
  try {
    WithFileErrors("f.yaml", [] { YAML::Node("text").as<std::vector<int>>(); });
    ADD_FAILURE() << "no error";
  } catch (const ParamError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("f.yaml: cannot be read: ", 0), 0u) << e.what();
  }
}

TEST(YamlReader, OutOfRangeNamesFileKeyAndRange) {
  EXPECT_EQ(ErrorOf("a: {x: -1}"), "test.yaml: key 'a.x': value -1 is out of range (allowed: [0, 10])");
}

TEST(YamlReader, WrongTypeIsRefused) {
  EXPECT_NE(ErrorOf("a: {x: fast}").find("key 'a.x': expected a number, got 'fast'"), std::string::npos);
  EXPECT_NE(ErrorOf("a: {n: 2.5}").find("key 'a.n': expected an integer"), std::string::npos);
}

TEST(YamlReader, UnknownKeyIsRefusedListingTheSchemasKeys) {
  EXPECT_EQ(ErrorOf("a: {x: 1, n: 3, mode: ekf, y: 1}"), "test.yaml: key 'a.y': unknown key (allowed: mode, n, x)");
  EXPECT_EQ(ErrorOf("a: {x: 1, n: 3, mode: ekf}\nb: 1"), "test.yaml: key 'b': unknown key (allowed: a)");
}

TEST(YamlReader, UnknownEnumValueListsAllowed) {
  EXPECT_NE(ErrorOf("a: {mode: magic}").find("(allowed: ekf, inversion)"), std::string::npos);
}

TEST(YamlReader, MissingFileAndBadSyntax) {
  EXPECT_THROW(YamlSection::LoadFile("/nonexistent/file.yaml"), ParamError);
  EXPECT_NE(ErrorOf("a: [1, 2").find("not valid YAML"), std::string::npos);
}

// Issue 23 item 7: a 7.9 kB alias bomb (ten levels of ten aliases, 1e10
// leaves once expanded) cost 22 s of CPU at 1e8 leaves and about 40 minutes
// at 1e10. It is refused while parsed, with one line naming the file.
std::string AliasBomb(int levels) {
  std::string text = "l0: &l0 [\"" + std::string(7300, 'x') + "\"]\n";
  for (int level = 1; level <= levels; ++level) {
    text += "l" + std::to_string(level) + ": &l" + std::to_string(level) + " [";
    for (int i = 0; i < 10; ++i) text += std::string(i ? ", " : "") + "*l" + std::to_string(level - 1);
    text += "]\n";
  }
  return text;
}

TEST(YamlReader, AnAliasBombIsRefusedWithOneLineNamingTheFile) {
  for (const int levels : {8, 10}) {
    const std::string bomb = AliasBomb(levels);
    try {
      YamlSection::LoadString(bomb, "bomb.yaml");
      ADD_FAILURE() << "accepted a bomb of 1e" << levels << " leaves";
    } catch (const ParamError& e) {
      EXPECT_EQ(std::string(e.what()),
                "bomb.yaml: more than 100000 YAML nodes once aliases are expanded (an alias bomb?): refused");
    }
  }
  // The same from a file, through every loader's LoadYamlMapping.
  const std::string path = ::testing::TempDir() + "/yaml_reader_bomb_" + std::to_string(::getpid()) + ".yaml";
  std::ofstream(path) << AliasBomb(10);
  EXPECT_THROW(LoadYamlMapping(path), ParamError);
  std::remove(path.c_str());
}

// Aliases as such are fine: a small document that uses a few is read whole.
TEST(YamlReader, AFewAliasesWithinTheBudgetAreRead) {
  YamlSection root = YamlSection::LoadString("a: &gain 2.5\nb: *gain\nlist: &l [1, 2]\nc: *l\n", "ok.yaml");
  double a = 0, b = 0;
  double c[2] = {0, 0};
  root.Double("a", 0, 10, &a);
  root.Double("b", 0, 10, &b);
  root.DoubleArray("list", 2, 0, 10, c);
  root.DoubleArray("c", 2, 0, 10, c);
  root.Finish();
  EXPECT_EQ(b, 2.5);
  EXPECT_EQ(c[1], 2.0);
}

// Issue 22 item 6: a misspelt key names the key it most likely meant, in one
// short line; a key close to none (or to two) lists the allowed keys.
TEST(YamlReader, AMisspeltKeySaysWhichKeyItMeant) {
  EXPECT_EQ(ErrorOf("a: {x: 1, n: 3, mdoe: ekf}"), "test.yaml: key 'a.mdoe': unknown key; did you mean 'mode'?");
  EXPECT_EQ(ErrorOf("a: {x: 1, n: 3, mode: ekf, modes: 1}"),
            "test.yaml: key 'a.modes': unknown key; did you mean 'mode'?");
  EXPECT_EQ(ErrorOf("a: {x: 1, n: 3, mode: ekf, speed: 1}"),
            "test.yaml: key 'a.speed': unknown key (allowed: mode, n, x)");
}

}  // namespace
}  // namespace birotor
