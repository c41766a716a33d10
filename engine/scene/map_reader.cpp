// MapReader: a YAML mapping read key by key, with defaults, required keys, unknown-key and
// duplicate-key checks. See yaml_reader.hpp.
#include <algorithm>
#include <map>

#include "engine/scene/number_text.hpp"
#include "engine/scene/schema_recorder.hpp"
#include "engine/scene/suggest.hpp"
#include "engine/scene/yaml_reader.hpp"

namespace rift {
namespace {

std::string join_path(const std::string& base, std::string_view key) {
  return base.empty() ? std::string(key) : base + "." + std::string(key);
}

const std::string kMissing = "nothing (the key is missing)";

const YamlEntry* find_entry(const YamlNode* node, std::string_view key) {
  if (!node) return nullptr;
  for (const auto& e : node->entries)
    if (e.key == key) return &e;
  return nullptr;
}

// Where messages about an entry's value point. A block mapping starts at its first inner key, which
// would blame a child; the entry's own key is the better place.
const SourceLocation& value_where(const YamlEntry& e) {
  return e.value.kind == YamlNode::Kind::mapping ? e.key_where : e.value.where;
}

}  // namespace

MapReader::MapReader(ReadContext& ctx, const YamlNode* node, std::string path, std::string doc_path,
                     SourceLocation where)
    : ctx_(&ctx),
      node_(node),
      path_(std::move(path)),
      doc_path_(std::move(doc_path)),
      where_(std::move(where)),
      instance_(ctx.recorder() ? ctx.recorder()->new_instance() : 0) {}

MapReader MapReader::silenced(ReadContext& ctx, std::string path, std::string doc_path,
                              SourceLocation where) {
  MapReader r(ctx, nullptr, std::move(path), std::move(doc_path), std::move(where));
  r.silent_ = true;
  return r;
}

std::string MapReader::key_path(std::string_view key) const {
  return join_path(path_, key);
}

std::string MapReader::doc_key_path(std::string_view key) const {
  return join_path(doc_path_, key);
}

bool MapReader::has(std::string_view key) const {
  if (ctx_->recorder()) ctx_->recorder()->presence_tested(instance_, doc_path_, key);
  return find_entry(node_, key) != nullptr;
}

bool MapReader::ok(std::string_view key) const {
  return !silent_ && failed_.find(key) == failed_.end();
}

SourceLocation MapReader::where(std::string_view key) const {
  const YamlEntry* e = find_entry(node_, key);
  return e ? value_where(*e) : where_;
}

std::string MapReader::found(std::string_view key) const {
  const YamlEntry* e = find_entry(node_, key);
  return e ? describe_found(e->value) : kMissing;
}

ResolvedNode& MapReader::ResolvedPlace::get() {
  if (node) return *node;
  ResolvedNode& in = parent->get();
  node = item >= 0 ? &in.entry(key, ResolvedNode::Kind::list).item(static_cast<size_t>(item))
                   : &in.entry(key, ResolvedNode::Kind::mapping);
  return *node;
}

void MapReader::record_values_at_root() {
  place_ = std::make_shared<ResolvedPlace>();
  place_->node = &ctx_->resolved();
}

bool MapReader::records_values() const {
  return place_ && !silent_ && !origin_;
}

void MapReader::resolved_value(std::string_view key, std::string text) {
  if (!records_values()) return;
  place_->get().entry(key, ResolvedNode::Kind::scalar).text = std::move(text);
}

MapReader MapReader::placed(MapReader child, std::string_view key, long item) const {
  child.place_ = child_place(key, item);
  return child;
}

std::shared_ptr<MapReader::ResolvedPlace> MapReader::child_place(std::string_view key, long item) const {
  if (!records_values()) return nullptr;
  auto p = std::make_shared<ResolvedPlace>();
  p->parent = place_;
  p->key = std::string(key);
  p->item = item;
  return p;
}

const YamlEntry* MapReader::lookup(std::string_view key) {
  declare(key);
  return silent_ ? nullptr : find_entry(node_, key);
}

MapReader MapReader::unused() {
  MapReader view = silenced(*ctx_, path_, doc_path_, where_);
  view.instance_ = instance_;
  view.origin_ = this;
  return view;
}

void MapReader::declare(std::string_view key) {
  if (origin_) return origin_->declare(key);
  ctx_->consumed(join_path(doc_path_, key));
  if (ctx_->recorder()) ctx_->recorder()->known(instance_, doc_path_, key);
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
}

void MapReader::default_varies(std::string_view key) {
  if (ctx_->recorder()) ctx_->recorder()->default_varies(doc_path_, key);
}

void MapReader::record(std::string_view key, const KeyRule& rule, bool required,
                       std::optional<std::string> default_json) {
  // Through unused() the key belongs to a variant the scene does not use: not required here.
  ctx_->recorder()->read(instance_, doc_path_, key,
                         KeyRead{rule, required && !origin_, std::move(default_json)});
}

bool MapReader::absent(std::string_view key, const YamlEntry* e, bool required, const std::string& expected) {
  if (e && e->value.kind != YamlNode::Kind::null) return false;
  if (required && !silent_) {
    ctx_->error(e ? e->value.where : where_, key_path(key), expected + " (required)",
                e ? describe_found(e->value) : kMissing);
    failed(key);
  } else if (e && !silent_) {
    // A key written with no value is almost always an unfinished edit; the default would hide it.
    ctx_->error(e->value.where, key_path(key), expected + " (or leave the key out for the default)",
                describe_found(e->value));
    failed(key);
  }
  return true;
}

void MapReader::error(std::string_view key, std::string expected, std::string hint) {
  const YamlEntry* e = find_entry(node_, key);
  ctx_->error(e ? value_where(*e) : where_, key_path(key), std::move(expected),
              e ? describe_found(e->value) : kMissing, std::move(hint));
  failed(key);
}

double MapReader::real(std::string_view key, const RealRule& rule, std::optional<double> fallback) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder())
    record(key, number_key(rule), !fallback, fallback ? std::optional(json_number(*fallback)) : std::nullopt);
  double out = fallback.value_or(0.0);
  if (!absent(key, e, !fallback, rule.describe())) {
    auto v = read_real(*ctx_, e->value, key_path(key), rule);
    if (!v) failed(key);
    out = v.value_or(out);
  }
  resolved_value(key, yaml_real(out));
  return out;
}

