// docs/scene-format.md must not drift from the reader: every key any valid scene under scenes/ makes
// the reader look up is in a table of the doc, every key in the doc's tables is read by the doc's own
// complete examples (engine/scene/scene_format_doc.hpp finds them, as `rift schema` does), and those
// examples are valid scenes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "engine/scene/load_scene.hpp"
#include "engine/scene/scene_format_doc.hpp"

namespace rift {
namespace {

const std::string kSource = RIFT_SOURCE_DIR;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string doc() {
  return read_text(kSource + "/docs/scene-format.md");
}

// The documented key paths (the first cell of every key table's rows).
std::set<std::string> documented_key_paths(const std::string& text) {
  std::set<std::string> keys;
  for (const auto& [key, row] : documented_keys(text)) keys.insert(key);
  return keys;
}

std::vector<std::filesystem::path> valid_scenes() {
  std::vector<std::filesystem::path> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(kSource + "/scenes")) {
    const auto rel = std::filesystem::relative(e.path(), kSource + "/scenes").string();
    if (e.is_regular_file() && e.path().extension() == ".yaml" && rel.rfind("bad/", 0) != 0)
      out.push_back(e.path());
  }
  return out;
}

TEST(SceneDocs, DocumentsEveryKeyOfEveryValidScene) {
  const std::set<std::string> documented = documented_key_paths(doc());
  ASSERT_GT(documented.size(), 40u);
  const auto scenes = valid_scenes();
  ASSERT_FALSE(scenes.empty());
  for (const auto& path : scenes) {
    SceneLoadResult r = read_scene_file(path.string());
    for (const auto& e : r.errors) ADD_FAILURE() << e.format();
    EXPECT_FALSE(r.consumed_keys.empty());
    for (const auto& key : r.consumed_keys)
      EXPECT_TRUE(documented.count(key))
          << path << " uses key '" << key << "', missing from docs/scene-format.md";
  }
}

TEST(SceneDocs, CompleteExampleIsValidAndUsesEveryDocumentedKey) {
  const std::string text = doc();
  const std::vector<std::string> examples = complete_examples(text);
  ASSERT_EQ(examples.size(), 4u);  // solid, fluid, fluid and solid, fluid in the cracks
  std::set<std::string> consumed;
  for (const auto& example : examples) {
    SceneLoadResult r = read_scene_text(example, "docs/scene-format.md (complete example)", kSource);
    for (const auto& e : r.errors) ADD_FAILURE() << e.format();
    consumed.insert(r.consumed_keys.begin(), r.consumed_keys.end());
  }
  const std::set<std::string> documented = documented_key_paths(text);
  for (const auto& key : documented)
    EXPECT_TRUE(consumed.count(key)) << "docs/scene-format.md documents '" << key
                                     << "', which the complete examples never read";
  for (const auto& key : consumed) EXPECT_TRUE(documented.count(key)) << "undocumented key '" << key << "'";
}

}  // namespace
}  // namespace rift
