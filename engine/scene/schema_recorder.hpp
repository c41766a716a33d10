#pragma once
// What the scene reader states about each key while it reads, collected for the JSON Schema of the
// scene format (scene_schema.hpp). A ReadContext may carry a SchemaRecorder; every MapReader accessor
// then reports the key's documented path, its kind and rule, and whether it is required or its default.
// Each MapReader is one instance of a mapping (a section, a list item); a key is required in the schema
// only if every instance of its mapping that touched any key read it as required, and none tested
// whether the scene gives it (MapReader::has): a reader that asks handles the key's absence, as for
// the variants of a mapping (mesh.generate's box or cylinder, a well's rate or pressure).
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/yaml_reader.hpp"

namespace rift {

// The rule one accessor applies to a key's value.
struct KeyRule {
  enum class Kind {
    number,         // RealRule
    integer,        // IntRule
    boolean,        // true or false
    string,         // any scalar; non-empty unless allow_empty
    choice,         // one of `options`
    vec3,           // 3 numbers, each under `real`
    string_list,    // at least one non-empty string
    choice_list,    // distinct `options`, at least `min_items`
    time_function,  // a number, {ramp: {...}} or {table: [[t, v], ...]} in `unit`
    section,        // a mapping whose keys are documented under `content`
    section_list,   // a list of such mappings, at least `min_items`
  };
  Kind kind = Kind::number;
  RealRule real;                     // number, vec3
  IntRule integer;                   // integer
  bool allow_empty = false;          // string
  bool nullable = false;             // number read as optional (null: not set); section (null: empty)
  std::vector<std::string> options;  // choice, choice_list
  size_t min_items = 0;              // string_list, choice_list, section_list
  std::string unit;                  // time_function
  std::string content;               // section, section_list: the documented path of its keys

  bool operator==(const KeyRule&) const = default;
  // Equal but for units, which a JSON Schema cannot state (they go to the description).
  bool same_but_units(const KeyRule& other) const;
};

// The rule of each accessor of MapReader (yaml_reader.hpp).
KeyRule number_key(const RealRule& rule, bool nullable = false);
KeyRule integer_key(const IntRule& rule);
KeyRule boolean_key();
KeyRule string_key(bool allow_empty);
KeyRule choice_key(std::span<const std::string_view> options);
KeyRule vec3_key(const RealRule& rule);
KeyRule string_list_key();
KeyRule choice_list_key(std::span<const std::string_view> options, size_t min_items);
KeyRule time_function_key(const std::string& unit);
KeyRule section_key(const std::string& content);  // null reads as an empty mapping
KeyRule section_list_key(const std::string& content, size_t min_items);

// What a reading said about a key: its rule, and required or its default (JSON text; none when the
// reader computes it, e.g. from another key).
struct KeyRead {
  KeyRule rule;
  bool required = false;
  std::optional<std::string> default_json;
};

// Every key of one documented mapping, merged over all the instances read.
struct RecordedKey {
  std::string name;
  std::vector<KeyRule> rules;      // distinct rules, in the order first seen; empty: only declared
  std::set<int> required_in;       // instances that read it as required
  std::set<std::string> defaults;  // distinct defaults (JSON text)
  bool default_unknown = false;    // some optional reading had no default to state
};

struct RecordedObject {
  std::set<int> instances;                       // instances that touched at least one key
  std::vector<RecordedKey> keys;                 // in the order first seen (the reading order)
  std::set<std::pair<int, std::string>> tested;  // (instance, key) whose presence was asked for
  RecordedKey* find(std::string_view name);
  const RecordedKey* find(std::string_view name) const;
  // Every instance read `k` as required and none asked whether it is given.
  bool required(const RecordedKey& k) const;
};

class SchemaRecorder {
 public:
  int new_instance() { return ++instances_; }
  // A key read with a rule, in instance `instance` of the mapping documented at `doc_path`.
  void read(int instance, const std::string& doc_path, std::string_view key, KeyRead what);
  // A key known there without being read (declare, forbid, or a shape the scene does not use).
  void known(int instance, const std::string& doc_path, std::string_view key);
  // The reader asked whether the scene gives the key (MapReader::has).
  void presence_tested(int instance, const std::string& doc_path, std::string_view key);
  // The key's default depends on other values: no default is stated for it.
  void default_varies(const std::string& doc_path, std::string_view key);

  // Documented mapping paths ("" the top level, "solid.materials", "ramp") and their keys.
  const std::map<std::string, RecordedObject>& objects() const { return objects_; }

 private:
  RecordedKey& key(int instance, const std::string& doc_path, std::string_view name);

  int instances_ = 0;
  std::map<std::string, RecordedObject> objects_;
};

// JSON text of a default value, as KeyRead::default_json holds it.
std::string json_number(double v);
std::string json_integer(int64_t v);
std::string json_boolean(bool v);
std::string json_string(const std::string& v);
std::string json_strings(const std::vector<std::string>& v);
std::string json_numbers(const std::vector<double>& v);

}  // namespace rift
