#pragma once
// Typed, checked access to a scene's YAML tree. Each accessor states the unit, default and range of a
// key; anything else becomes a diagnostic with file:line:column, key path, what was expected and what
// was found, and reading goes on so one pass reports every problem of a file. A MapReader remembers
// which keys were asked for, so finish() can name unknown keys (with a "did you mean") and the docs
// test can check that every key the reader knows is documented. With a SchemaRecorder on the context,
// every accessor also reports the key's rule (schema_recorder.hpp), from which `rift schema` is made.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/resolved_scene.hpp"
#include "engine/scene/scene_diagnostic.hpp"
#include "engine/scene/time_function.hpp"
#include "engine/scene/yaml_tree.hpp"

namespace rift {

class SchemaRecorder;
struct KeyRule;

// Diagnostics and bookkeeping shared by every reader of one scene.
class ReadContext {
 public:
  ReadContext() = default;
  explicit ReadContext(SchemaRecorder* recorder) : recorder_(recorder) {}

  void error(const SourceLocation& where, std::string key_path, std::string expected, std::string found,
             std::string hint = {});
  // Records a key path without list indices (e.g. "solid.materials.density") as known to the reader.
  void consumed(const std::string& doc_path) { consumed_.insert(doc_path); }
  const std::vector<SceneDiagnostic>& errors() const { return errors_; }
  const std::set<std::string>& consumed_keys() const { return consumed_; }
  SchemaRecorder* recorder() const { return recorder_; }  // null: nothing is recorded
  // What the readers read, value by value (resolved_scene.hpp): the resolved scene.
  ResolvedNode& resolved() { return resolved_; }

 private:
  std::vector<SceneDiagnostic> errors_;
  ResolvedNode resolved_;
  std::set<std::string> consumed_;
  SchemaRecorder* recorder_ = nullptr;
};

// The accepted range of a real number and its unit, as error messages state them.
struct RealRule {
  std::string unit;  // "" for a dimensionless number
  std::optional<double> min, max;
  bool min_open = false, max_open = false;  // exclusive bounds

  bool accepts(double v) const;
  std::string describe() const;  // e.g. "a number in Pa, > 0", "a number, in [0, 0.5)"
  bool operator==(const RealRule&) const = default;
};
RealRule any_real(std::string unit);
RealRule positive(std::string unit);      // > 0
RealRule non_negative(std::string unit);  // >= 0

struct IntRule {
  int64_t min = INT64_MIN, max = INT64_MAX;
  std::string describe() const;  // e.g. "an integer >= 1"
  bool operator==(const IntRule&) const = default;
};

// Readers of one value at `path`; each reports a diagnostic and returns nullopt when the value is wrong.
std::optional<double> read_real(ReadContext&, const YamlNode&, const std::string& path, const RealRule&);
std::optional<int64_t> read_integer(ReadContext&, const YamlNode&, const std::string& path, const IntRule&);
std::optional<bool> read_boolean(ReadContext&, const YamlNode&, const std::string& path);
std::optional<std::string> read_string(ReadContext&, const YamlNode&, const std::string& path,
                                       bool allow_empty = false);
std::optional<size_t> read_choice(ReadContext&, const YamlNode&, const std::string& path,
                                  std::span<const std::string_view> options);
std::optional<std::array<double, 3>> read_vec3(ReadContext&, const YamlNode&, const std::string& path,
                                               const RealRule&);
// number, {ramp: {...}} or {table: [[t, v], ...]}; see read_time_function.cpp.
std::optional<TimeFunction> read_time_function(ReadContext&, const YamlNode&, const std::string& path,
                                               const std::string& unit);

// How a found value is shown in messages: "'12abc'", "the string \"3\"", "a list of 2 items", ...
std::string describe_found(const YamlNode&);
// "a, b, c"
std::string join_names(std::span<const std::string_view> names);

// One value of an enum and its spelling in a scene file: the reader maps names to values through one
// table (scene_names.hpp) and the resolved scene records the name read, so no enum's order matters.
template <class E>
struct Named {
  E value;
  std::string_view name;
};

template <class E, size_t N>
std::string_view name_of(const std::array<Named<E>, N>& table, E value) {
  for (const Named<E>& n : table)
    if (n.value == value) return n.name;
  return "?";
}

// One YAML mapping (a scene section or a list item) being read.
class MapReader {
 public:
  // `node` null: the section is absent or empty; keys take their defaults and required ones are
  // reported at `where`. `doc_path` is `path` without list indices, for the documentation check.
  MapReader(ReadContext& ctx, const YamlNode* node, std::string path, std::string doc_path,
            SourceLocation where);

  // Present in the file (null values count). Asking tells the recorder that the reader handles the
  // key's absence: it is not required (schema_recorder.hpp).
  bool has(std::string_view key) const;
  bool ok(std::string_view key) const;  // read without a diagnostic
  std::string key_path(std::string_view key) const;
  std::string doc_key_path(std::string_view key) const;  // without list indices, as the docs name it
  SourceLocation where(std::string_view key) const;      // the value's location, else the section's
  const SourceLocation& where() const { return where_; }
  std::string found(std::string_view key) const;  // describe_found of the value
  ReadContext& context() { return *ctx_; }

