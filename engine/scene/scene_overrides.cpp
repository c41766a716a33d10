#include "engine/scene/scene_overrides.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstddef>

namespace rift {
namespace {

// One step of an override path: a key, then zero or more list indices.
struct PathStep {
  std::string key;
  std::vector<size_t> indices;
};

const char* kSyntax = "key.path=value, e.g. solid.materials[0].density=3000";

bool is_key_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
}

// Parses the key path "a.b[1].c" of the override `where`. Reports and returns nullopt when it is not of
// that form or an index is too large to be one.
std::optional<std::vector<PathStep>> parse_path(const std::string& text, const SourceLocation& where,
                                                ReadContext& ctx) {
  const auto malformed = [&] {
    ctx.error(where, "", kSyntax, "the key path '" + text + "'");
    return std::nullopt;
  };
  std::vector<PathStep> steps;
  size_t i = 0;
  while (true) {
    PathStep step;
    while (i < text.size() && is_key_char(text[i])) step.key += text[i++];
    if (step.key.empty()) return malformed();
    while (i < text.size() && text[i] == '[') {
      const size_t close = text.find(']', i);
      if (close == std::string::npos || close == i + 1) return malformed();
      const std::string digits = text.substr(i + 1, close - i - 1);
      for (char c : digits)
        if (!std::isdigit(static_cast<unsigned char>(c))) return malformed();
      size_t index = 0;
      if (std::from_chars(digits.data(), digits.data() + digits.size(), index).ec != std::errc()) {
        ctx.error(where, text.substr(0, close + 1), "a list index",
                  "index " + digits + ", which is out of range");
        return std::nullopt;
      }
      step.indices.push_back(index);
      i = close + 1;
    }
    steps.push_back(std::move(step));
    if (i == text.size()) return steps;
    if (text[i] != '.') return malformed();
    ++i;
  }
}

// Walks one override path, creating what is missing. Reports and returns null when the tree is in the way.
class OverrideWalker {
 public:
  OverrideWalker(ReadContext& ctx, SourceLocation where) : ctx_(ctx), where_(std::move(where)) {}

  YamlNode* walk(YamlNode& root, const std::vector<PathStep>& steps) {
    YamlNode* node = &root;
    for (const auto& step : steps) {
      node = enter_key(*node, step.key);
      if (!node) return nullptr;
      for (size_t index : step.indices) {
        node = enter_index(*node, index);
        if (!node) return nullptr;
      }
    }
    return node;
  }

 private:
  YamlNode* enter_key(YamlNode& node, const std::string& key) {
    if (node.kind == YamlNode::Kind::null) {
      node.kind = YamlNode::Kind::mapping;  // "creates missing mappings"
      node.where = where_;
    }
    if (node.kind != YamlNode::Kind::mapping) {
      ctx_.error(where_, path_, "a mapping to set '" + key + "' in", describe_found(node));
      return nullptr;
    }
    path_ += (path_.empty() ? "" : ".") + key;
    for (auto& e : node.entries)
      if (e.key == key) return &e.value;
    YamlEntry entry;
    entry.key = key;
    entry.key_where = where_;
    entry.value.where = where_;
    node.entries.push_back(std::move(entry));
    return &node.entries.back().value;
  }

  YamlNode* enter_index(YamlNode& node, size_t index) {
    if (node.kind == YamlNode::Kind::null) {
      node.kind = YamlNode::Kind::sequence;  // a missing list, created like a missing mapping
      node.where = where_;
    }
    const size_t size = node.kind == YamlNode::Kind::sequence ? node.items.size() : 0;
    if (node.kind != YamlNode::Kind::sequence || index > size) {
      ctx_.error(
          where_, path_ + "[" + std::to_string(index) + "]",
          node.kind == YamlNode::Kind::sequence
              ? "an index <= " + std::to_string(size) + " (the list has " + std::to_string(size) +
                    " items; index " + std::to_string(size) + " appends one)"
              : "a list to index into",
          node.kind == YamlNode::Kind::sequence ? "index " + std::to_string(index) : describe_found(node));
      return nullptr;
    }
    path_ += "[" + std::to_string(index) + "]";
    if (index == size) {
      node.items.emplace_back();
      node.items.back().where = where_;
    }
    return &node.items[index];
  }

  ReadContext& ctx_;
  SourceLocation where_;
  std::string path_;
};

// `--set path=null` (or ~) removes what path names: a key from its mapping, an item from its list, so the
// scene reads as if it had never been written there (its default, or no section). A path that names
// nothing removes nothing. False when the tree is in the way (a scalar where a mapping or list should be).
bool remove_path(YamlNode& root, const std::vector<PathStep>& steps) {
  struct Token {
    const std::string* key;
    size_t index;
  };
  std::vector<Token> tokens;
  for (const auto& step : steps) {
    tokens.push_back({&step.key, 0});
    for (size_t index : step.indices) tokens.push_back({nullptr, index});
  }
  YamlNode* node = &root;
  for (size_t t = 0; t < tokens.size(); ++t) {
    const bool last = t + 1 == tokens.size();
    if (tokens[t].key) {
      if (node->kind == YamlNode::Kind::null) return true;
      if (node->kind != YamlNode::Kind::mapping) return false;
      auto it = std::find_if(node->entries.begin(), node->entries.end(),
                             [&](const YamlEntry& e) { return e.key == *tokens[t].key; });
      if (it == node->entries.end()) return true;
      if (last) {
        node->entries.erase(it);
        return true;
      }
      node = &it->value;
    } else {
      if (node->kind == YamlNode::Kind::null) return true;
      if (node->kind != YamlNode::Kind::sequence) return false;
      if (tokens[t].index >= node->items.size()) return true;
      if (last) {
        node->items.erase(node->items.begin() + static_cast<std::ptrdiff_t>(tokens[t].index));
        return true;
      }
      node = &node->items[tokens[t].index];
    }
  }
  return true;
}

bool is_null_text(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.erase(text.begin());
  return text == "null" || text == "~" || text == "Null" || text == "NULL";
}

void apply_override(YamlNode& root, const std::string& text, ReadContext& ctx) {
  const SourceLocation where{"--set " + text, 0, 0};
  const size_t eq = text.find('=');
  if (eq == std::string::npos) {
    ctx.error(where, "", kSyntax, "no '=' in '" + text + "'");
    return;
  }
  const auto steps = parse_path(text.substr(0, eq), where, ctx);
  if (!steps) return;
  if (is_null_text(text.substr(eq + 1))) {
    if (!remove_path(root, *steps))
      ctx.error(where, text.substr(0, eq), "a path through mappings and lists to remove",
                "a plain value in the way");
    return;
  }
  YamlParseResult value = parse_yaml_tree(text.substr(eq + 1), where.file, /*override_origin=*/true);
  if (value.error) {
    value.error->key_path = text.substr(0, eq);
    ctx.error(where, value.error->key_path, "a YAML value after '='", value.error->found);
    return;
  }
  YamlNode* target = OverrideWalker(ctx, where).walk(root, *steps);
  if (target) *target = std::move(value.root);
}

}  // namespace

void apply_overrides(YamlNode& root, const std::vector<std::string>& overrides, ReadContext& ctx) {
  for (const auto& text : overrides) apply_override(root, text, ctx);
}

}  // namespace rift
