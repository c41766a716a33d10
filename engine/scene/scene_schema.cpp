// The scene format's JSON Schema from what the reader recorded while reading the docs' complete
// examples. See scene_schema.hpp.
#include "engine/scene/scene_schema.hpp"

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "engine/scene/load_scene.hpp"
#include "engine/scene/schema_recorder.hpp"

namespace rift {
namespace {

using Json = nlohmann::ordered_json;  // keys in reading order, as the docs list them

std::string join_path(const std::string& base, const std::string& key) {
  return base.empty() ? key : base + "." + key;
}

Json number_schema(const RealRule& r, bool nullable) {
  Json s;
  s["type"] = nullable ? Json::array({"number", "null"}) : Json("number");
  if (r.min) s[r.min_open ? "exclusiveMinimum" : "minimum"] = *r.min;
  if (r.max) s[r.max_open ? "exclusiveMaximum" : "maximum"] = *r.max;
  return s;
}

Json integer_schema(const IntRule& r) {
  Json s;
  s["type"] = "integer";
  if (r.min != INT64_MIN) s["minimum"] = r.min;
  if (r.max != INT64_MAX) s["maximum"] = r.max;
  return s;
}

// The reader takes any scalar as a string's text (docs: "string: any scalar"), and a YAML loader makes
// `name: 2024` a number: the schema accepts what the reader accepts.
Json string_schema(bool allow_empty) {
  Json s;
  s["type"] = Json::array({"string", "number", "boolean"});
  if (!allow_empty) s["minLength"] = 1;
  return s;
}

Json at_least(Json list, size_t min_items) {
  if (min_items > 0) list["minItems"] = min_items;
  return list;
}

// The forms read_time_function (read_time_function.cpp) accepts: a number, {ramp: {...}} with the
// ramp's recorded keys, or {table: [[t, v], ...]} of at least two pairs.
Json time_function_schema(Json ramp, const std::string& table_description) {
  Json table;
  table["description"] = table_description;
  table["type"] = "array";
  table["minItems"] = 2;
  table["items"] = {{"type", "array"}, {"minItems", 2}, {"maxItems", 2}, {"items", {{"type", "number"}}}};
  auto form = [](const std::string& key, Json value) {
    Json s;
    s["type"] = "object";
    s["properties"][key] = std::move(value);
    s["required"] = Json::array({key});
    s["additionalProperties"] = false;
    return s;
  };
  Json s;
  s["anyOf"] = Json::array({Json{{"type", "number"}}, form("ramp", std::move(ramp)), form("table", table)});
  return s;
}

// Writes the schema of the recorded mappings, each key described by its docs table row.
class SchemaWriter {
 public:
  SchemaWriter(const SchemaRecorder& recorder, std::map<std::string, DocumentedKey> docs)
      : objects_(recorder.objects()), docs_(std::move(docs)) {
    // A mapping read from more than one place under another path (fluid.mesh reads as mesh) is written
    // once, in definitions, and referred to from each place.
    for (const auto& [path, object] : objects_)
      for (const RecordedKey& k : object.keys)
        for (const KeyRule& r : k.rules)
          if ((r.kind == KeyRule::Kind::section || r.kind == KeyRule::Kind::section_list) &&
              r.content != join_path(path, k.name))
            shared_.insert(r.content);
  }

  Json root() {
    Json s;
    s["$schema"] = "http://json-schema.org/draft-07/schema#";
    s["title"] = "Rift scene";
    s["description"] =
        "A Rift scene: one YAML document describing a run (docs/scene-format.md). Made by `rift schema` "
        "from the scene reader's own rules; each key is described by its meaning in docs/scene-format.md, "
        "its unit in brackets.";
    s.update(object_schema("", false));
    Json definitions;
    definitions["time_function"] = time_function();
    for (const std::string& path : shared_) definitions[path] = object_schema(path, true);
    s["definitions"] = std::move(definitions);
    return s;
  }

  size_t keys() const { return described_.size(); }

 private:
  Json object_schema(const std::string& path, bool nullable) {
    Json s;
    s["type"] = nullable ? Json::array({"object", "null"}) : Json("object");
    const auto it = objects_.find(path);
    if (it == objects_.end()) return s;
    const RecordedObject& object = it->second;
    Json properties = Json::object(), required = Json::array();
    for (const RecordedKey& k : object.keys) {
      properties[k.name] = key_schema(path, k);
      // Required only where every mapping of this path that was read needs the key: a key required
      // for one variant (a pressure boundary's value) is optional in the schema.
      if (object.required(k)) required.push_back(k.name);
    }
    s["properties"] = std::move(properties);
    if (!required.empty()) s["required"] = std::move(required);
    s["additionalProperties"] = false;
    return s;
  }

