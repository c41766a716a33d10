// Readers of single YAML values (numbers, booleans, strings, choices, vectors) with the rules and
// messages the scene format promises. See yaml_reader.hpp.
#include <cmath>

#include "engine/scene/number_text.hpp"
#include "engine/scene/suggest.hpp"
#include "engine/scene/yaml_reader.hpp"

namespace rift {

void ReadContext::error(const SourceLocation& where, std::string key_path, std::string expected,
                        std::string found, std::string hint) {
  errors_.push_back(
      diagnostic_at(where, std::move(key_path), std::move(expected), std::move(found), std::move(hint)));
}

bool RealRule::accepts(double v) const {
  if (min && (min_open ? v <= *min : v < *min)) return false;
  if (max && (max_open ? v >= *max : v > *max)) return false;
  return true;
}

std::string RealRule::describe() const {
  std::string out = "a number";
  if (!unit.empty()) out += " in " + unit;
  if (min && max) {
    out += std::string(", in ") + (min_open ? "(" : "[") + message_real(*min) + ", " + message_real(*max) +
           (max_open ? ")" : "]");
  } else if (min) {
    out += std::string(", ") + (min_open ? "> " : ">= ") + message_real(*min);
  } else if (max) {
    out += std::string(", ") + (max_open ? "< " : "<= ") + message_real(*max);
  }
  return out;
}

RealRule any_real(std::string unit) {
  return {std::move(unit), {}, {}, false, false};
}
RealRule positive(std::string unit) {
  return {std::move(unit), 0.0, {}, true, false};
}
RealRule non_negative(std::string unit) {
  return {std::move(unit), 0.0, {}, false, false};
}

std::string IntRule::describe() const {
  if (min != INT64_MIN && max != INT64_MAX)
    return "an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (min != INT64_MIN) return "an integer >= " + std::to_string(min);
  if (max != INT64_MAX) return "an integer <= " + std::to_string(max);
  return "an integer";
}

std::string describe_found(const YamlNode& node) {
  switch (node.kind) {
    case YamlNode::Kind::null:
      return "nothing";
    case YamlNode::Kind::scalar:
      return node.plain ? "'" + node.text + "'" : "the string \"" + node.text + "\"";
    case YamlNode::Kind::sequence:
      return "a list of " + std::to_string(node.items.size()) + (node.items.size() == 1 ? " item" : " items");
    case YamlNode::Kind::mapping:
      return "a mapping";
  }
  return "?";
}

std::string join_names(std::span<const std::string_view> names) {
  std::string out;
  for (auto n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

std::optional<double> read_real(ReadContext& ctx, const YamlNode& node, const std::string& path,
                                const RealRule& rule) {
  // Quoted numbers are strings in YAML; accepting them would hide a mistake in the file.
  if (node.kind != YamlNode::Kind::scalar || !node.plain) {
    ctx.error(node.where, path, rule.describe(), describe_found(node));
    return std::nullopt;
  }
  double v = 0.0;
  switch (parse_real_text(node.text, v)) {
    case NumberParse::ok:
      break;
    case NumberParse::not_a_number:
      ctx.error(node.where, path, rule.describe(), describe_found(node) + ", which is not a number");
      return std::nullopt;
    case NumberParse::not_finite:
      ctx.error(node.where, path, rule.describe(), describe_found(node) + ", which is not a finite number");
      return std::nullopt;
    case NumberParse::out_of_range:
      ctx.error(node.where, path, rule.describe(), describe_found(node) + ", beyond the range of a double");
      return std::nullopt;
  }
  if (!rule.accepts(v)) {
    ctx.error(node.where, path, rule.describe(), describe_found(node));
    return std::nullopt;
  }
  return v;
}

std::optional<int64_t> read_integer(ReadContext& ctx, const YamlNode& node, const std::string& path,
                                    const IntRule& rule) {
  if (node.kind != YamlNode::Kind::scalar || !node.plain) {
    ctx.error(node.where, path, rule.describe(), describe_found(node));
    return std::nullopt;
  }
  int64_t v = 0;
  const NumberParse parsed = parse_integer_text(node.text, v);
  if (parsed != NumberParse::ok) {
    ctx.error(node.where, path, rule.describe(),
              describe_found(node) + (parsed == NumberParse::out_of_range ? ", which is out of range"
                                                                          : ", which is not an integer"));
    return std::nullopt;
  }
  if (v < rule.min || v > rule.max) {
    ctx.error(node.where, path, rule.describe(), describe_found(node));
    return std::nullopt;
  }
  return v;
}

std::optional<bool> read_boolean(ReadContext& ctx, const YamlNode& node, const std::string& path) {
  // YAML 1.1 also reads yes/no/on/off/y/n as booleans; the scene format takes only true and false so
  // that a value means the same to every YAML reader.
  if (node.kind == YamlNode::Kind::scalar && node.plain) {
    if (node.text == "true") return true;
    if (node.text == "false") return false;
  }
  ctx.error(node.where, path, "true or false", describe_found(node));
  return std::nullopt;
}

std::optional<std::string> read_string(ReadContext& ctx, const YamlNode& node, const std::string& path,
                                       bool allow_empty) {
  if (node.kind != YamlNode::Kind::scalar || (node.text.empty() && !allow_empty)) {
    ctx.error(node.where, path, allow_empty ? "a string" : "a non-empty string", describe_found(node));
    return std::nullopt;
  }
  return node.text;
}

std::optional<size_t> read_choice(ReadContext& ctx, const YamlNode& node, const std::string& path,
                                  std::span<const std::string_view> options) {
  const std::string expected = "one of " + join_names(options);
  if (node.kind != YamlNode::Kind::scalar) {
    ctx.error(node.where, path, expected, describe_found(node));
    return std::nullopt;
  }
  for (size_t i = 0; i < options.size(); ++i)
    if (node.text == options[i]) return i;
  std::vector<std::string> names(options.begin(), options.end());
  ctx.error(node.where, path, expected, describe_found(node), did_you_mean(node.text, names));
  return std::nullopt;
}

std::optional<std::array<double, 3>> read_vec3(ReadContext& ctx, const YamlNode& node,
                                               const std::string& path, const RealRule& rule) {
  if (node.kind != YamlNode::Kind::sequence || node.items.size() != 3) {
    ctx.error(node.where, path, "a list of 3 numbers (x, y, z), each " + rule.describe(),
              describe_found(node));
    return std::nullopt;
  }
  std::array<double, 3> out{};
  bool good = true;
  for (size_t i = 0; i < 3; ++i) {
    auto v = read_real(ctx, node.items[i], path + "[" + std::to_string(i) + "]", rule);
    good = good && v.has_value();
    if (v) out[i] = *v;
  }
  if (!good) return std::nullopt;
  return out;
}

}  // namespace rift
