// SchemaRecorder: the rules the scene reader states, merged per documented mapping. See
// schema_recorder.hpp.
#include "engine/scene/schema_recorder.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

namespace rift {

bool KeyRule::same_but_units(const KeyRule& other) const {
  KeyRule a = *this, b = other;
  a.real.unit = b.real.unit = "";
  a.unit = b.unit = "";
  return a == b;
}

namespace {

KeyRule rule_of(KeyRule::Kind kind) {
  KeyRule r;
  r.kind = kind;
  return r;
}

std::vector<std::string> names(std::span<const std::string_view> options) {
  return {options.begin(), options.end()};
}

}  // namespace

KeyRule number_key(const RealRule& rule, bool nullable) {
  KeyRule r = rule_of(KeyRule::Kind::number);
  r.real = rule;
  r.nullable = nullable;
  return r;
}

KeyRule integer_key(const IntRule& rule) {
  KeyRule r = rule_of(KeyRule::Kind::integer);
  r.integer = rule;
  return r;
}

KeyRule boolean_key() {
  return rule_of(KeyRule::Kind::boolean);
}

KeyRule string_key(bool allow_empty) {
  KeyRule r = rule_of(KeyRule::Kind::string);
  r.allow_empty = allow_empty;
  return r;
}

KeyRule choice_key(std::span<const std::string_view> options) {
  KeyRule r = rule_of(KeyRule::Kind::choice);
  r.options = names(options);
  return r;
}

KeyRule vec3_key(const RealRule& rule) {
  KeyRule r = rule_of(KeyRule::Kind::vec3);
  r.real = rule;
  return r;
}

KeyRule string_list_key() {
  KeyRule r = rule_of(KeyRule::Kind::string_list);
  r.min_items = 1;
  return r;
}

KeyRule choice_list_key(std::span<const std::string_view> options, size_t min_items) {
  KeyRule r = rule_of(KeyRule::Kind::choice_list);
  r.options = names(options);
  r.min_items = min_items;
  return r;
}

KeyRule time_function_key(const std::string& unit) {
  KeyRule r = rule_of(KeyRule::Kind::time_function);
  r.unit = unit;
  return r;
}

KeyRule section_key(const std::string& content) {
  KeyRule r = rule_of(KeyRule::Kind::section);
  r.content = content;
  r.nullable = true;
  return r;
}

KeyRule section_list_key(const std::string& content, size_t min_items) {
  KeyRule r = rule_of(KeyRule::Kind::section_list);
  r.content = content;
  r.min_items = min_items;
  return r;
}

RecordedKey* RecordedObject::find(std::string_view name) {
  auto it = std::find_if(keys.begin(), keys.end(), [&](const RecordedKey& k) { return k.name == name; });
  return it == keys.end() ? nullptr : &*it;
}

const RecordedKey* RecordedObject::find(std::string_view name) const {
  return const_cast<RecordedObject*>(this)->find(name);
}

bool RecordedObject::required(const RecordedKey& k) const {
  if (instances.empty()) return false;
  for (int i : instances)
    if (!k.required_in.count(i) || tested.count({i, k.name})) return false;
  return true;
}

RecordedKey& SchemaRecorder::key(int instance, const std::string& doc_path, std::string_view name) {
  RecordedObject& object = objects_[doc_path];
  if (instance != 0) object.instances.insert(instance);
  if (RecordedKey* k = object.find(name)) return *k;
  object.keys.push_back(RecordedKey{std::string(name), {}, {}, {}, false});
  return object.keys.back();
}

void SchemaRecorder::read(int instance, const std::string& doc_path, std::string_view name, KeyRead what) {
  RecordedKey& k = key(instance, doc_path, name);
  if (std::find(k.rules.begin(), k.rules.end(), what.rule) == k.rules.end()) k.rules.push_back(what.rule);
  if (what.required) k.required_in.insert(instance);
  if (what.default_json)
    k.defaults.insert(*what.default_json);
  else if (!what.required)
    k.default_unknown = true;
}

void SchemaRecorder::known(int instance, const std::string& doc_path, std::string_view name) {
  key(instance, doc_path, name);
}

void SchemaRecorder::presence_tested(int instance, const std::string& doc_path, std::string_view name) {
  objects_[doc_path].tested.emplace(instance, std::string(name));
}

void SchemaRecorder::default_varies(const std::string& doc_path, std::string_view name) {
  key(0, doc_path, name).default_unknown = true;
}

std::string json_number(double v) {
  return nlohmann::json(v).dump();
}
std::string json_integer(int64_t v) {
  return nlohmann::json(v).dump();
}
std::string json_boolean(bool v) {
  return nlohmann::json(v).dump();
}
std::string json_string(const std::string& v) {
  return nlohmann::json(v).dump();
}
std::string json_strings(const std::vector<std::string>& v) {
  return nlohmann::json(v).dump();
}
std::string json_numbers(const std::vector<double>& v) {
  return nlohmann::json(v).dump();
}

}  // namespace rift