  Json key_schema(const std::string& path, const RecordedKey& k) {
    const std::string key_path = join_path(path, k.name);
    described_.insert(key_path);
    Json rule = merged(k.rules);
    // Draft-07 ignores the siblings of a $ref: the reference goes into allOf beside the description.
    if (rule.contains("$ref")) rule = Json{{"allOf", Json::array({rule})}};
    Json s;
    s["description"] = description(key_path, k.rules);
    s.update(rule);
    if (k.defaults.size() == 1 && !k.default_unknown) s["default"] = Json::parse(*k.defaults.begin());
    return s;
  }

  // A key read with different rules in different places (a boundary's direction in m/s for a velocity,
  // in Pa for a traction) gets one schema when they differ only in units, which a schema cannot state;
  // rules that differ otherwise become anyOf: which place applies depends on other keys (the boundary's
  // type), which the schema does not follow, and a union never refuses what the reader accepts.
  Json merged(const std::vector<KeyRule>& rules) {
    std::vector<const KeyRule*> distinct;
    for (const KeyRule& r : rules) {
      bool seen = false;
      for (const KeyRule* d : distinct) seen = seen || d->same_but_units(r);
      if (!seen) distinct.push_back(&r);
    }
    if (distinct.empty()) return Json::object();  // declared only: any value (the docs test flags it)
    if (distinct.size() == 1) return rule_schema(*distinct.front());
    Json any = Json::array();
    for (const KeyRule* d : distinct) any.push_back(rule_schema(*d));
    return Json{{"anyOf", std::move(any)}};
  }

  Json rule_schema(const KeyRule& r) {
    using Kind = KeyRule::Kind;
    switch (r.kind) {
      case Kind::number:
        return number_schema(r.real, r.nullable);
      case Kind::integer:
        return integer_schema(r.integer);
      case Kind::boolean:
        return Json{{"type", "boolean"}};
      case Kind::string:
        return string_schema(r.allow_empty);
      case Kind::choice:
        return Json{{"enum", r.options}};
      case Kind::vec3:
        return Json{
            {"type", "array"}, {"items", number_schema(r.real, false)}, {"minItems", 3}, {"maxItems", 3}};
      case Kind::string_list:
        return Json{{"type", "array"}, {"items", string_schema(false)}, {"minItems", 1}};
      case Kind::choice_list:
        return at_least(Json{{"type", "array"}, {"items", {{"enum", r.options}}}, {"uniqueItems", true}},
                        r.min_items);
      case Kind::time_function:
        return Json{{"$ref", "#/definitions/time_function"}};
      case Kind::section:
        return mapping(r.content, true);
      case Kind::section_list:
        return at_least(Json{{"type", "array"}, {"items", mapping(r.content, false)}}, r.min_items);
    }
    return Json::object();
  }

  // A mapping documented at `content`: written here, or referred to when it is shared (always nullable
  // there, as a section is; a list item must be a mapping).
  Json mapping(const std::string& content, bool nullable) {
    if (!shared_.count(content)) return object_schema(content, nullable);
    Json ref{{"$ref", "#/definitions/" + content}};
    if (nullable) return ref;
    return Json{{"allOf", Json::array({ref, Json{{"type", "object"}}})}};
  }

  // Time-function keys are documented once for all of them, from "ramp" and "table".
  Json time_function() {
    Json ramp;
    ramp["description"] = description("ramp", {});
    ramp.update(object_schema("ramp", false));
    described_.insert("ramp");
    described_.insert("table");
    return time_function_schema(std::move(ramp), description("table", {}));
  }

  // The docs' meaning of the key, and its unit in brackets (the docs' unit column, else the reader's).
  std::string description(const std::string& key_path, const std::vector<KeyRule>& rules) const {
    const auto it = docs_.find(key_path);
    std::string text, unit;
    if (it != docs_.end()) {
      text = it->second.meaning;
      unit = it->second.unit;
    } else if (!rules.empty()) {
      unit =
          rules.front().kind == KeyRule::Kind::time_function ? rules.front().unit : rules.front().real.unit;
    }
    if (!unit.empty() && unit != "-") text += (text.empty() ? "[" : " [") + unit + "]";
    return text;
  }

  const std::map<std::string, RecordedObject>& objects_;
  const std::map<std::string, DocumentedKey> docs_;
  std::set<std::string> shared_;     // mapping paths written in definitions
  std::set<std::string> described_;  // key paths written
};

}  // namespace

SceneSchema scene_schema(std::string_view doc) {
  SceneSchema out;
  SchemaRecorder recorder;
  const std::vector<std::string> examples = complete_examples(doc);
  if (examples.empty())
    out.problems.push_back("docs/scene-format.md: no complete example to read the keys from");
  for (size_t i = 0; i < examples.size(); ++i) {
    const std::string label = "docs/scene-format.md (complete example " + std::to_string(i + 1) + ")";
    const SceneLoadResult r = read_scene_text(examples[i], label, ".", {}, &recorder);
    for (const auto& e : r.errors) out.problems.push_back(e.format());
  }
  SchemaWriter writer(recorder, documented_keys(doc));
  out.json = writer.root().dump(2) + "\n";
  out.keys = writer.keys();
  return out;
}

}  // namespace rift
