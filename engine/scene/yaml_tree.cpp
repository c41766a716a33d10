#include "engine/scene/yaml_tree.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <sstream>

namespace rift {
namespace {

// Aliases are expanded by yaml-cpp, so a small file can name a huge tree ("billion laughs"). A scene
// has a few hundred nodes; these limits stop a hostile or broken file long before memory runs out.
constexpr int kMaxDepth = 64;
constexpr long kMaxNodes = 1'000'000;

// The start of each document, for the first three at most. yaml-cpp 0.7 does not consume a ',' outside
// a flow collection at document level: every HandleNextDocument then returns one more empty document at
// the same place, and YAML::LoadAll loops until memory runs out (", a" as a scene took 24 GB). Counting
// with a bound finds both a real second document and that stall.
class DocumentStarts : public YAML::EventHandler {
 public:
  std::vector<YAML::Mark> starts;
  void OnDocumentStart(const YAML::Mark& mark) override { starts.push_back(mark); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
  }
  void OnMapEnd() override {}
};

std::vector<YAML::Mark> document_starts(const std::string& text) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStarts handler;
  for (int k = 0; k < 3 && parser.HandleNextDocument(handler); ++k) {
  }
  return handler.starts;
}

struct Converter {
  Converter(std::string label_, bool override_origin_)
      : label(std::move(label_)), override_origin(override_origin_) {}

  std::string label;
  bool override_origin = false;
  long nodes = 0;
  std::optional<SceneDiagnostic> error;

  SourceLocation locate(const YAML::Mark& mark, const SourceLocation& fallback) const {
    if (override_origin) return {label, 0, 0};
    if (mark.line < 0) return fallback;
    return {label, mark.line + 1, mark.column + 1};
  }

  void fail(const SourceLocation& where, std::string expected, std::string found) {
    if (!error) error = diagnostic_at(where, "", std::move(expected), std::move(found));
  }

  YamlNode convert(const YAML::Node& in, const SourceLocation& fallback, int depth) {
    YamlNode out;
    out.where = locate(in.Mark(), fallback);
    if (++nodes > kMaxNodes || depth > kMaxDepth) {
      fail(out.where, "a scene-sized document", "a document nested or aliased too deeply");
      return out;
    }
    switch (in.Type()) {
      case YAML::NodeType::Scalar:
        out.kind = YamlNode::Kind::scalar;
        out.text = in.Scalar();
        out.plain = in.Tag() == "?";  // yaml-cpp: "?" plain, "!" quoted, else an explicit tag
        break;
      case YAML::NodeType::Sequence:
        out.kind = YamlNode::Kind::sequence;
        for (const auto& item : in) out.items.push_back(convert(item, out.where, depth + 1));
        break;
      case YAML::NodeType::Map:
        out.kind = YamlNode::Kind::mapping;
        for (auto it = in.begin(); it != in.end(); ++it) add_entry(out, it->first, it->second, depth);
        break;
      default:  // Null or Undefined
        break;
    }
    return out;
  }

  void add_entry(YamlNode& map, const YAML::Node& key, const YAML::Node& value, int depth) {
    YamlEntry entry;
    entry.key_where = locate(key.Mark(), map.where);
    if (!key.IsScalar()) {
      fail(entry.key_where, "a plain key name", "a list or mapping used as a key");
      return;
    }
    entry.key = key.Scalar();
    entry.value = convert(value, entry.key_where, depth + 1);
    // yaml-cpp places an empty value at the start of the next line; the key's line is where it is.
    if (entry.value.kind == YamlNode::Kind::null) entry.value.where = entry.key_where;
    map.entries.push_back(std::move(entry));
  }
};

}  // namespace

SceneDiagnostic diagnostic_at(const SourceLocation& where, std::string key_path, std::string expected,
                              std::string found, std::string hint) {
  return {where.file,          where.line,       where.column,   std::move(key_path),
          std::move(expected), std::move(found), std::move(hint)};
}

YamlParseResult parse_yaml_tree(const std::string& text, const std::string& file_label,
                                bool override_origin) {
  YamlParseResult result;
  std::vector<YAML::Mark> starts;
  YAML::Node doc;
  try {
    starts = document_starts(text);
    if (starts.size() == 1) doc = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    Converter c(file_label, override_origin);
    SourceLocation where = c.locate(e.mark, {file_label, 1, 1});
    result.error = diagnostic_at(where, "", "well-formed YAML", "a syntax error: " + e.msg);
    return result;
  }
  Converter converter(file_label, override_origin);
  // A second document after "---" would otherwise be ignored without a word.
  if (starts.size() > 1) {
    const bool stalled = starts[1].pos == starts[0].pos;
    result.error = diagnostic_at(converter.locate(starts[1], {file_label, 1, 1}), "",
                                 stalled ? "well-formed YAML" : "a single YAML document",
                                 stalled ? "a syntax error: a ',' outside a flow list [..] or mapping {..}"
                                         : "a second document (after '---')");
    return result;
  }
  result.root = converter.convert(doc, {file_label, override_origin ? 0 : 1, override_origin ? 0 : 1}, 0);
  result.error = converter.error;
  return result;
}

}  // namespace rift