std::optional<double> MapReader::optional_real(std::string_view key, const RealRule& rule) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder()) record(key, number_key(rule, /*nullable=*/true), false, std::nullopt);
  std::optional<double> v;
  if (e && e->value.kind != YamlNode::Kind::null) {  // null: "not set" on purpose
    v = read_real(*ctx_, e->value, key_path(key), rule);
    if (!v) failed(key);
  }
  resolved_value(key, v ? yaml_real(*v) : "null");
  return v;
}

int64_t MapReader::integer(std::string_view key, const IntRule& rule, std::optional<int64_t> fallback) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder())
    record(key, integer_key(rule), !fallback,
           fallback ? std::optional(json_integer(*fallback)) : std::nullopt);
  int64_t out = fallback.value_or(0);
  if (!absent(key, e, !fallback, rule.describe())) {
    auto v = read_integer(*ctx_, e->value, key_path(key), rule);
    if (!v) failed(key);
    out = v.value_or(out);
  }
  resolved_value(key, std::to_string(out));
  return out;
}

bool MapReader::boolean(std::string_view key, std::optional<bool> fallback) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder())
    record(key, boolean_key(), !fallback, fallback ? std::optional(json_boolean(*fallback)) : std::nullopt);
  bool out = fallback.value_or(false);
  if (!absent(key, e, !fallback, "true or false")) {
    auto v = read_boolean(*ctx_, e->value, key_path(key));
    if (!v) failed(key);
    out = v.value_or(out);
  }
  resolved_value(key, out ? "true" : "false");
  return out;
}

std::string MapReader::string(std::string_view key, std::optional<std::string> fallback, bool allow_empty) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder())
    record(key, string_key(allow_empty), !fallback,
           fallback ? std::optional(json_string(*fallback)) : std::nullopt);
  std::string out = fallback.value_or("");
  if (!absent(key, e, !fallback, allow_empty ? "a string" : "a non-empty string")) {
    auto v = read_string(*ctx_, e->value, key_path(key), allow_empty);
    if (!v) failed(key);
    if (v) out = std::move(*v);
  }
  resolved_value(key, resolved_string(out));
  return out;
}

size_t MapReader::choice(std::string_view key, std::span<const std::string_view> options,
                         std::optional<size_t> fallback) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder())
    record(key, choice_key(options), !fallback,
           fallback ? std::optional(json_string(std::string(options[*fallback]))) : std::nullopt);
  size_t out = fallback.value_or(0);
  if (!absent(key, e, !fallback, "one of " + join_names(options))) {
    auto v = read_choice(*ctx_, e->value, key_path(key), options);
    if (!v) failed(key);
    out = v.value_or(out);
  }
  if (out < options.size()) resolved_value(key, std::string(options[out]));
  return out;
}

