#include "params/yaml_reader.h"

#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "params/regular_file.h"

namespace birotor {
namespace {

// Deeper nesting than this is refused before it is walked (no schema nests
// more than four levels).
constexpr int kMaxNestingDepth = 32;

std::string Number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

// Edit distance of two keys: insertions, deletions, substitutions and
// swaps of two neighbouring characters ("mdoe" is one edit from "mode").
size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

// The known key a misspelt one most likely meant: the nearest within a third
// of its length (at most 3 edits; none for keys of one or two characters), or
// "" when none is that close or two are equally close.
std::string ClosestKey(const std::string& key, const std::set<std::string>& known) {
  const size_t limit = std::min<size_t>(3, key.size() / 3);
  if (limit == 0) return "";
  std::string best;
  size_t best_distance = limit + 1;
  bool tie = false;
  for (const std::string& candidate : known) {
    const size_t distance = EditDistance(key, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
      tie = false;
    } else if (distance == best_distance) {
      tie = true;
    }
  }
  return tie ? "" : best;
}

// What a node holds, for "expected a number, got ..." messages.
std::string Describe(const YAML::Node& node) {
  if (node.IsScalar()) return Quoted(node.Scalar());
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a mapping";
  return "nothing";
}

YAML::Node RequireMapping(YAML::Node root, const std::string& label) {
  if (root.IsNull()) return YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) throw ParamError(label + ": the top level must be a mapping of keys");
  return root;
}

// Refuses, anywhere in the document, keys that are not plain names (e.g.
// `? [a, b] : 1`) and keys that appear twice in one mapping.
void CheckKeys(const YAML::Node& node, const std::string& label, const std::string& path, int depth) {
  if (depth > kMaxNestingDepth) {
    throw ParamError(label + ": " + (path.empty() ? "the file" : "key " + Quoted(path)) + " is nested deeper than " +
                     std::to_string(kMaxNestingDepth) + " levels");
  }
  if (node.IsSequence()) {
    for (size_t i = 0; i < node.size(); ++i) {
      CheckKeys(node[i], label, path + "[" + std::to_string(i) + "]", depth + 1);
    }
    return;
  }
  if (!node.IsMap()) return;
  std::set<std::string> seen;
  for (const auto& item : node) {
    if (!item.first.IsScalar()) {
      throw ParamError(label + ": " + (path.empty() ? "the top level" : "key " + Quoted(path)) +
                       " has a key that is not a plain name (a list or a mapping used as a key)");
    }
    const std::string key = item.first.Scalar();
    const std::string key_path = path.empty() ? key : path + "." + key;
    if (!seen.insert(key).second) {
      throw ParamError(label + ": key " + Quoted(key_path) + ": appears twice (each key may be given once)");
    }
    CheckKeys(item.second, label, key_path, depth + 1);
  }
}

// Counts the nodes of a document as its readers would walk them: an alias
// counts as every node of what it names. Throws once the count passes
// kMaxYamlNodes, so a 7.9 kB alias bomb of 1e10 leaves is refused while it
// is parsed (linear in its text), before any tree is built or walked.
class NodeBudget : public YAML::EventHandler {
 public:
  explicit NodeBudget(std::string label) : label_(std::move(label)) {}
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t anchor) override { Leaf(anchor); }
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t anchor, const std::string&) override {
    Leaf(anchor);
  }
  void OnAlias(const YAML::Mark&, YAML::anchor_t anchor) override { Add(anchor < sizes_.size() ? sizes_[anchor] : 1); }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    Open(anchor);
  }
  void OnSequenceEnd() override { Close(); }
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t anchor, YAML::EmitterStyle::value) override {
    Open(anchor);
  }
  void OnMapEnd() override { Close(); }

 private:
  struct Collection {
    YAML::anchor_t anchor;
    uint64_t nodes;  // itself and everything in it so far
  };
  void Leaf(YAML::anchor_t anchor) {
    Remember(anchor, 1);
    Add(1);
  }
  void Open(YAML::anchor_t anchor) {
    Count(1);
    open_.push_back({anchor, 1});
  }
  void Close() {
    const Collection done = open_.back();
    open_.pop_back();
    Remember(done.anchor, done.nodes);
    if (!open_.empty()) open_.back().nodes += done.nodes;
  }
  // n nodes inside the innermost open collection (sizes stay <= the budget).
  void Add(uint64_t n) {
    Count(n);
    if (!open_.empty()) open_.back().nodes += n;
  }
  void Count(uint64_t n) {
    total_ += n;
    if (total_ > kMaxYamlNodes) {
      throw ParamError(label_ + ": more than " + std::to_string(kMaxYamlNodes) +
                       " YAML nodes once aliases are expanded (an alias bomb?): refused");
    }
  }
  void Remember(YAML::anchor_t anchor, uint64_t nodes) {
    if (anchor == YAML::NullAnchor) return;
    if (sizes_.size() <= anchor) sizes_.resize(anchor + 1, 1);
    sizes_[anchor] = nodes;
  }

  std::string label_;
  std::vector<uint64_t> sizes_;  // nodes of each anchored node, by anchor id
  std::vector<Collection> open_;
  uint64_t total_ = 0;
};

