// `rift schema`: the scene format's JSON Schema, made from the reader's own rules while it reads the
// docs' complete examples (engine/scene/scene_schema.hpp). It must be a valid draft-07 schema, describe
// every documented key, accept every valid scene and catch the usual mistakes, as a third-party
// validator sees it: Python's jsonschema on the YAML read by ruamel.yaml. ruamel.yaml reads YAML 1.2,
// as the scene reader does; PyYAML reads YAML 1.1, where `6.0e10` and `1e-3` are strings and `yes` a
// boolean, so every scene would fail on its numbers. The Python checks are skipped, saying so, when
// those packages are missing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "engine/core/spawn.hpp"
#include "engine/scene/load_scene.hpp"
#include "engine/scene/scene_format_doc.hpp"
#include "engine/scene/scene_schema.hpp"
#include "engine/scene/schema_recorder.hpp"
#include "tests/unit/test_io_temp_dir.hpp"

namespace rift {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

const std::string kSource = RIFT_SOURCE_DIR;

std::string source_doc() {
  return test::slurp(kSource + "/docs/scene-format.md");
}

const SceneSchema& schema() {
  static const SceneSchema s = scene_schema();
  return s;
}

// The schemas a value at `node` may have to satisfy: `node` with its references, allOf and anyOf
// followed (a time function's forms, fluid.mesh's reference to mesh), and a list's items.
void alternatives(const Json& root, const Json& node, std::vector<const Json*>& out) {
  out.push_back(&node);
  if (node.contains("$ref")) {
    const std::string ref = node["$ref"];
    alternatives(root, root.at(Json::json_pointer(ref.substr(1))), out);
  }
  for (const char* key : {"allOf", "anyOf"})
    if (node.contains(key))
      for (const Json& sub : node[key]) alternatives(root, sub, out);
  if (node.contains("items")) alternatives(root, node["items"], out);
}

// The schema of the documented key `path` ("solid.materials.density"), or null. Time-function keys
// start afresh in the docs ("ramp.rate"), so their walk starts at the time function's definition.
const Json* key_schema(const Json& root, const std::string& path) {
  const bool in_time_function = path == "ramp" || path == "table" || path.rfind("ramp.", 0) == 0;
  const Json* node = in_time_function ? &root["definitions"]["time_function"] : &root;
  for (size_t start = 0; node && start <= path.size();) {
    const size_t dot = std::min(path.find('.', start), path.size());
    const std::string key = path.substr(start, dot - start);
    std::vector<const Json*> options;
    alternatives(root, *node, options);
    node = nullptr;
    for (const Json* o : options)
      if (o->contains("properties") && (*o)["properties"].contains(key)) node = &(*o)["properties"][key];
    start = dot + 1;
  }
  return node;
}

TEST(SceneSchema, IsDraft07JsonFromExamplesThatRead) {
  for (const auto& p : schema().problems) ADD_FAILURE() << p;
  const Json s = Json::parse(schema().json);  // throws on anything but JSON
  EXPECT_EQ(s["$schema"], "http://json-schema.org/draft-07/schema#");
  EXPECT_EQ(s["title"], "Rift scene");
  EXPECT_EQ(s["additionalProperties"], false);
  EXPECT_EQ(s["required"], Json::array({"scene", "time"}));
}

TEST(SceneSchema, TheBinarysDocsAreTheSourceDocs) {
  EXPECT_TRUE(scene_format_doc() == source_doc())
      << "the docs built into the binary differ from docs/scene-format.md: re-run cmake";
}

TEST(SceneSchema, DescribesEveryDocumentedKeyWithARule) {
  const Json s = Json::parse(schema().json);
  const auto documented = documented_keys(source_doc());
  ASSERT_GT(documented.size(), 100u);
  EXPECT_EQ(schema().keys, documented.size());
  for (const auto& [path, row] : documented) {
    const Json* k = key_schema(s, path);
    if (!k) {
      ADD_FAILURE() << "documented key '" << path << "' is not in the schema";
      continue;
    }
    EXPECT_FALSE(k->value("description", "").empty()) << path;
    const bool ruled = k->contains("type") || k->contains("enum") || k->contains("anyOf") ||
                       k->contains("allOf") || k->contains("$ref");
    EXPECT_TRUE(ruled) << path << " has no rule: the reader only declares it, in every complete example";
  }
  // Rules as the reader states them, descriptions and units from the docs.
  const Json* end = key_schema(s, "time.end");
  ASSERT_TRUE(end);
  EXPECT_EQ((*end)["type"], "number");
  EXPECT_EQ((*end)["exclusiveMinimum"], 0.0);
  EXPECT_EQ((*end)["description"], "simulated end time [s]");
  const Json* poisson = key_schema(s, "solid.materials.poisson");
  ASSERT_TRUE(poisson);
  EXPECT_EQ((*poisson)["minimum"], 0.0);
  EXPECT_EQ((*poisson)["exclusiveMaximum"], 0.5);
  EXPECT_EQ((*key_schema(s, "fluid.scheme"))["default"], "backward_euler");
  EXPECT_EQ((*key_schema(s, "time.dt"))["type"], Json::array({"number", "null"}));
  EXPECT_FALSE(key_schema(s, "solid.materials.fracture.penalty")->contains("default"));  // 10 x young
  EXPECT_EQ((*key_schema(s, "fluid.mesh"))["allOf"][0]["$ref"], "#/definitions/mesh");
}

// The reader reports the same with a recorder as without: recording only listens.
TEST(SceneSchema, RecordingChangesNothingTheReaderReports) {
  std::vector<std::string> texts = complete_examples(source_doc());
  texts.push_back(test::slurp(kSource + "/scenes/bad/unknown_key.yaml"));
  for (const std::string& text : texts) {
    SchemaRecorder recorder;
    const SceneLoadResult plain = read_scene_text(text, "scene.yaml", kSource);
    const SceneLoadResult recorded = read_scene_text(text, "scene.yaml", kSource, {}, &recorder);
    ASSERT_EQ(plain.errors.size(), recorded.errors.size());
    for (size_t i = 0; i < plain.errors.size(); ++i)
      EXPECT_EQ(plain.errors[i].format(), recorded.errors[i].format());
    EXPECT_EQ(plain.consumed_keys, recorded.consumed_keys);
    ASSERT_EQ(plain.scene.has_value(), recorded.scene.has_value());
    if (plain.scene) {
      EXPECT_EQ(plain.scene->resolved_yaml, recorded.scene->resolved_yaml);
    }
    EXPECT_FALSE(recorder.objects().empty());
  }
}

// argv: the schema, then "valid:<file>" or "invalid:<file>" per scene. Prints one line per scene
// and exits 1 when any scene is not as expected.
constexpr const char* kValidate = R"py(
import json, sys
from importlib.metadata import version
import jsonschema
from ruamel.yaml import YAML
schema = json.load(open(sys.argv[1]))
jsonschema.Draft7Validator.check_schema(schema)
validator = jsonschema.Draft7Validator(schema)
yaml = YAML(typ="safe", pure=True)  # YAML 1.2, as the scene reader
# The scene reader has no timestamps: a date-like value is a string's text.
yaml.constructor.add_constructor("tag:yaml.org,2002:timestamp", lambda c, node: c.construct_scalar(node))
print(f"jsonschema {version('jsonschema')}, ruamel.yaml {version('ruamel.yaml')}: the schema is valid draft-07")
wrong = 0
for arg in sys.argv[2:]:
    expect, path = arg.split(":", 1)
    with open(path) as f:
        scene = yaml.load(f)
    errors = sorted(validator.iter_errors(scene), key=lambda e: list(e.absolute_path))
    got = "invalid" if errors else "valid"
    wrong += got != expect
    first = f": {'.'.join(map(str, errors[0].absolute_path))}: {errors[0].message}" if errors else ""
    print(f"{path}: {got}{first}" + ("" if got == expect else f" (expected {expect})"))
sys.exit(1 if wrong else 0)
)py";