std::array<double, 3> MapReader::vec3(std::string_view key, const RealRule& rule,
                                      std::optional<std::array<double, 3>> fallback) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder())
    record(key, vec3_key(rule), !fallback,
           fallback ? std::optional(json_numbers({fallback->begin(), fallback->end()})) : std::nullopt);
  std::array<double, 3> out = fallback.value_or(std::array<double, 3>{});
  if (!absent(key, e, !fallback, "a list of 3 numbers (x, y, z), each " + rule.describe())) {
    auto v = read_vec3(*ctx_, e->value, key_path(key), rule);
    if (!v) failed(key);
    out = v.value_or(out);
  }
  resolved_value(key, resolved_vec3(out.data()));
  return out;
}

std::vector<std::string> MapReader::string_list(std::string_view key, std::vector<std::string> fallback) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder())
    record(key, string_list_key(), fallback.empty(),
           fallback.empty() ? std::nullopt : std::optional(json_strings(fallback)));
  std::vector<std::string> out = string_list_value(key, e, std::move(fallback));
  std::string text;
  for (const auto& v : out) text += (text.empty() ? "" : ", ") + resolved_string(v);
  resolved_value(key, "[" + text + "]");
  return out;
}

std::vector<std::string> MapReader::string_list_value(std::string_view key, const YamlEntry* e,
                                                      std::vector<std::string> fallback) {
  const std::string expected = "a list of at least one non-empty string";
  if (absent(key, e, fallback.empty(), expected)) return fallback;
  if (e->value.kind != YamlNode::Kind::sequence || e->value.items.empty()) {
    ctx_->error(e->value.where, key_path(key), expected, describe_found(e->value));
    failed(key);
    return fallback;
  }
  std::vector<std::string> out;
  for (size_t i = 0; i < e->value.items.size(); ++i) {
    auto v = read_string(*ctx_, e->value.items[i], key_path(key) + "[" + std::to_string(i) + "]");
    if (v)
      out.push_back(*v);
    else
      failed(key);
  }
  return ok(key) ? out : fallback;
}

std::vector<size_t> MapReader::choice_list(std::string_view key, std::span<const std::string_view> options,
                                           std::vector<size_t> fallback, size_t min_items) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder()) {
    std::vector<std::string> names;
    for (size_t i : fallback) names.emplace_back(options[i]);
    record(key, choice_list_key(options, min_items), false, json_strings(names));
  }
  std::vector<size_t> out = choice_list_value(key, e, options, std::move(fallback), min_items);
  std::string text;
  for (size_t i : out)
    if (i < options.size()) text += (text.empty() ? "" : ", ") + std::string(options[i]);
  resolved_value(key, "[" + text + "]");
  return out;
}

std::vector<size_t> MapReader::choice_list_value(std::string_view key, const YamlEntry* e,
                                                 std::span<const std::string_view> options,
                                                 std::vector<size_t> fallback, size_t min_items) {
  const std::string expected = "a list of distinct names among " + join_names(options);
  if (absent(key, e, false, expected)) return fallback;
  if (e->value.kind != YamlNode::Kind::sequence || e->value.items.size() < min_items) {
    ctx_->error(e->value.where, key_path(key),
                expected + (min_items > 0 ? ", at least " + std::to_string(min_items) : ""),
                describe_found(e->value));
    failed(key);
    return fallback;
  }
  std::vector<size_t> out;
  for (size_t i = 0; i < e->value.items.size(); ++i) {
    const YamlNode& item = e->value.items[i];
    const std::string item_path = key_path(key) + "[" + std::to_string(i) + "]";
    auto v = read_choice(*ctx_, item, item_path, options);
    if (v && std::find(out.begin(), out.end(), *v) != out.end()) {
      ctx_->error(item.where, item_path, "each name at most once", describe_found(item) + " again");
      v.reset();
    }
    if (v)
      out.push_back(*v);
    else
      failed(key);
  }
  return ok(key) ? out : fallback;
}

TimeFunction MapReader::time_function(std::string_view key, const std::string& unit,
                                      std::optional<TimeFunction> fallback) {
  const YamlEntry* e = lookup(key);
  if (ctx_->recorder()) {
    // A default is stated as a number, the constant form; the reader has no other form as a default.
    const bool constant = fallback && fallback->kind == TimeFunction::Kind::constant;
    record(key, time_function_key(unit), !fallback,
           constant ? std::optional(json_number(fallback->value)) : std::nullopt);
  }
  const std::string in_unit = unit.empty() ? "" : " in " + unit;
  TimeFunction out = fallback.value_or(TimeFunction{});
  if (!absent(key, e, !fallback, "a time function" + in_unit + " (a number, {ramp: ...} or {table: ...})")) {
    auto v = read_time_function(*ctx_, e->value, key_path(key), unit);
    if (!v) failed(key);
    if (v) out = std::move(*v);
  }
  resolved_value(key, resolved_time_function(out));
  return out;
}