ParamError SyntaxError(const std::string& label, const YAML::Exception& e) {
  return ParamError(label + ": not valid YAML at line " + std::to_string(e.mark.line + 1) + ": " + Quoted(e.msg));
}

}  // namespace

std::string Quoted(const std::string& text) {
  // Control characters (a line break in a quoted YAML scalar, or in a YAML
  // syntax message about such a byte) are written as escapes, so that the
  // message stays one line.
  std::string out = "'";
  for (size_t i = 0; i < std::min(text.size(), kMaxQuotedChars); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\n') {
      out += "\\n";
    } else if (c < 0x20 || c == 0x7f) {
      static const char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xf];
    } else {
      out += static_cast<char>(c);
    }
  }
  if (text.size() <= kMaxQuotedChars) return out + "'";
  return out + "...' (" + std::to_string(text.size()) + " characters)";
}

std::string RangeText(double min, double max) { return "[" + Number(min) + ", " + Number(max) + "]"; }

std::string ReadParameterFileText(const std::string& file) {
  // A regular file only (a FIFO is refused without waiting for a writer,
  // /dev/zero before a byte is read); a symbolic link to one is followed.
  std::string text, error;
  if (!ReadRegularFile(file, kMaxParameterFileBytes, LinkPolicy::kFollow, &text, &error)) {
    throw ParamError(error + "; a parameter or scenario file is a regular file of a few kB");
  }
  return text;
}

YAML::Node ParseYamlMapping(const std::string& text, const std::string& label) {
  if (text.size() > kMaxParameterFileBytes) {
    throw ParamError(label + ": larger than " + std::to_string(kMaxParameterFileBytes) + " bytes: refused");
  }
  YAML::Node root;
  try {
    root = RequireMapping(LoadYamlWithinBudget(text, label), label);
    CheckKeys(root, label, "", 0);
  } catch (const ParamError&) {
    throw;
  } catch (const YAML::Exception& e) {
    throw SyntaxError(label, e);
  } catch (const std::exception& e) {
    throw ParamError(label + ": cannot be read: " + Quoted(e.what()));
  }
  return root;
}

YAML::Node LoadYamlWithinBudget(const std::string& text, const std::string& label) {
  {
    std::istringstream in(text);
    YAML::Parser parser(in);
    NodeBudget budget(label);
    while (parser.HandleNextDocument(budget)) {
    }
  }
  return YAML::Load(text);
}

YAML::Node LoadYamlMapping(const std::string& file) { return ParseYamlMapping(ReadParameterFileText(file), file); }

void WithFileErrors(const std::string& file, const std::function<void()>& read) {
  try {
    read();
  } catch (const ParamError&) {
    throw;
  } catch (const YAML::Exception& e) {
    throw ParamError(file + ": cannot be read: " + Quoted(e.what()));
  } catch (const std::exception& e) {
    throw ParamError(file + ": cannot be read: " + Quoted(e.what()));
  }
}

