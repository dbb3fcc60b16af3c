// One table per option struct: each row names a key of the struct's YAML
// section, the field it fills and its allowed range. The generic reader
// ReadOptions walks the table, so the keys a file may hold, the reader and
// the "unknown key" check (YamlSection::Finish, which knows every key read)
// come from the one list; the defaults are the struct's own member
// initialisers. Cross-field rules (hysteresis, a rate that must divide the
// step) stay next to the call, after the table is read.
#pragma once

#include <string>
#include <vector>

#include "params/yaml_reader.h"

namespace birotor {

template <typename Struct>
struct OptionKey {
  enum class Kind { kReal, kInteger, kFlag, kText, kRealPair };
  const char* name = nullptr;
  Kind kind = Kind::kReal;
  double min = 0.0;  // numbers: allowed range, both ends included
  double max = 0.0;
  double Struct::*real = nullptr;
  int Struct::*integer = nullptr;
  bool Struct::*flag = nullptr;
  std::string Struct::*text = nullptr;
  double (Struct::*pair)[2] = nullptr;
  std::vector<std::string> choices;  // text: the allowed values (empty: any)
};

template <typename Struct>
using OptionTable = std::vector<OptionKey<Struct>>;

template <typename Struct>
OptionKey<Struct> Row(const char* name, typename OptionKey<Struct>::Kind kind, double min, double max) {
  OptionKey<Struct> key;
  key.name = name;
  key.kind = kind;
  key.min = min;
  key.max = max;
  return key;
}

template <typename Struct>
OptionKey<Struct> Real(const char* name, double Struct::*field, double min, double max) {
  OptionKey<Struct> key = Row<Struct>(name, OptionKey<Struct>::Kind::kReal, min, max);
  key.real = field;
  return key;
}

template <typename Struct>
OptionKey<Struct> Integer(const char* name, int Struct::*field, int min, int max) {
  OptionKey<Struct> key = Row<Struct>(name, OptionKey<Struct>::Kind::kInteger, min, max);
  key.integer = field;
  return key;
}

template <typename Struct>
OptionKey<Struct> Flag(const char* name, bool Struct::*field) {
  OptionKey<Struct> key = Row<Struct>(name, OptionKey<Struct>::Kind::kFlag, 0, 0);
  key.flag = field;
  return key;
}

template <typename Struct>
OptionKey<Struct> Text(const char* name, std::string Struct::*field, std::vector<std::string> choices = {}) {
  OptionKey<Struct> key = Row<Struct>(name, OptionKey<Struct>::Kind::kText, 0, 0);
  key.text = field;
  key.choices = std::move(choices);
  return key;
}

// A two-element array (one value per arm or rotor), each in [min, max].
template <typename Struct>
OptionKey<Struct> RealPair(const char* name, double (Struct::*field)[2], double min, double max) {
  OptionKey<Struct> key = Row<Struct>(name, OptionKey<Struct>::Kind::kRealPair, min, max);
  key.pair = field;
  return key;
}

// Reads every key of the table from section into *options (each required,
// each range-checked; ParamError names the file, the key and the range).
template <typename Struct>
void ReadOptions(YamlSection& section, const OptionTable<Struct>& table, Struct* options) {
  using Kind = typename OptionKey<Struct>::Kind;
  for (const OptionKey<Struct>& key : table) {
    switch (key.kind) {
      case Kind::kReal:
        section.Double(key.name, key.min, key.max, &(options->*key.real));
        break;
      case Kind::kInteger:
        section.Int(key.name, static_cast<int>(key.min), static_cast<int>(key.max), &(options->*key.integer));
        break;
      case Kind::kFlag:
        section.Bool(key.name, &(options->*key.flag));
        break;
      case Kind::kText:
        section.String(key.name, key.choices, &(options->*key.text));
        break;
      case Kind::kRealPair:
        section.DoubleArray(key.name, 2, key.min, key.max, options->*key.pair);
        break;
    }
  }
}

// ReadOptions, then Finish: the section holds exactly the table's keys.
template <typename Struct>
void ReadOptionSection(YamlSection section, const OptionTable<Struct>& table, Struct* options) {
  ReadOptions(section, table, options);
  section.Finish();
}

}  // namespace birotor