MapReader MapReader::section(std::string_view key, bool required, const std::string* doc_path) {
  const YamlEntry* e = lookup(key);
  const std::string path = key_path(key), doc = doc_path ? *doc_path : join_path(doc_path_, key);
  if (ctx_->recorder()) record(key, section_key(doc), required, std::nullopt);
  if (!e) {
    if (!required && !silent_) return placed(MapReader(*ctx_, nullptr, path, doc, where_), key);
    if (!silent_) ctx_->error(where_, path, "a section (mapping) '" + std::string(key) + "'", kMissing);
    failed(key);
    return silenced(*ctx_, path, doc, where_);
  }
  // Keys missing from the section are reported at the section's own key ("time:"), where it starts.
  if (e->value.kind == YamlNode::Kind::null)
    return placed(MapReader(*ctx_, nullptr, path, doc, e->key_where), key);
  if (e->value.kind != YamlNode::Kind::mapping) {
    ctx_->error(e->value.where, path, "a mapping of keys", describe_found(e->value));
    failed(key);
    return silenced(*ctx_, path, doc, e->key_where);
  }
  return placed(MapReader(*ctx_, &e->value, path, doc, e->key_where), key);
}

std::vector<MapReader> MapReader::section_list(std::string_view key, size_t min_items) {
  const YamlEntry* e = lookup(key);
  const std::string path = key_path(key), doc = join_path(doc_path_, key);
  if (ctx_->recorder()) record(key, section_list_key(doc, min_items), min_items > 0, std::nullopt);
  const std::string expected = min_items > 0
                                   ? "a list of at least " + std::to_string(min_items) + " mapping(s)"
                                   : "a list of mappings";
  if (origin_) return {silenced(*ctx_, path + "[0]", doc, where_)};  // see unused()
  if (absent(key, e, min_items > 0, expected)) {
    resolved_value(key, "[]");
    return {};
  }
  if (e->value.kind != YamlNode::Kind::sequence || e->value.items.size() < min_items) {
    ctx_->error(e->value.where, path, expected, describe_found(e->value));
    failed(key);
    return {};
  }
  std::vector<MapReader> out;
  for (size_t i = 0; i < e->value.items.size(); ++i) {
    const YamlNode& item = e->value.items[i];
    const std::string item_path = path + "[" + std::to_string(i) + "]";
    if (item.kind == YamlNode::Kind::mapping) {
      out.push_back(placed(MapReader(*ctx_, &item, item_path, doc, item.where), key, static_cast<long>(i)));
    } else {
      ctx_->error(item.where, item_path, "a mapping of keys", describe_found(item));
      failed(key);
      out.push_back(silenced(*ctx_, item_path, doc, item.where));
    }
  }
  if (out.empty()) resolved_value(key, "[]");  // the items record themselves under the key
  return out;
}

void MapReader::forbid(std::string_view key, const std::string& why) {
  declare(key);
  const YamlEntry* e = silent_ ? nullptr : find_entry(node_, key);
  if (!e) return;
  ctx_->error(e->key_where, key_path(key), "no '" + std::string(key) + "' key " + why, "one");
  failed(key);
}

void MapReader::finish() {
  if (silent_ || !node_) return;
  std::map<std::string, const YamlEntry*, std::less<>> first;
  std::string allowed;
  for (const auto& k : known_) allowed += (allowed.empty() ? "" : ", ") + k;
  for (const auto& e : node_->entries) {
    const bool known = std::find(known_.begin(), known_.end(), e.key) != known_.end();
    auto [it, inserted] = first.emplace(e.key, &e);
    if (!inserted) {
      const SourceLocation& w = it->second->key_where;
      ctx_->error(e.key_where, key_path(e.key), "each key at most once in a mapping",
                  "'" + e.key + "' again (first at " +
                      (w.line > 0 ? "line " + std::to_string(w.line) : w.file) + ")");
    } else if (!known) {
      ctx_->error(e.key_where, key_path(e.key),
                  known_.empty() ? "no keys here" : "one of the keys " + allowed,
                  "unknown key '" + e.key + "'", did_you_mean(e.key, known_));
    }
  }
}

}  // namespace rift
