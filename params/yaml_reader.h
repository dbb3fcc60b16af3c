// The one reader of YAML parameter and scenario files. A file is complete or
// refused: every key a reader asks for must be present (all missing keys are
// named in one line), keys nobody asks for are refused with the schema's list,
// duplicate keys and keys that are not plain names are refused, files above
// 1 MB, files that are not regular (a FIFO, a device) and documents above
// 100 000 nodes once aliases are expanded (an alias bomb) are refused, and
// values are quoted with at most 80 characters. Every error names the file,
// the key (as a dotted path) and the allowed range.
// Used once at start-up; never on a per-sample path.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <functional>
#include <memory>
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

// Parameter and scenario files larger than this are refused [bytes].
constexpr size_t kMaxParameterFileBytes = 1 << 20;
// Error messages quote at most this many characters of a value or key.
constexpr size_t kMaxQuotedChars = 80;

// 'text', or its first characters and "... (N characters)" when it is longer
// than kMaxQuotedChars; control characters as escapes (\n, \xNN), so a
// message stays one line.
std::string Quoted(const std::string& text);

// A view on one YAML mapping of a file, with the dotted path that leads to it.
// Every reader call declares a key of the schema: a key that is absent is
// recorded as missing (reported for the whole file by Finish() of the root or
// by CheckComplete()); a value out of range throws at once.
class YamlSection {
 public:
  // A root section over a parsed mapping (see LoadYamlMapping).
  YamlSection(std::string file, YAML::Node root);

  // Loads a file and returns its root section (the root must be a mapping).
  static YamlSection LoadFile(const std::string& file);
  // Parses YAML text (file is only used in messages).
  static YamlSection LoadString(const std::string& text, const std::string& file);

  bool Has(const std::string& key) const;
  void Double(const std::string& key, double min, double max, double* value);
  // Same as Double (every key is required); kept for readers that say so.
  void RequiredDouble(const std::string& key, double min, double max, double* value);
  void Int(const std::string& key, int64_t min, int64_t max, int64_t* value);
  void Int(const std::string& key, int min, int max, int* value);
  void Bool(const std::string& key, bool* value);
  void String(const std::string& key, const std::vector<std::string>& allowed, std::string* value);
  void AnyString(const std::string& key, std::string* value);
  // A fixed-length list of doubles, each in [min, max].
  void DoubleArray(const std::string& key, int count, double min, double max, double* values);
  // The same, or a list of shared_count equal numbers that every one of the
  // count elements takes (a file written for another count, with a value
  // that is the same everywhere).
  void DoubleArray(const std::string& key, int count, int shared_count, double min, double max, double* values);
  // A list of doubles of any length (may be []), each in [min, max].
  void DoubleList(const std::string& key, double min, double max, std::vector<double>* values);

  // Sub-mapping. An absent section is reported as one missing key, and the
  // keys read from it are not reported again.
  YamlSection Section(const std::string& key);
  // Elements of a sequence of mappings (may be []).
  std::vector<YamlSection> SectionList(const std::string& key);

  // Throws if the mapping has a key that no reader asked for (the message
  // lists the keys the readers asked for). On the root section, then throws
  // if any key of the file was missing.
  void Finish() const;
  // Throws if any key read so far from this file was missing (for files of
  // which only one section is read, e.g. the vehicle of an estimator file).
  void CheckComplete() const;

  [[noreturn]] void Fail(const std::string& key, const std::string& problem, const std::string& allowed) const;
  const std::string& file() const { return file_; }
  // The dotted path of this section ("" for the root).
  const std::string& path() const { return path_; }
  std::string KeyPath(const std::string& key) const;
  // Whether any key read so far from this file was missing (cross-field
  // checks skip a section whose values are partly defaults).
  bool HasMissingKeys() const { return !missing_->empty(); }

 private:
  // Keys the file lacks, shared by every section of one file.
  using MissingKeys = std::shared_ptr<std::vector<std::string>>;
  YamlSection(std::string file, std::string path, YAML::Node node, MissingKeys missing, bool absent);

  // The value of key, or an undefined node (recorded as missing) when the key
  // is absent or has no value.
  YAML::Node Get(const std::string& key);

  std::string file_;
  std::string path_;
  YAML::Node node_;
  MissingKeys missing_;
  bool absent_ = false;  // the section itself is missing: do not report its keys
  std::set<std::string> read_keys_;
};

// Documents with more nodes than this, counting each alias as the nodes it
// names, are refused (the shipped files have under 600).
constexpr uint64_t kMaxYamlNodes = 100000;

// YAML::Load(text) after counting its nodes, aliases expanded, in one pass
// over the parser's events: ParamError naming label when the count passes
// kMaxYamlNodes (an alias bomb), so no caller ever walks such a tree. YAML
// syntax errors escape as YAML::Exception. Every YAML text the programs read
// goes through here.
YAML::Node LoadYamlWithinBudget(const std::string& text, const std::string& label);

// Reads a parameter file of at most kMaxParameterFileBytes into text.
// ParamError names the file when it cannot be read or is too large.
std::string ReadParameterFileText(const std::string& file);

// Parses a YAML file (or text) whose top level must be a mapping; an empty
// file gives an empty mapping. Refuses files above 1 MB, duplicate keys and
// keys that are not plain names anywhere in the document. ParamError names
// the file (or label) on failure; no YAML exception escapes.
YAML::Node LoadYamlMapping(const std::string& file);
YAML::Node ParseYamlMapping(const std::string& text, const std::string& label);

// Runs read(), turning any YAML or standard exception that escapes it into a
// ParamError that names the file; ParamError passes through unchanged.
void WithFileErrors(const std::string& file, const std::function<void()>& read);

// "[min, max]" with compact number formatting.
std::string RangeText(double min, double max);

}  // namespace birotor
