// docs/scene-format.md must not drift from the reader: every key any valid scene under scenes/ makes
// the reader look up is in a table of the doc, every key in the doc's tables is read by the doc's own
// complete example, and that example is a valid scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "engine/scene/load_scene.hpp"

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

// The first cell of every table row that starts with a `key`: the documented key paths.
std::set<std::string> documented_keys(const std::string& text) {
  std::set<std::string> keys;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| `", 0) != 0) continue;
    const size_t end = line.find('`', 3);
    if (end != std::string::npos) keys.insert(line.substr(3, end - 3));
  }
  return keys;
}

// The ```yaml blocks under each "## Complete example..." heading (one for the solid, one for the fluid, and
// one for both, one for the fluid in the cracks: no one scene can use every key, e.g. a fluid-only scene's
// fluid.mesh excludes mesh, and fracture_flow excludes solid.fracture.crack_pressure).
std::vector<std::string> complete_examples(const std::string& text) {
  std::vector<std::string> out;
  for (size_t heading = text.find("## Complete example"); heading != std::string::npos;
       heading = text.find("## Complete example", heading + 1)) {
    const size_t open = text.find("```yaml\n", heading);
    const size_t close = open == std::string::npos ? open : text.find("```", open + 8);
    if (open == std::string::npos || close == std::string::npos) return {};
    out.push_back(text.substr(open + 8, close - open - 8));
  }
  return out;
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
  const std::set<std::string> documented = documented_keys(doc());
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
  const std::set<std::string> documented = documented_keys(text);
  for (const auto& key : documented)
    EXPECT_TRUE(consumed.count(key)) << "docs/scene-format.md documents '" << key
                                     << "', which the complete examples never read";
  for (const auto& key : consumed) EXPECT_TRUE(documented.count(key)) << "undocumented key '" << key << "'";
}

}  // namespace
}  // namespace rift
