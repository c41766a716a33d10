#include "engine/scene/resolved_scene.hpp"

#include <cstdio>

#include "engine/scene/number_text.hpp"

namespace rift {

ResolvedNode& ResolvedNode::entry(std::string_view key, Kind k) {
  for (auto& [name, node] : entries)
    if (name == key) {
      if (node->kind != k) {
        *node = ResolvedNode();
        node->kind = k;
      }
      return *node;
    }
  entries.emplace_back(std::string(key), std::make_unique<ResolvedNode>());
  entries.back().second->kind = k;
  return *entries.back().second;
}

ResolvedNode& ResolvedNode::item(size_t index) {
  while (items.size() <= index) items.push_back(std::make_unique<ResolvedNode>());
  return *items[index];
}

std::string resolved_string(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string resolved_vec3(const double v[3]) {
  return "[" + yaml_real(v[0]) + ", " + yaml_real(v[1]) + ", " + yaml_real(v[2]) + "]";
}

std::string resolved_time_function(const TimeFunction& f) {
  switch (f.kind) {
    case TimeFunction::Kind::constant:
      return yaml_real(f.value);
    case TimeFunction::Kind::ramp:
      return "{ramp: {value: " + yaml_real(f.value) + ", start_time: " + yaml_real(f.start_time) +
             ", rate: " + yaml_real(f.rate) + ", limit: " + (f.has_limit ? yaml_real(f.limit) : "null") +
             "}}";
    case TimeFunction::Kind::table: {
      std::string rows;
      for (const auto& [t, v] : f.points)
        rows += (rows.empty() ? "[" : ", [") + yaml_real(t) + ", " + yaml_real(v) + "]";
      return "{table: [" + rows + "]}";
    }
  }
  return {};
}

namespace {

void emit_mapping(std::string& out, const ResolvedNode& m, int indent, bool first_as_item);

// "key: value" or "key:" and the nested block, at `indent` (the first key of a list item after "- ").
void emit_entry(std::string& out, const std::string& key, const ResolvedNode& v, int indent) {
  out += key;
  out += ':';
  switch (v.kind) {
    case ResolvedNode::Kind::scalar:
      out += ' ' + v.text + '\n';
      return;
    case ResolvedNode::Kind::mapping:
      if (v.entries.empty()) {
        out += " {}\n";
        return;
      }
      out += '\n';
      emit_mapping(out, v, indent + 1, false);
      return;
    case ResolvedNode::Kind::list:
      if (v.items.empty()) {
        out += " []\n";
        return;
      }
      out += '\n';
      for (const auto& item : v.items) {
        out.append(static_cast<size_t>(indent + 1) * 2, ' ');
        out += "- ";
        if (item->entries.empty())
          out += "{}\n";
        else
          emit_mapping(out, *item, indent + 2, true);
      }
      return;
  }
}

void emit_mapping(std::string& out, const ResolvedNode& m, int indent, bool first_as_item) {
  for (size_t k = 0; k < m.entries.size(); ++k) {
    if (k > 0 || !first_as_item) out.append(static_cast<size_t>(indent) * 2, ' ');
    emit_entry(out, m.entries[k].first, *m.entries[k].second, indent);
  }
}

}  // namespace

std::string emit_resolved_tree(const ResolvedNode& root) {
  std::string out;
  emit_mapping(out, root, 0, false);
  return out;
}

}  // namespace rift