  // `fallback` nullopt: the key is required.
  double real(std::string_view key, const RealRule& rule, std::optional<double> fallback);
  std::optional<double> optional_real(std::string_view key, const RealRule& rule);  // absent/null: nullopt
  int64_t integer(std::string_view key, const IntRule& rule, std::optional<int64_t> fallback);
  bool boolean(std::string_view key, std::optional<bool> fallback);
  std::string string(std::string_view key, std::optional<std::string> fallback, bool allow_empty = false);
  size_t choice(std::string_view key, std::span<const std::string_view> options,
                std::optional<size_t> fallback);
  // The same, for an enum named by `table`.
  template <class E, size_t N>
  E choice(std::string_view key, const std::array<Named<E>, N>& table, std::optional<E> fallback) {
    std::array<std::string_view, N> names;
    std::optional<size_t> fallback_index;
    for (size_t i = 0; i < N; ++i) {
      names[i] = table[i].name;
      if (fallback && table[i].value == *fallback) fallback_index = i;
    }
    return table[choice(key, names, fallback_index)].value;
  }
  std::array<double, 3> vec3(std::string_view key, const RealRule& rule,
                             std::optional<std::array<double, 3>> fallback);
  // A list of non-empty strings with at least one item.
  std::vector<std::string> string_list(std::string_view key, std::vector<std::string> fallback);
  // A list of distinct options (indices into `options`).
  std::vector<size_t> choice_list(std::string_view key, std::span<const std::string_view> options,
                                  std::vector<size_t> fallback, size_t min_items);
  TimeFunction time_function(std::string_view key, const std::string& unit,
                             std::optional<TimeFunction> fallback);
  // A nested mapping; a null value reads as an empty one. Not a mapping, or required and absent:
  // reported here, and the returned reader stays silent so the mistake is not repeated per key (as it
  // does in a silent reader).
  // `doc_path`: the documented path of its keys when they are another section's (fluid.mesh reads as mesh).
  MapReader section(std::string_view key, bool required, const std::string* doc_path = nullptr);
  const std::string& path() const { return path_; }
  // A list of mappings. Absent: empty (an error when min_items > 0).
  std::vector<MapReader> section_list(std::string_view key, size_t min_items);

  void forbid(std::string_view key, const std::string& why);  // a known key that must be absent here
  void declare(std::string_view key);  // a known key this pass does not read (still counts as consumed)
  // The default just read for `key` depends on other values (10 x young, block<i>): the schema states none.
  void default_varies(std::string_view key);
  // A silent view of this mapping for the keys of a variant the scene does not use (a cylinder's keys
  // in a box scene, theta when scheme is given): reading a key through it declares the key here and
  // reports its rule to the recorder as not required here; every accessor returns its fallback and
  // nothing is reported to the user. Its section() is a silenced reader and its section_list() one
  // silenced item, so the caller's item reader declares the item's keys. Use it at once: it refers to
  // this reader.
  MapReader unused();
  // A diagnostic about the key's value (for checks across keys), found = describe_found(value).
  void error(std::string_view key, std::string expected, std::string hint = {});
  // Records this mapping's keys as the resolved scene's top level (ReadContext::resolved): the document's
  // reader. Sections and list items of a recording reader record under their key.
  void record_values_at_root();
  // Records `text` as the resolved value of `key`: every accessor does so with the value it returns, and
  // a caller sets the value a key stands for when it is not the one read (a path made absolute). Nothing
  // is recorded by a silent reader or a view of unused keys.
  void resolved_value(std::string_view key, std::string text);
  // Reports keys never asked for (typos) and duplicate keys. Call once, after every key was read.
  void finish();

  // A reader for a mapping that was reported as wrong already: every accessor returns its fallback.
  static MapReader silenced(ReadContext& ctx, std::string path, std::string doc_path, SourceLocation where);
  bool silent() const { return silent_; }

 private:
  const YamlEntry* lookup(std::string_view key);  // declares the key; first entry or null
  // For an absent or null key: reports it if required; true when the caller should use the fallback.
  bool absent(std::string_view key, const YamlEntry* e, bool required, const std::string& expected);
  void failed(std::string_view key) { failed_.insert(std::string(key)); }
  // Reports the key's rule to the context's recorder, when there is one.
  void record(std::string_view key, const KeyRule& rule, bool required,
              std::optional<std::string> default_json);

  // Where this mapping's values go in the resolved scene, made when its first value is recorded, so a
  // section opened but not read (an absent optional one) leaves no trace.
  struct ResolvedPlace {
    std::shared_ptr<ResolvedPlace> parent;
    std::string key;  // the entry in the parent mapping
    long item = -1;   // >= 0: item of the parent entry's list
    ResolvedNode* node = nullptr;
    ResolvedNode& get();
  };
  bool records_values() const;  // resolved_value records (a place, not silent, not a view of unused keys)
  std::shared_ptr<ResolvedPlace> child_place(std::string_view key, long item) const;
  // The lists' values as read (the accessors record them).
  std::vector<std::string> string_list_value(std::string_view key, const YamlEntry* e,
                                             std::vector<std::string> fallback);
  std::vector<size_t> choice_list_value(std::string_view key, const YamlEntry* e,
                                        std::span<const std::string_view> options,
                                        std::vector<size_t> fallback, size_t min_items);
  // `child`, a section or list item read at `key`, recording its values there.
  MapReader placed(MapReader child, std::string_view key, long item = -1) const;

  ReadContext* ctx_;
  const YamlNode* node_;
  std::shared_ptr<ResolvedPlace> place_;  // null: nothing recorded
  std::string path_, doc_path_;
  SourceLocation where_;
  std::vector<std::string> known_;
  std::set<std::string, std::less<>> failed_;
  bool silent_ = false;          // the mapping itself is wrong and was reported already
  int instance_ = 0;             // this mapping's number for the recorder (0: no recorder)
  MapReader* origin_ = nullptr;  // unused(): the reader whose keys this view declares
};

}  // namespace rift
