#pragma once
// A YAML document as plain data for the scene reader. Every node keeps where it came from (file
// line/column, or the --set override that wrote it), mappings keep their keys in file order *with
// duplicates*, and scalars remember whether they were quoted. yaml-cpp's Node cannot carry an
// override's origin and mutates itself on lookup, so the reader works on this copy instead.
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene_diagnostic.hpp"

namespace rift {

// Where a node was written. line == 0 marks a value from an override, whose text is in `file`.
struct SourceLocation {
  std::string file;
  int line = 0;    // 1-based
  int column = 0;  // 1-based
};

struct YamlEntry;

struct YamlNode {
  enum class Kind { null, scalar, sequence, mapping };
  Kind kind = Kind::null;
  std::string text;   // scalar: its text
  bool plain = true;  // scalar: written without quotes or an explicit tag
  SourceLocation where;
  std::vector<YamlNode> items;     // sequence
  std::vector<YamlEntry> entries;  // mapping, in document order, duplicate keys kept
};

struct YamlEntry {
  std::string key;
  SourceLocation key_where;
  YamlNode value;
};

struct YamlParseResult {
  YamlNode root;                         // a null node for an empty document
  std::optional<SceneDiagnostic> error;  // malformed YAML: the parser's message and position
};

// Parses `text`, which must hold at most one document. With `override_label` set, every node is located at
// that label instead of a line (the value of a --set override).
YamlParseResult parse_yaml_tree(const std::string& text, const std::string& file_label,
                                bool override_origin = false);

// A diagnostic at `where`.
SceneDiagnostic diagnostic_at(const SourceLocation& where, std::string key_path, std::string expected,
                              std::string found, std::string hint = {});

}  // namespace rift
