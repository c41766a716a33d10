#include "engine/scene/scene_diff.hpp"

#include <algorithm>
#include <map>

#include "engine/scene/yaml_tree.hpp"

namespace rift {
namespace {

// Every leaf (scalar, null, empty list or section) under its path, with a text that tells kinds apart.
void flatten(const YamlNode& node, const std::string& path, std::map<std::string, std::string>& out) {
  switch (node.kind) {
    case YamlNode::Kind::null:
      out[path] = "~null";
      return;
    case YamlNode::Kind::scalar:
      out[path] = (node.plain ? "=" : "\"") + node.text;
      return;
    case YamlNode::Kind::sequence:
      if (node.items.empty()) out[path] = "[]";
      for (size_t i = 0; i < node.items.size(); ++i)
        flatten(node.items[i], path + "[" + std::to_string(i) + "]", out);
      return;
    case YamlNode::Kind::mapping:
      if (node.entries.empty()) out[path] = "{}";
      for (const auto& e : node.entries) flatten(e.value, path.empty() ? e.key : path + "." + e.key, out);
      return;
  }
}

}  // namespace

std::vector<std::string> differing_keys(const std::string& yaml_a, const std::string& yaml_b) {
  const YamlParseResult a = parse_yaml_tree(yaml_a, "a"), b = parse_yaml_tree(yaml_b, "b");
  if (a.error || b.error) return {""};
  std::map<std::string, std::string> fa, fb;
  flatten(a.root, "", fa);
  flatten(b.root, "", fb);
  std::vector<std::string> out;
  for (const auto& [path, value] : fa) {
    const auto it = fb.find(path);
    if (it == fb.end() || it->second != value) out.push_back(path);
  }
  for (const auto& [path, value] : fb)
    if (!fa.count(path)) out.push_back(path);
  std::sort(out.begin(), out.end());
  return out;
}

bool only_extension_keys(const std::vector<std::string>& paths) {
  if (paths.empty()) return false;
  for (const auto& p : paths)
    if (p != "time.end" && !p.starts_with("output.") && p != "output") return false;
  return true;
}

}  // namespace rift
