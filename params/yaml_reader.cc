#include "params/yaml_reader.h"

#include <cmath>
#include <sstream>

namespace birotor {
namespace {

std::string Number(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

}  // namespace

std::string RangeText(double min, double max) { return "[" + Number(min) + ", " + Number(max) + "]"; }

YamlSection::YamlSection(std::string file, std::string path, YAML::Node node)
    : file_(std::move(file)), path_(std::move(path)), node_(std::move(node)) {}

namespace {

YAML::Node RequireMapping(YAML::Node root, const std::string& label) {
  if (root.IsNull()) return YAML::Node(YAML::NodeType::Map);
  if (!root.IsMap()) throw ParamError(label + ": the top level must be a mapping of keys");
  return root;
}

ParamError SyntaxError(const std::string& label, const YAML::Exception& e) {
  return ParamError(label + ": not valid YAML at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
}

}  // namespace

YAML::Node LoadYamlMapping(const std::string& file) {
  try {
    return RequireMapping(YAML::LoadFile(file), file);
  } catch (const YAML::BadFile&) {
    throw ParamError(file + ": cannot open the file");
  } catch (const YAML::Exception& e) {
    throw SyntaxError(file, e);
  }
}

YAML::Node ParseYamlMapping(const std::string& text, const std::string& label) {
  try {
    return RequireMapping(YAML::Load(text), label);
  } catch (const YAML::Exception& e) {
    throw SyntaxError(label, e);
  }
}

YamlSection YamlSection::LoadFile(const std::string& file) { return YamlSection(file, "", LoadYamlMapping(file)); }

YamlSection YamlSection::LoadString(const std::string& text, const std::string& file) {
  return YamlSection(file, "", ParseYamlMapping(text, file));
}

std::string YamlSection::KeyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

void YamlSection::Fail(const std::string& key, const std::string& problem, const std::string& allowed) const {
  std::string message = file_ + ": key '" + KeyPath(key) + "': " + problem;
  if (!allowed.empty()) message += " (allowed: " + allowed + ")";
  throw ParamError(message);
}

bool YamlSection::Has(const std::string& key) const { return node_.IsMap() && node_[key].IsDefined(); }

YAML::Node YamlSection::Get(const std::string& key) {
  read_keys_.insert(key);
  if (!node_.IsMap()) return YAML::Node();
  return node_[key];
}

void YamlSection::Double(const std::string& key, double min, double max, double* value) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return;
  double x = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, x))
    Fail(key, "expected a number, got '" + (n.IsScalar() ? n.Scalar() : std::string("a structure")) + "'",
         RangeText(min, max));
  if (!std::isfinite(x) || x < min || x > max)
    Fail(key, "value " + Number(x) + " is out of range", RangeText(min, max));
  *value = x;
}

void YamlSection::RequiredDouble(const std::string& key, double min, double max, double* value) {
  if (!Has(key)) Fail(key, "missing", "a number in " + RangeText(min, max));
  Double(key, min, max, value);
}

void YamlSection::Int(const std::string& key, int64_t min, int64_t max, int64_t* value) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return;
  int64_t x = 0;
  if (!n.IsScalar() || !YAML::convert<int64_t>::decode(n, x))
    Fail(key, "expected an integer, got '" + (n.IsScalar() ? n.Scalar() : std::string("a structure")) + "'",
         RangeText(static_cast<double>(min), static_cast<double>(max)));
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
  if (!n.IsDefined() || n.IsNull()) return;
  bool x = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, x))
    Fail(key, "expected true or false, got '" + (n.IsScalar() ? n.Scalar() : std::string("a structure")) + "'",
         "true, false");
  *value = x;
}

void YamlSection::String(const std::string& key, const std::vector<std::string>& allowed, std::string* value) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return;
  std::string list;
  for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
  if (!n.IsScalar()) Fail(key, "expected a string", list);
  const std::string x = n.Scalar();
  bool ok = allowed.empty();
  for (const std::string& a : allowed) ok = ok || (a == x);
  if (!ok) Fail(key, "unknown value '" + x + "'", list);
  *value = x;
}

void YamlSection::AnyString(const std::string& key, std::string* value) { String(key, {}, value); }

void YamlSection::DoubleArray(const std::string& key, int count, double min, double max, double* values) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return;
  const std::string allowed = std::to_string(count) + " numbers, each in " + RangeText(min, max);
  if (!n.IsSequence() || static_cast<int>(n.size()) != count)
    Fail(key, "expected a list of " + std::to_string(count), allowed);
  for (int i = 0; i < count; ++i) {
    double x = 0;
    if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], x))
      Fail(key, "element " + std::to_string(i) + " is not a number", allowed);
    if (!std::isfinite(x) || x < min || x > max)
      Fail(key, "element " + std::to_string(i) + " = " + Number(x) + " is out of range", allowed);
    values[i] = x;
  }
}

void YamlSection::DoubleList(const std::string& key, double min, double max, std::vector<double>* values) {
  const YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return;
  const std::string allowed = "a list of numbers, each in " + RangeText(min, max);
  if (!n.IsSequence()) Fail(key, "expected a list", allowed);
  values->clear();
  for (size_t i = 0; i < n.size(); ++i) {
    double x = 0;
    if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], x))
      Fail(key, "element " + std::to_string(i) + " is not a number", allowed);
    if (!std::isfinite(x) || x < min || x > max)
      Fail(key, "element " + std::to_string(i) + " = " + Number(x) + " is out of range", allowed);
    values->push_back(x);
  }
}

YamlSection YamlSection::Section(const std::string& key) {
  YAML::Node n = Get(key);
  if (!n.IsDefined() || n.IsNull()) return YamlSection(file_, KeyPath(key), YAML::Node(YAML::NodeType::Map));
  if (!n.IsMap()) Fail(key, "expected a mapping of keys", "");
  return YamlSection(file_, KeyPath(key), n);
}

std::vector<YamlSection> YamlSection::SectionList(const std::string& key) {
  YAML::Node n = Get(key);
  std::vector<YamlSection> out;
  if (!n.IsDefined() || n.IsNull()) return out;
  if (!n.IsSequence()) Fail(key, "expected a list", "");
  for (size_t i = 0; i < n.size(); ++i) {
    const std::string path = KeyPath(key) + "[" + std::to_string(i) + "]";
    if (!n[i].IsMap()) throw ParamError(file_ + ": key '" + path + "': expected a mapping of keys");
    out.emplace_back(file_, path, n[i]);
  }
  return out;
}

void YamlSection::Finish() const {
  if (!node_.IsMap()) return;
  for (const auto& item : node_) {
    const std::string key = item.first.as<std::string>();
    if (read_keys_.count(key) == 0) {
      std::string known;
      for (const std::string& k : read_keys_) known += (known.empty() ? "" : ", ") + k;
      throw ParamError(file_ + ": key '" + KeyPath(key) + "': unknown key (allowed: " + known + ")");
    }
  }
}

}  // namespace birotor
