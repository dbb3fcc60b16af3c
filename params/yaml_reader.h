// Validated reading of YAML parameter files. Every error names the file, the
// key (as a dotted path) and the allowed range, so a user can fix the file
// without reading code. Used once at start-up; never on a per-sample path.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace birotor {

// Thrown by the readers; what() is a complete one-line message:
// "<file>: key '<path>': <problem> (allowed: <range>)".
class ParamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A view on one YAML mapping of a file, with the dotted path that leads to it.
// Reading a key marks it as known; Finish() rejects keys that were never read.
class YamlSection {
 public:
  YamlSection(std::string file, std::string path, YAML::Node node);

  // Loads a file and returns its root section (the root must be a mapping).
  static YamlSection LoadFile(const std::string& file);
  // Parses YAML text (file is only used in messages).
  static YamlSection LoadString(const std::string& text, const std::string& file);

  bool Has(const std::string& key) const;
  // Optional keys keep *value when absent; Required* throw when absent.
  void Double(const std::string& key, double min, double max, double* value);
  void RequiredDouble(const std::string& key, double min, double max, double* value);
  void Int(const std::string& key, int64_t min, int64_t max, int64_t* value);
  void Int(const std::string& key, int min, int max, int* value);
  void Bool(const std::string& key, bool* value);
  void String(const std::string& key, const std::vector<std::string>& allowed, std::string* value);
  void AnyString(const std::string& key, std::string* value);
  // A fixed-length list of doubles, each in [min, max].
  void DoubleArray(const std::string& key, int count, double min, double max, double* values);
  // A list of doubles of any length, each in [min, max].
  void DoubleList(const std::string& key, double min, double max, std::vector<double>* values);

  // Sub-mapping; an absent key gives an empty section.
  YamlSection Section(const std::string& key);
  // Elements of a sequence of mappings.
  std::vector<YamlSection> SectionList(const std::string& key);

  // Throws if the mapping has a key that no reader asked for.
  void Finish() const;

  [[noreturn]] void Fail(const std::string& key, const std::string& problem, const std::string& allowed) const;
  const std::string& file() const { return file_; }
  std::string KeyPath(const std::string& key) const;

 private:
  YAML::Node Get(const std::string& key);

  std::string file_;
  std::string path_;
  YAML::Node node_;
  std::set<std::string> read_keys_;
};

// Parses a YAML file (or text) whose top level must be a mapping; an empty
// file gives an empty mapping. ParamError names the file (or label) on failure.
YAML::Node LoadYamlMapping(const std::string& file);
YAML::Node ParseYamlMapping(const std::string& text, const std::string& label);

// "[min, max]" with compact number formatting.
std::string RangeText(double min, double max);

}  // namespace birotor