YamlSection::YamlSection(std::string file, YAML::Node root)
    : YamlSection(std::move(file), "", std::move(root), std::make_shared<std::vector<std::string>>(), false) {}

YamlSection::YamlSection(std::string file, std::string path, YAML::Node node, MissingKeys missing, bool absent)
    : file_(std::move(file)),
      path_(std::move(path)),
      node_(std::move(node)),
      missing_(std::move(missing)),
      absent_(absent) {}

YamlSection YamlSection::LoadFile(const std::string& file) { return YamlSection(file, LoadYamlMapping(file)); }

YamlSection YamlSection::LoadString(const std::string& text, const std::string& file) {
  return YamlSection(file, ParseYamlMapping(text, file));
}

std::string YamlSection::KeyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

void YamlSection::Fail(const std::string& key, const std::string& problem, const std::string& allowed) const {
  std::string message = file_ + ": key " + Quoted(KeyPath(key)) + ": " + problem;
  if (!allowed.empty()) message += " (allowed: " + allowed + ")";
  throw ParamError(message);
}

bool YamlSection::Has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

YAML::Node YamlSection::Get(const std::string& key) {
  read_keys_.insert(key);
  if (Has(key)) return node_[key];
  if (!absent_) missing_->push_back(KeyPath(key));
  return YAML::Node(YAML::NodeType::Undefined);
}

void YamlSection::Double(const std::string& key, double min, double max, double* value) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined()) return;
  double x = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, x))
    Fail(key, "expected a number, got " + Describe(n), RangeText(min, max));
  if (!std::isfinite(x) || x < min || x > max)
    Fail(key, "value " + Number(x) + " is out of range", RangeText(min, max));
  *value = x;
}

void YamlSection::RequiredDouble(const std::string& key, double min, double max, double* value) {
  Double(key, min, max, value);
}

void YamlSection::Int(const std::string& key, int64_t min, int64_t max, int64_t* value) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined()) return;
  int64_t x = 0;
  if (!n.IsScalar() || !YAML::convert<int64_t>::decode(n, x))
    Fail(key, "expected an integer, got " + Describe(n), RangeText(static_cast<double>(min), static_cast<double>(max)));
  if (x < min || x > max)
    Fail(key, "value " + std::to_string(x) + " is out of range",
         RangeText(static_cast<double>(min), static_cast<double>(max)));
  *value = x;
}

void YamlSection::Int(const std::string& key, int min, int max, int* value) {
  int64_t x = *value;
  Int(key, static_cast<int64_t>(min), static_cast<int64_t>(max), &x);
  *value = static_cast<int>(x);
}

void YamlSection::Bool(const std::string& key, bool* value) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined()) return;
  bool x = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, x))
    Fail(key, "expected true or false, got " + Describe(n), "true, false");
  *value = x;
}

void YamlSection::String(const std::string& key, const std::vector<std::string>& allowed, std::string* value) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined()) return;
  const std::string list = Join(allowed);
  if (!n.IsScalar()) Fail(key, "expected a string, got " + Describe(n), list);
  const std::string x = n.Scalar();
  bool ok = allowed.empty();
  for (const std::string& a : allowed) ok = ok || (a == x);
  if (!ok) Fail(key, "unknown value " + Quoted(x), list);
  if (x.size() > kMaxQuotedChars) Fail(key, "longer than " + std::to_string(kMaxQuotedChars) + " characters", "");
  *value = x;
}

void YamlSection::AnyString(const std::string& key, std::string* value) { String(key, {}, value); }

void YamlSection::DoubleArray(const std::string& key, int count, double min, double max, double* values) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined()) return;
  const std::string allowed = std::to_string(count) + " numbers, each in " + RangeText(min, max);
  if (!n.IsSequence() || static_cast<int>(n.size()) != count)
    Fail(key, "expected a list of " + std::to_string(count) + ", got " + Describe(n), allowed);
  for (int i = 0; i < count; ++i) {
    double x = 0;
    if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], x))
      Fail(key, "element " + std::to_string(i) + " is not a number: " + Describe(n[i]), allowed);
    if (!std::isfinite(x) || x < min || x > max)
      Fail(key, "element " + std::to_string(i) + " = " + Number(x) + " is out of range", allowed);
    values[i] = x;
  }
}