struct Validation {
  int status;
  std::string output;
};

Validation validate(const std::string& python, const test::TempDir& dir,
                    const std::vector<std::string>& cases) {
  std::ofstream(dir / "schema.json") << schema().json;
  std::ofstream(dir / "validate.py") << kValidate;
  std::vector<std::string> argv{python, (dir / "validate.py").string(), (dir / "schema.json").string()};
  argv.insert(argv.end(), cases.begin(), cases.end());
  const fs::path log = dir / "validate.log";
  const int status = run_program(argv, {}, log);
  return {status, test::slurp(log)};
}

std::string python_or_skip_reason(std::string& python) {
  python = python_with("jsonschema, ruamel.yaml");
  return python.empty() ? "no python3 with jsonschema and ruamel.yaml (Debian: apt-get install "
                          "python3-jsonschema python3-ruamel.yaml); the schema is not checked by a validator"
                        : "";
}

TEST(SceneSchema, ValidatesEveryValidSceneAndCompleteExample) {
  std::string python;
  const std::string skip = python_or_skip_reason(python);
  if (!skip.empty()) GTEST_SKIP() << skip;
  test::TempDir dir;
  std::vector<std::string> cases;
  for (const auto& e : fs::recursive_directory_iterator(kSource + "/scenes")) {
    const std::string rel = fs::relative(e.path(), kSource + "/scenes").string();
    const bool bad = rel.rfind("bad/", 0) == 0 || rel.find("/bad/") != std::string::npos;
    if (e.is_regular_file() && e.path().extension() == ".yaml" && !bad)
      cases.push_back("valid:" + e.path().string());
  }
  ASSERT_GT(cases.size(), 20u);
  const std::vector<std::string> examples = complete_examples(source_doc());
  ASSERT_EQ(examples.size(), 4u);
  for (size_t i = 0; i < examples.size(); ++i) {
    const fs::path file = dir / ("complete_example_" + std::to_string(i + 1) + ".yaml");
    std::ofstream(file) << examples[i];
    cases.push_back("valid:" + file.string());
  }
  const Validation v = validate(python, dir, cases);
  std::printf("%s", v.output.c_str());
  EXPECT_EQ(v.status, 0) << v.output;
}

