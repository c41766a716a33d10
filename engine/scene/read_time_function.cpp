// Time functions in scene files: a number (constant), {ramp: {...}} or {table: [[t, v], ...]}.
#include "engine/scene/number_text.hpp"
#include "engine/scene/yaml_reader.hpp"

namespace rift {
namespace {

std::string in_unit(const std::string& unit) {
  return unit.empty() ? "" : " in " + unit;
}

std::string expected_forms(const std::string& unit) {
  return "a time function" + in_unit(unit) + ": a number, {ramp: {value, start_time, rate, limit}} or " +
         "{table: [[t0, v0], [t1, v1], ...]}";
}

// Keys inside a time function are documented once for all of them, so their doc path starts afresh
// ("ramp.rate") instead of under the key that holds the function.
std::optional<TimeFunction> read_ramp(ReadContext& ctx, const YamlNode& node, const std::string& path,
                                      const std::string& unit) {
  if (node.kind != YamlNode::Kind::mapping) {
    ctx.error(node.where, path, "a mapping with value, start_time, rate and optionally limit",
              describe_found(node));
    return std::nullopt;
  }
  MapReader ramp(ctx, &node, path, "ramp", node.where);
  TimeFunction f;
  f.kind = TimeFunction::Kind::ramp;
  f.value = ramp.real("value", any_real(unit), std::nullopt);
  f.start_time = ramp.real("start_time", non_negative("s"), std::nullopt);
  f.rate = ramp.real("rate", any_real(unit.empty() ? "1/s" : unit + "/s"), std::nullopt);
  const auto limit = ramp.optional_real("limit", any_real(unit));
  f.has_limit = limit.has_value();
  f.limit = limit.value_or(0.0);
  // A limit behind the starting value would clamp the function before the ramp even starts.
  if (f.has_limit && ramp.ok("value") && ramp.ok("rate") && ramp.ok("limit") &&
      (f.rate >= 0 ? f.limit < f.value : f.limit > f.value)) {
    ramp.error("limit", "a limit the ramp reaches: " + std::string(f.rate >= 0 ? ">=" : "<=") + " value (" +
                            message_real(f.value) + ")");
  }
  ramp.finish();
  if (!ramp.ok("value") || !ramp.ok("start_time") || !ramp.ok("rate") || !ramp.ok("limit"))
    return std::nullopt;
  return f;
}

std::optional<TimeFunction> read_table(ReadContext& ctx, const YamlNode& node, const std::string& path,
                                       const std::string& unit) {
  const std::string expected = "a list of at least 2 [time in s, value" + in_unit(unit) + "] pairs";
  if (node.kind != YamlNode::Kind::sequence || node.items.size() < 2) {
    ctx.error(node.where, path, expected, describe_found(node));
    return std::nullopt;
  }
  TimeFunction f;
  f.kind = TimeFunction::Kind::table;
  bool good = true;
  for (size_t i = 0; i < node.items.size(); ++i) {
    const YamlNode& row = node.items[i];
    const std::string row_path = path + "[" + std::to_string(i) + "]";
    if (row.kind != YamlNode::Kind::sequence || row.items.size() != 2) {
      ctx.error(row.where, row_path, "a [time in s, value" + in_unit(unit) + "] pair", describe_found(row));
      good = false;
      continue;
    }
    auto t = read_real(ctx, row.items[0], row_path + "[0]", any_real("s"));
    auto v = read_real(ctx, row.items[1], row_path + "[1]", any_real(unit));
    if (!t || !v) {
      good = false;
      continue;
    }
    if (!f.points.empty() && *t <= f.points.back().first) {
      ctx.error(row.items[0].where, row_path + "[0]",
                "a time > " + message_real(f.points.back().first) + " s (times strictly increasing)",
                describe_found(row.items[0]));
      good = false;
    }
    f.points.emplace_back(*t, *v);
  }
  if (!good) return std::nullopt;
  return f;
}

}  // namespace

std::optional<TimeFunction> read_time_function(ReadContext& ctx, const YamlNode& node,
                                               const std::string& path, const std::string& unit) {
  if (node.kind == YamlNode::Kind::scalar) {
    auto v = read_real(ctx, node, path, any_real(unit));
    if (!v) return std::nullopt;
    TimeFunction f;
    f.value = *v;
    return f;
  }
  if (node.kind != YamlNode::Kind::mapping || node.entries.size() != 1 ||
      (node.entries[0].key != "ramp" && node.entries[0].key != "table")) {
    MapReader forms(ctx, &node, path, "", node.where);
    if (node.kind == YamlNode::Kind::mapping && !node.entries.empty()) {
      forms.declare("ramp");
      forms.declare("table");
      const size_t before = ctx.errors().size();
      forms.finish();  // names unknown keys with a suggestion
      if (ctx.errors().size() > before) return std::nullopt;
    }
    ctx.error(node.where, path, expected_forms(unit), describe_found(node));
    return std::nullopt;
  }
  const YamlEntry& form = node.entries[0];
  ctx.consumed(form.key);
  const std::string form_path = path + "." + form.key;
  return form.key == "ramp" ? read_ramp(ctx, form.value, form_path, unit)
                            : read_table(ctx, form.value, form_path, unit);
}

}  // namespace rift