void YamlSection::DoubleArray(const std::string& key, int count, int shared_count, double min, double max,
                              double* values) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined()) return;
  if (shared_count == count || !n.IsSequence() || static_cast<int>(n.size()) != shared_count) {
    DoubleArray(key, count, min, max, values);
    return;
  }
  std::vector<double> shared(static_cast<size_t>(shared_count));
  DoubleArray(key, shared_count, min, max, shared.data());
  for (double x : shared) {
    if (x != shared.front()) {
      Fail(key,
           "a list of " + std::to_string(shared_count) + " with different numbers for " + std::to_string(count) +
               " elements",
           std::to_string(count) + " numbers, or " + std::to_string(shared_count) + " equal ones, each in " +
               RangeText(min, max));
    }
  }
  for (int i = 0; i < count; ++i) values[i] = shared.front();
}

void YamlSection::DoubleList(const std::string& key, double min, double max, std::vector<double>* values) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined()) return;
  const std::string allowed = "a list of numbers, each in " + RangeText(min, max);
  if (!n.IsSequence()) Fail(key, "expected a list, got " + Describe(n), allowed);
  values->clear();
  for (size_t i = 0; i < n.size(); ++i) {
    double x = 0;
    if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], x))
      Fail(key, "element " + std::to_string(i) + " is not a number: " + Describe(n[i]), allowed);
    if (!std::isfinite(x) || x < min || x > max)
      Fail(key, "element " + std::to_string(i) + " = " + Number(x) + " is out of range", allowed);
    values->push_back(x);
  }
}

YamlSection YamlSection::Section(const std::string& key) {
  const bool parent_absent = absent_;
  YAML::Node n = Get(key);
  if (!n.IsDefined()) {
    return YamlSection(file_, KeyPath(key), YAML::Node(YAML::NodeType::Map), missing_, true);
  }
  if (!n.IsMap()) Fail(key, "expected a mapping of keys, got " + Describe(n), "");
  return YamlSection(file_, KeyPath(key), n, missing_, parent_absent);
}

std::vector<YamlSection> YamlSection::SectionList(const std::string& key) {
  YAML::Node n = Get(key);
  std::vector<YamlSection> out;
  if (!n.IsDefined()) return out;
  if (!n.IsSequence()) Fail(key, "expected a list (may be []), got " + Describe(n), "");
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string path = KeyPath(key) + "[" + std::to_string(i) + "]";
    if (!n[i].IsMap()) throw ParamError(file_ + ": key " + Quoted(path) + ": expected a mapping of keys");
    out.push_back(YamlSection(file_, path, n[i], missing_, absent_));
  }
  return out;
}

void YamlSection::Finish() const {
  if (node_.IsMap()) {
    for (const auto& item : node_) {
      const std::string key = item.first.Scalar();  // plain names only (CheckKeys)
      if (read_keys_.count(key) == 0) {
        const std::string close = ClosestKey(key, read_keys_);
        if (!close.empty()) {
          throw ParamError(file_ + ": key " + Quoted(KeyPath(key)) + ": unknown key; did you mean " + Quoted(close) +
                           "?");
        }
        std::vector<std::string> known(read_keys_.begin(), read_keys_.end());
        throw ParamError(file_ + ": key " + Quoted(KeyPath(key)) + ": unknown key (allowed: " + Join(known) + ")");
      }
    }
  }
  if (path_.empty()) CheckComplete();
}

void YamlSection::CheckComplete() const {
  if (missing_->empty()) return;
  throw ParamError(file_ + ": missing " + (missing_->size() == 1 ? "key" : std::to_string(missing_->size()) + " keys") +
                   ": " + Join(*missing_) + " (every key is required; the shipped reference files have them all)");
}

}  // namespace birotor