// A small valid scene, and copies with one line replaced by a mistake; the validator names the key.
TEST(SceneSchema, CatchesTheUsualMistakes) {
  std::string python;
  const std::string skip = python_or_skip_reason(python);
  if (!skip.empty()) GTEST_SKIP() << skip;
  const std::vector<std::string> lines{
      "scene: {name: bar}",
      "time: {end: 1.0e-4}",
      "mesh: {generate: {box: [0.1, 0.02, 0.02], cells: [10, 2, 2]}}",
      "solid:",
      "  materials: [{name: rock, density: 2700, young: 6.0e10, poisson: 0.25}]",
      "  boundaries: [{surface: xmin, type: fixed}]",
  };
  struct Mistake {
    size_t line;
    std::string text, message;
  };
  const std::vector<Mistake> mistakes{
      {1, "time: {end: 1.0e-4, ends: 2}", "Additional properties are not allowed ('ends' was unexpected)"},
      {1, "time: {end: soon}", "time.end: 'soon' is not of type 'number'"},
      {1, "time: {end: -1}", "time.end: -1 is less than or equal to the minimum of 0"},
      {5, "  boundaries: [{surface: xmin, type: fxed}]", "solid.boundaries.0.type: 'fxed' is not one of"},
      {0, "scene: {description: no name}", "scene: 'name' is a required property"},
      {1, "time: {end: 1.0e-4, allow_unstable_dt: yes}",
       "'yes' is not of type 'boolean'"},                                            // YAML 1.1's true
      {1, "time: {end: \"1.0e-4\"}", "time.end: '1.0e-4' is not of type 'number'"},  // quoted
  };
  test::TempDir dir;
  auto write = [&](const std::vector<std::string>& text, size_t i) {
    const fs::path file = dir / ("case" + std::to_string(i) + ".yaml");
    std::ofstream out(file);
    for (const auto& l : text) out << l << "\n";
    return file.string();
  };
  std::vector<std::string> cases{"valid:" + write(lines, 0)};
  for (size_t i = 0; i < mistakes.size(); ++i) {
    std::vector<std::string> text = lines;
    text[mistakes[i].line] = mistakes[i].text;
    cases.push_back("invalid:" + write(text, i + 1));
  }
  const Validation v = validate(python, dir, cases);
  std::printf("%s", v.output.c_str());
  EXPECT_EQ(v.status, 0) << v.output;
  for (const Mistake& m : mistakes)
    EXPECT_NE(v.output.find(m.message), std::string::npos) << m.message << "\n" << v.output;
}

// `rift schema` prints the schema; with --out it writes the same text to the file; --help lists it.
TEST(Cli, SchemaPrintsOrWritesTheSceneSchema) {
  test::TempDir dir;
  EXPECT_EQ(run_program({RIFT_EXECUTABLE, "schema"}, {}, dir / "stdout.json"), 0);
  EXPECT_EQ(test::slurp(dir / "stdout.json"), schema().json);
  EXPECT_EQ(run_program({RIFT_EXECUTABLE, "schema", "--out", (dir / "scene.schema.json").string()}, {},
                        dir / "out.log"),
            0);
  EXPECT_EQ(test::slurp(dir / "scene.schema.json"), schema().json);
  EXPECT_NE(test::slurp(dir / "out.log").find("scene.schema.json"), std::string::npos);
  EXPECT_NE(run_program({RIFT_EXECUTABLE, "schema", "--out", (dir / "no" / "such" / "x.json").string()}, {},
                        dir / "bad.log"),
            0);
  EXPECT_EQ(run_program({RIFT_EXECUTABLE, "--help"}, {}, dir / "help.log"), 0);
  EXPECT_NE(test::slurp(dir / "help.log").find("schema"), std::string::npos);
}

}  // namespace
}  // namespace rift
