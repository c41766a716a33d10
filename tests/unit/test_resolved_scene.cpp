// The resolved scene is what the readers read (engine/scene/resolved_scene.hpp): every example and
// validation scene's resolved YAML names every key its file gives, reads back to itself, and keeps
// nothing of a section opened but not read or of a variant the scene does not use.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "engine/scene/load_scene.hpp"
#include "engine/scene/resolved_scene.hpp"
#include "engine/scene/yaml_reader.hpp"
#include "engine/scene/yaml_tree.hpp"

namespace rift {
namespace {

std::vector<std::filesystem::path> scene_files() {
  std::vector<std::filesystem::path> files;
  for (const char* folder : {"examples", "validation"})
    for (const auto& e :
         std::filesystem::directory_iterator(std::string(RIFT_SOURCE_DIR) + "/scenes/" + folder))
      if (e.path().extension() == ".yaml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

const YamlNode* find_key(const YamlNode& m, const std::string& key) {
  for (const auto& e : m.entries)
    if (e.key == key) return &e.value;
  return nullptr;
}

// Every mapping key of `given` (list items by position) is in `resolved`; the missing paths.
void missing_keys(const YamlNode& given, const YamlNode& resolved, const std::string& path,
                  std::vector<std::string>& missing) {
  if (given.kind == YamlNode::Kind::mapping) {
    for (const auto& e : given.entries) {
      const std::string p = path.empty() ? e.key : path + "." + e.key;
      const YamlNode* r = resolved.kind == YamlNode::Kind::mapping ? find_key(resolved, e.key) : nullptr;
      if (!r)
        missing.push_back(p);
      else
        missing_keys(e.value, *r, p, missing);
    }
  } else if (given.kind == YamlNode::Kind::sequence && resolved.kind == YamlNode::Kind::sequence) {
    for (size_t i = 0; i < given.items.size() && i < resolved.items.size(); ++i)
      if (given.items[i].kind == YamlNode::Kind::mapping)
        missing_keys(given.items[i], resolved.items[i], path + "[" + std::to_string(i) + "]", missing);
  }
}

TEST(ResolvedScene, EverySceneReadsBackToItselfWithEveryKeyItGives) {
  const auto files = scene_files();
  ASSERT_GT(files.size(), 20u);
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    const SceneLoadResult r = read_scene_file(file.string());
    ASSERT_TRUE(r.scene) << r.errors.at(0).format();
    const SceneLoadResult again = read_scene_text(r.scene->resolved_yaml, "resolved.yaml", "/");
    ASSERT_TRUE(again.scene) << again.errors.at(0).format() << "\n" << r.scene->resolved_yaml;
    EXPECT_EQ(again.scene->resolved_yaml, r.scene->resolved_yaml);
    EXPECT_EQ(again.scene->hash, r.scene->hash);
    std::string text;
    {
      std::ifstream in(file);
      text.assign(std::istreambuf_iterator<char>(in), {});
    }
    const YamlParseResult given = parse_yaml_tree(text, file.string());
    const YamlParseResult resolved = parse_yaml_tree(r.scene->resolved_yaml, "resolved");
    ASSERT_FALSE(resolved.error);
    std::vector<std::string> missing;
    missing_keys(given.root, resolved.root, "", missing);
    EXPECT_TRUE(missing.empty()) << "not in the resolved scene: " << missing.front();
  }
}

TEST(ResolvedScene, RecordsWhatIsReadWhereItIsRead) {
  const YamlParseResult doc = parse_yaml_tree(
      "a: {x: 1}\nlist:\n  - {name: p}\n  - {name: q, extra: 2}\nvariant: {box: [1, 2, 3]}\n", "t");
  ASSERT_FALSE(doc.error);
  ReadContext ctx;
  MapReader root(ctx, &doc.root, "", "", {"t", 1, 1});
  root.record_values_at_root();
  MapReader a = root.section("a", true);
  EXPECT_EQ(a.real("x", any_real(""), std::nullopt), 1.0);
  EXPECT_EQ(a.real("y", any_real(""), 0.5), 0.5);    // a default is recorded too
  MapReader absent = root.section("absent", false);  // opened, never read: no trace
  (void)absent;
  for (MapReader& item : root.section_list("list", 1)) {
    item.string("name", std::nullopt);
    item.integer("extra", IntRule{}, 0);
  }
  MapReader v = root.section("variant", true);
  v.vec3("box", any_real("m"), std::nullopt);
  v.unused().real("diameter", any_real("m"), 1.0);  // the other variant's key: not the scene's
  EXPECT_EQ(emit_resolved_tree(ctx.resolved()),
            "a:\n  x: 1.0\n  y: 0.5\n"
            "list:\n  - name: \"p\"\n    extra: 0\n  - name: \"q\"\n    extra: 2\n"
            "variant:\n  box: [1.0, 2.0, 3.0]\n");
}

}  // namespace
}  // namespace rift
