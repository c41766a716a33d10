// The scene reader: typed accessors, defaults, ranges, overrides, time functions and the resolved YAML.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "engine/scene/load_scene.hpp"
#include "engine/scene/number_text.hpp"
#include "engine/scene/resolved_yaml.hpp"
#include "engine/scene/suggest.hpp"
#include "engine/scene/yaml_reader.hpp"

namespace rift {
namespace {

// The smallest valid scene: only required keys.
const std::string kMinimal = R"(scene:
  name: minimal
time:
  end: 1.0e-3
mesh:
  generate:
    box: [1, 2, 3]
    size_min: 0.1
    size_max: 0.2
)";

const std::string kWithSolid = kMinimal + R"(solid:
  materials:
    - name: rock
      density: 2700
      young: 6.0e10
      poisson: 0.25
  boundaries:
    - surface: zmin
      type: fixed
    - surface: zmax
      type: traction
      direction: [0, 0, -1]
)";

SceneLoadResult read(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  return read_scene_text(yaml, "test.yaml", "", overrides);
}

Scene read_ok(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  SceneLoadResult r = read(yaml, overrides);
  for (const auto& e : r.errors) ADD_FAILURE() << e.format();
  return r.scene.value_or(Scene{});
}

// One diagnostic, and what it says.
SceneDiagnostic read_one_error(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  SceneLoadResult r = read(yaml, overrides);
  EXPECT_EQ(r.errors.size(), 1u);
  if (r.errors.size() != 1u)
    for (const auto& e : r.errors) ADD_FAILURE() << e.format();
  return r.errors.empty() ? SceneDiagnostic{} : r.errors[0];
}

// --- Single values -----------------------------------------------------------------------------

// Reads `text` as a real through the same path the scene keys use.
std::optional<double> real_of(const std::string& text, const RealRule& rule = any_real("m")) {
  YamlParseResult p = parse_yaml_tree("v: " + text, "t");
  EXPECT_FALSE(p.error);
  ReadContext ctx;
  return read_real(ctx, p.root.entries.at(0).value, "v", rule);
}

TEST(SceneValues, NumbersAreStrict) {
  EXPECT_EQ(real_of("1.0e-3"), 1.0e-3);
  EXPECT_EQ(real_of("2700"), 2700.0);
  EXPECT_EQ(real_of("+2"), 2.0);
  EXPECT_EQ(real_of("-.5"), -0.5);
  EXPECT_EQ(real_of("6.0E10"), 6.0e10);
  for (const char* bad : {"1.0e-3.5", "12abc", ".", "nan", "inf", "-inf", ".inf", ".nan", "0x10", "1e999",
                          "1,5", "'3'", "\"3\"", "[1]", "{a: 1}", "", "1 000"})
    EXPECT_FALSE(real_of(bad).has_value()) << bad;
}

TEST(SceneValues, RangesHonourOpenAndClosedBounds) {
  const RealRule poisson{"", 0.0, 0.5, false, true};  // [0, 0.5)
  EXPECT_TRUE(real_of("0", poisson));
  EXPECT_TRUE(real_of("0.4999", poisson));
  EXPECT_FALSE(real_of("0.5", poisson));
  EXPECT_FALSE(real_of("-1e-300", poisson));
  EXPECT_FALSE(real_of("0", positive("s")));
  EXPECT_TRUE(real_of("0", non_negative("s")));
  EXPECT_EQ(poisson.describe(), "a number, in [0, 0.5)");
  EXPECT_EQ(positive("Pa").describe(), "a number in Pa, > 0");
  EXPECT_EQ(non_negative("s").describe(), "a number in s, >= 0");
}

TEST(SceneValues, BooleansAreOnlyTrueAndFalse) {
  for (const char* bad : {"yes", "no", "on", "off", "y", "True", "FALSE", "1", "\"true\""}) {
    SceneDiagnostic d = read_one_error(kMinimal + "output:\n  surface: " + bad + "\n");
    EXPECT_EQ(d.key_path, "output.surface") << bad;
    EXPECT_EQ(d.expected, "true or false");
    EXPECT_EQ(d.line, 11);
    EXPECT_EQ(d.column, 12);
  }
  EXPECT_TRUE(read_ok(kMinimal + "output:\n  surface: true\n").output.surface);
}

TEST(SceneValues, IntegersRejectFractionsAndRange) {
  EXPECT_EQ(read_ok(kMinimal + "checkpoint:\n  every_steps: 250\n").checkpoint.every_steps, 250);
  EXPECT_EQ(read_one_error(kMinimal + "checkpoint:\n  every_steps: 2.5\n").found,
            "'2.5', which is not an integer");
  EXPECT_EQ(read_one_error(kMinimal + "checkpoint:\n  keep: 0\n").expected, "an integer in [1, 2147483647]");
  EXPECT_EQ(read_one_error(kMinimal + "checkpoint:\n  every_steps: -1\n").expected, "an integer >= 0");
}

TEST(SceneValues, ChoicesSuggestTheClosestName) {
  SceneDiagnostic d =
      read_one_error(kWithSolid + "    - surface: x\n      type: velocty\n      direction: [1, 0, 0]\n");
  EXPECT_EQ(d.key_path, "solid.boundaries[2].type");
  EXPECT_EQ(d.hint, "did you mean 'velocity'?");
  EXPECT_EQ(d.line, 23);
  EXPECT_EQ(d.column, 13);
}

TEST(SceneValues, EditDistanceCountsSwapsAsOneEdit) {
  EXPECT_EQ(edit_distance("soild", "solid"), 1);
  EXPECT_EQ(edit_distance("densty", "density"), 1);
  EXPECT_EQ(edit_distance("", "abc"), 3);
  const std::vector<std::string> keys{"scene", "time", "mesh", "solid"};
  EXPECT_EQ(closest_match("soild", keys), "solid");
  EXPECT_EQ(closest_match("fluid", keys), "");  // 3 edits from "solid": not a likely typo
}

TEST(SceneValues, ShortestRealsReadBackBitIdentical) {
  for (double v : {0.1, 1.0 / 3.0, 6.02214076e23, 1e-300, 2700.0, 5e-324, -2.5e-8}) {
    double back = 0.0;
    ASSERT_EQ(parse_real_text(yaml_real(v), back), NumberParse::ok) << yaml_real(v);
    EXPECT_EQ(back, v);
  }
  EXPECT_EQ(yaml_real(2700.0), "2700.0");
  EXPECT_EQ(yaml_real(1e-8), "1.0e-08");
  EXPECT_EQ(yaml_real(6e10), "6.0e+10");
  EXPECT_EQ(yaml_real(-0.0), "0.0");
}

TEST(SceneValues, Fnv1aMatchesReferenceVectors) {
  // Published FNV-1a 64 test vectors (offset basis for "", and "a").
  EXPECT_EQ(fnv1a64_hex(""), "cbf29ce484222325");
  EXPECT_EQ(fnv1a64_hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(fnv1a64_hex("foobar"), "85944171f73967e8");
}

TEST(SceneValues, DiagnosticFormat) {
  SceneDiagnostic d{"bar.yaml", 12, 5, "solid.materials[0].density", "a number in kg/m^3, > 0", "'-1'", ""};
  EXPECT_EQ(d.format(),
            "bar.yaml:12:5: solid.materials[0].density: expected a number in kg/m^3, > 0, found '-1'");
  d.hint = "did you mean 'x'?";
  EXPECT_EQ(d.format(),
            "bar.yaml:12:5: solid.materials[0].density: expected a number in kg/m^3, > 0, found '-1' "
            "(did you mean 'x'?)");
  SceneDiagnostic o{"--set time.end=-1", 0, 0, "time.end", "a number in s, > 0", "'-1'", ""};
  EXPECT_EQ(o.format(), "--set time.end=-1: time.end: expected a number in s, > 0, found '-1'");
}

// --- Defaults ------------------------------------------------------------------------------------

TEST(SceneDefaults, MinimalSceneGetsEveryDefault) {
  Scene s = read_ok(kMinimal);
  EXPECT_EQ(s.name, "minimal");
  EXPECT_EQ(s.description, "");
  EXPECT_EQ(s.source_file, "test.yaml");
  EXPECT_EQ(s.time.end, 1.0e-3);
  EXPECT_FALSE(s.time.dt.has_value());
  EXPECT_EQ(s.time.safety, 0.5);
  EXPECT_FALSE(s.time.allow_unstable_dt);
  EXPECT_FALSE(s.mesh.file.has_value());
  EXPECT_EQ(s.mesh.scale, 1.0);
  ASSERT_TRUE(s.mesh.generate.has_value());
  EXPECT_EQ(s.mesh.generate->size, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(s.mesh.generate->origin, (std::array<double, 3>{0, 0, 0}));
  EXPECT_EQ(s.mesh.generate->grading, 0.5);
  EXPECT_EQ(s.mesh.generate->seed, 1u);
  EXPECT_TRUE(s.mesh.generate->notches.empty());
  EXPECT_FALSE(s.solid.has_value());
  EXPECT_EQ(s.output.interval, 0.0);
  EXPECT_TRUE(s.output.fields.empty());
  EXPECT_FALSE(s.output.surface);
  EXPECT_EQ(s.checkpoint.every_steps, 0);
  EXPECT_EQ(s.checkpoint.every_seconds, 0.0);
  EXPECT_EQ(s.checkpoint.keep, 2);
  EXPECT_EQ(s.hash.size(), 16u);
}

TEST(SceneDefaults, SolidDefaults) {
  Scene s = read_ok(kWithSolid);
  ASSERT_TRUE(s.solid.has_value());
  EXPECT_EQ(s.solid->gravity, (std::array<double, 3>{0, 0, 0}));
  const MaterialSpec& m = s.solid->materials.at(0);
  EXPECT_EQ(m.regions, std::vector<std::string>{"all"});
  EXPECT_EQ(m.damping, 0.0);
  EXPECT_EQ(m.young, 6.0e10);
  const auto& fixed = s.solid->boundaries.at(0);
  EXPECT_EQ(fixed.kind, SolidBoundarySpec::Kind::fixed);
  EXPECT_EQ(fixed.components, (std::array<bool, 3>{true, true, true}));
  const auto& traction = s.solid->boundaries.at(1);
  EXPECT_EQ(traction.kind, SolidBoundarySpec::Kind::traction);
  EXPECT_EQ(traction.direction, (std::array<double, 3>{0, 0, -1}));
  EXPECT_EQ(traction.function.kind, TimeFunction::Kind::constant);
  EXPECT_EQ(traction.function(0.5), 1.0);
}

TEST(SceneDefaults, NotchIsReadAndChecked) {
  const std::string notch = R"(mesh:
  generate:
    box: [0.049, 0.1, 0.05]
    size_min: 0.002
    size_max: 0.005
    notches:
      - {shape: slot, face: xmin, opening_axis: y, center: 0.05, depth: 0.0245, opening: 0.00245}
)";
  const std::string head = "scene: {name: n}\ntime: {end: 1}\n";
  Scene s = read_ok(head + notch);
  const NotchSpec& n = s.mesh.generate->notches.at(0);
  EXPECT_EQ(n.shape, NotchSpec::Shape::slot);
  EXPECT_EQ(n.face, "xmin");
  EXPECT_EQ(n.opening_axis, 1);
  EXPECT_EQ(n.depth, 0.0245);
  EXPECT_EQ(n.name, "notch");
  // Depth equal to the box along x (0.049) cuts the box in two; opening 0.1 sticks out of 0 .. 0.1.
  EXPECT_EQ(read_one_error(head + notch, {"mesh.generate.notches[0].depth=0.049"}).key_path,
            "mesh.generate.notches[0].depth");
  EXPECT_EQ(read_one_error(head + notch, {"mesh.generate.notches[0].opening=0.1"}).key_path,
            "mesh.generate.notches[0].opening");
  EXPECT_EQ(read_one_error(head + notch, {"mesh.generate.notches[0].opening_axis=x"}).key_path,
            "mesh.generate.notches[0].opening_axis");
}

TEST(SceneDefaults, CylinderIsReadAndChecked) {
  const std::string head = "scene: {name: n}\ntime: {end: 1}\n";
  const std::string disc =
      "mesh:\n  generate:\n    cylinder: {diameter: 0.05, thickness: 0.025}\n"
      "    size_min: 0.002\n    size_max: 0.005\n";
  const MeshGenerateSpec g = *read_ok(head + disc).mesh.generate;
  EXPECT_EQ(g.shape, MeshGenerateSpec::Shape::cylinder);
  EXPECT_EQ(g.cylinder.diameter, 0.05);
  EXPECT_EQ(g.cylinder.thickness, 0.025);
  EXPECT_EQ(g.cylinder.load_arc, 10.0);
  EXPECT_EQ(read_ok(kMinimal).mesh.generate->shape, MeshGenerateSpec::Shape::box);
  const SceneDiagnostic arc = read_one_error(head + disc, {"mesh.generate.cylinder.load_arc=90"});
  EXPECT_EQ(arc.key_path, "mesh.generate.cylinder.load_arc");
  EXPECT_EQ(arc.expected, "a number in deg, in (0, 90)");
  EXPECT_EQ(read_one_error(head + disc, {"mesh.generate.cylinder.diameter=0"}).key_path,
            "mesh.generate.cylinder.diameter");
  const SceneDiagnostic notch = read_one_error(head + disc, {"mesh.generate.notches=[]"});
  EXPECT_EQ(notch.key_path, "mesh.generate.notches");
  EXPECT_EQ(notch.line, 0);  // given by --set
  const SceneDiagnostic neither = read_one_error(head + "mesh: {generate: {size_min: 1, size_max: 1}}\n");
  EXPECT_EQ(neither.key_path, "mesh.generate");
  EXPECT_EQ(neither.found, "none");
}

// --- Overrides -----------------------------------------------------------------------------------

TEST(SceneOverrides, ReplaceCreateAndIndex) {
  Scene s = read_ok(
      kWithSolid, {"time.end=2.5e-3", "solid.materials[0].density=3000", "time.dt=1e-8", "checkpoint.keep=5",
                   "solid.gravity=[0, 0, -9.81]",
                   "solid.boundaries[1].value={ramp: {value: 0, start_time: 0, rate: 2}}", "time.end=3e-3"});
  EXPECT_EQ(s.time.end, 3e-3);  // the later override wins
  EXPECT_EQ(s.solid->materials[0].density, 3000.0);
  EXPECT_EQ(s.time.dt, 1e-8);       // key created in an existing section
  EXPECT_EQ(s.checkpoint.keep, 5);  // section created
  EXPECT_EQ(s.solid->gravity[2], -9.81);
  EXPECT_EQ(s.solid->boundaries[1].function(1.5), 3.0);
}

TEST(SceneOverrides, AppendsAListItem) {
  Scene s = read_ok(kWithSolid, {"solid.materials[1]={name: clay, density: 1800, young: 1e8, poisson: 0.3}"});
  ASSERT_EQ(s.solid->materials.size(), 2u);
  EXPECT_EQ(s.solid->materials[1].name, "clay");
}

// key=null removes what the path names, so the scene reads as if it had never been written: a key takes
// its default, a list item goes, a section goes; a path that names nothing removes nothing.
TEST(SceneOverrides, NullRemovesTheKey) {
  Scene s = read_ok(kWithSolid, {"time.dt=1e-8", "time.dt=null", "solid.boundaries[1]=~", "time.safety=0.25",
                                 "time.safety=null", "checkpoint.keep=null"});
  EXPECT_FALSE(s.time.dt > 0.0);  // not set again
  ASSERT_EQ(s.solid->boundaries.size(), 1u);
  EXPECT_EQ(s.time.safety, read_ok(kMinimal).time.safety);  // the default
  EXPECT_FALSE(read_ok(kWithSolid, {"solid=null"}).solid);
  // Required keys are still required once removed.
  EXPECT_EQ(read_one_error(kWithSolid, {"solid.materials[0].poisson=null"}).key_path,
            "solid.materials[0].poisson");
  EXPECT_EQ(read_one_error(kMinimal, {"scene.name.first=null"}).expected,
            "a path through mappings and lists to remove");
}

TEST(SceneOverrides, UnknownKeyIsReportedAtTheOverride) {
  SceneDiagnostic d = read_one_error(kWithSolid, {"solid.materials[0].densty=3000"});
  EXPECT_EQ(d.file, "--set solid.materials[0].densty=3000");
  EXPECT_EQ(d.line, 0);
  EXPECT_EQ(d.key_path, "solid.materials[0].densty");
  EXPECT_EQ(d.hint, "did you mean 'density'?");
  EXPECT_EQ(d.format().rfind("--set solid.materials[0].densty=3000: solid.materials[0].densty: expected", 0),
            0u);
}

TEST(SceneOverrides, BadValuesAndMalformedOverrides) {
  SceneDiagnostic bad_value = read_one_error(kMinimal, {"time.end=-1"});
  EXPECT_EQ(bad_value.file, "--set time.end=-1");
  EXPECT_EQ(bad_value.key_path, "time.end");
  EXPECT_EQ(read_one_error(kMinimal, {"time.end"}).found, "no '=' in 'time.end'");
  EXPECT_EQ(read_one_error(kMinimal, {"time..end=1"}).found, "the key path 'time..end'");
  EXPECT_EQ(read_one_error(kMinimal, {"time.end=[1"}).expected, "a YAML value after '='");
  EXPECT_EQ(read_one_error(kWithSolid, {"solid.materials[3].density=1"}).key_path, "solid.materials[3]");
  EXPECT_EQ(read_one_error(kMinimal, {"scene.name.first=1"}).expected, "a mapping to set 'first' in");
}

TEST(SceneOverrides, IndexTooLargeForAnIndexIsReported) {
  // 2^64 and beyond do not fit a list index; the path is reported, not the conversion's exception.
  for (const std::string index : {"18446744073709551616", "99999999999999999999"}) {
    const std::string text = "solid.materials[" + index + "].density=1";
    const SceneDiagnostic d = read_one_error(kWithSolid, {text});
    EXPECT_EQ(d.format(), "--set " + text + ": solid.materials[" + index +
                              "]: expected a list index, found index " + index + ", which is out of range");
  }
  // The largest index that fits is an index: the list is too short for it.
  const SceneDiagnostic fits =
      read_one_error(kWithSolid, {"solid.materials[18446744073709551615].density=1"});
  EXPECT_EQ(fits.key_path, "solid.materials[18446744073709551615]");
  EXPECT_EQ(fits.found, "index 18446744073709551615");
}

// --- Time functions ------------------------------------------------------------------------------

std::string pressure(const std::string& value) {
  return kWithSolid + "    - surface: p\n      type: pressure\n      value: " + value + "\n";
}

TEST(SceneTimeFunctions, ConstantRampTable) {
  Scene c = read_ok(pressure("15.0e6"));
  EXPECT_EQ(c.solid->boundaries[2].function(7.0), 15.0e6);

  // value 1e6 until 1e-4 s, then +2e10 Pa/s, capped at 5e6: reaches the cap at 1e-4 + 4e6/2e10 = 3e-4 s.
  Scene r = read_ok(pressure("{ramp: {value: 1.0e6, start_time: 1.0e-4, rate: 2.0e10, limit: 5.0e6}}"));
  const TimeFunction& ramp = r.solid->boundaries[2].function;
  EXPECT_EQ(ramp.kind, TimeFunction::Kind::ramp);
  EXPECT_TRUE(ramp.has_limit);
  EXPECT_EQ(ramp(0.0), 1.0e6);
  EXPECT_DOUBLE_EQ(ramp(2.0e-4), 3.0e6);  // 1e6 + 2e10 * 1e-4; DOUBLE_EQ for the rounding of 2e-4 - 1e-4
  EXPECT_EQ(ramp(1.0), 5.0e6);

  Scene t = read_ok(pressure("{table: [[0, 0], [1.0e-3, 1.0e6], [2.0e-3, 0]]}"));
  const TimeFunction& table = t.solid->boundaries[2].function;
  ASSERT_EQ(table.points.size(), 3u);
  EXPECT_DOUBLE_EQ(table(0.5e-3), 0.5e6);
  EXPECT_EQ(table(5.0), 0.0);
}

TEST(SceneTimeFunctions, Errors) {
  EXPECT_EQ(read_one_error(pressure("{ramp: {value: 1, start_time: 0}}")).key_path,
            "solid.boundaries[2].value.ramp.rate");
  EXPECT_EQ(read_one_error(pressure("{table: [[0, 1]]}")).expected,
            "a list of at least 2 [time in s, value in Pa] pairs");
  EXPECT_EQ(read_one_error(pressure("{table: [[0, 1], [1]]}")).key_path,
            "solid.boundaries[2].value.table[1]");
  EXPECT_EQ(read_one_error(pressure("{table: [[0, 1], [0, 2]]}")).key_path,
            "solid.boundaries[2].value.table[1][0]");
  EXPECT_EQ(read_one_error(pressure("{rmap: {value: 1}}")).hint, "did you mean 'ramp'?");
  EXPECT_EQ(read_one_error(pressure("{ramp: {value: 5, start_time: 0, rate: 1, limit: 4}}")).key_path,
            "solid.boundaries[2].value.ramp.limit");
  // A pressure has no default value.
  SceneDiagnostic missing = read_one_error(kWithSolid + "    - surface: p\n      type: pressure\n");
  EXPECT_EQ(missing.key_path, "solid.boundaries[2].value");
  EXPECT_EQ(missing.line, 22);  // the item's first key
}

// --- Resolved YAML -------------------------------------------------------------------------------

TEST(SceneResolved, RoundTripGivesTheSameHash) {
  const std::string full =
      pressure("{table: [[0, 0], [1.0e-3, 1.0e6]]}") +
      "    - surface: v\n      type: velocity\n      components: [y]\n"
      "      direction: [0.1, 0, 0]\n      value: {ramp: {value: 0, start_time: 0, rate: 3}}\n"
      "output: {interval: 1.0e-4, fields: [stress, damage], surface: true}\n"
      "checkpoint: {every_steps: 100, every_seconds: 600, keep: 3}\n";
  const Scene first = read_ok(full, {"scene.description='quoted \"text\", with: colons'", "time.dt=3.3e-9",
                                     "mesh.generate.notches[0]={shape: wedge, face: ymax, opening_axis: z, "
                                     "center: 1.5, depth: 0.5, opening: 0.1, name: cut}"});
  const Scene again = read_ok(first.resolved_yaml);
  EXPECT_EQ(again.resolved_yaml, first.resolved_yaml);
  EXPECT_EQ(again.hash, first.hash);
  EXPECT_EQ(again.description, "quoted \"text\", with: colons");
  EXPECT_EQ(again.time.dt, 3.3e-9);
  EXPECT_EQ(again.mesh.generate->notches.at(0).name, "cut");
  EXPECT_EQ(again.solid->boundaries[3].components, (std::array<bool, 3>{false, true, false}));
  EXPECT_FALSE(again.solid->boundaries[3].function.has_limit);
  EXPECT_EQ(again.output.fields, (std::vector<std::string>{"stress", "damage"}));
  // Anything that changes the scene changes the hash; layout and comments of the source do not.
  EXPECT_NE(read_ok(full, {"time.end=2e-3"}).hash, read_ok(full).hash);
  EXPECT_EQ(read_ok("# comment\n" + full).hash, read_ok(full).hash);
}

TEST(SceneResolved, EveryKeyIsWritten) {
  const std::string y = read_ok(kWithSolid).resolved_yaml;
  for (const char* key : {"name:",        "description:",
                          "end:",         "dt: null",
                          "safety:",      "allow_unstable_dt:",
                          "scale:",       "box:",
                          "origin:",      "size_min:",
                          "size_max:",    "grading:",
                          "seed:",        "notches: []",
                          "gravity:",     "regions: [\"all\"]",
                          "damping:",     "components: [x, y, z]",
                          "value: 1.0",   "interval:",
                          "fields: []",   "surface: false",
                          "every_steps:", "every_seconds:",
                          "keep:"})
    EXPECT_NE(y.find(key), std::string::npos) << key << "\n" << y;
}

// --- Mesh files ----------------------------------------------------------------------------------

class SceneMeshFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("rift_scene_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_ / "meshes");
    std::ofstream(dir_ / "meshes" / "bar.msh") << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
    std::ofstream(dir_ / "scene.yaml") << "scene: {name: f}\ntime: {end: 1}\nmesh:\n  file: meshes/bar.msh\n"
                                          "  scale: 1.0e-3\n";
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(SceneMeshFile, RelativePathStartsAtTheSceneFolder) {
  SceneLoadResult r = read_scene_file((dir_ / "scene.yaml").string());
  ASSERT_TRUE(r.scene) << r.errors.at(0).format();
  EXPECT_EQ(*r.scene->mesh.file, (dir_ / "meshes" / "bar.msh").lexically_normal().string());
  EXPECT_EQ(r.scene->mesh.scale, 1.0e-3);
  EXPECT_EQ(r.scene->source_file, (dir_ / "scene.yaml").string());
  // The resolved scene names the file absolutely, so it reads back from anywhere.
  SceneLoadResult again = read_scene_text(r.scene->resolved_yaml, "elsewhere.yaml", "/");
  ASSERT_TRUE(again.scene);
  EXPECT_EQ(again.scene->hash, r.scene->hash);
}

TEST_F(SceneMeshFile, MissingFileNamesTheResolvedPath) {
  SceneLoadResult r = read_scene_file((dir_ / "scene.yaml").string(), {"mesh.file=nope.msh"});
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].key_path, "mesh.file");
  EXPECT_NE(r.errors[0].hint.find((dir_ / "nope.msh").string()), std::string::npos) << r.errors[0].format();
}

TEST_F(SceneMeshFile, TheHashCoversTheMeshFileContent) {
  // The same path with other bytes is another scene: a restart must not continue on a replaced mesh.
  const std::string scene = (dir_ / "scene.yaml").string();
  const std::string first = read_scene_file(scene).scene->hash;
  std::ofstream(dir_ / "meshes" / "bar.msh")
      << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Comments\nx\n$EndComments\n";
  const SceneLoadResult changed = read_scene_file(scene);
  ASSERT_TRUE(changed.scene);
  EXPECT_NE(changed.scene->hash, first);
  EXPECT_NE(changed.scene->hash, fnv1a64_hex(changed.scene->resolved_yaml));
  EXPECT_EQ(changed.scene->resolved_yaml, read_scene_file(scene).scene->resolved_yaml)
      << "the YAML is the same";
  std::ofstream(dir_ / "meshes" / "bar.msh") << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  EXPECT_EQ(read_scene_file(scene).scene->hash, first);
  // A scene without mesh files hashes its resolved YAML alone.
  const Scene generated = read_ok(kMinimal);
  EXPECT_EQ(generated.hash, fnv1a64_hex(generated.resolved_yaml));
}

TEST_F(SceneMeshFile, AFileAboveMaxFileBytesIsAnErrorOfMeshFile) {
  SceneLoadResult r = read_scene_file((dir_ / "scene.yaml").string(), {"mesh.max_file_bytes=10"});
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].key_path, "mesh.file");
  EXPECT_NE(r.errors[0].hint.find("the mesh file is 35 bytes, above the limit of 10 bytes (raise it with "
                                  "mesh.max_file_bytes)"),
            std::string::npos)
      << r.errors[0].format();
  const SceneLoadResult ok = read_scene_file((dir_ / "scene.yaml").string(), {"mesh.max_file_bytes=35"});
  ASSERT_TRUE(ok.scene);
  EXPECT_EQ(ok.scene->mesh.max_file_bytes, 35u);
  EXPECT_NE(ok.scene->resolved_yaml.find("  max_file_bytes: 35\n"), std::string::npos)
      << ok.scene->resolved_yaml;
}

TEST(SceneFile, MalformedYamlAndExtraDocumentsAreOneDiagnostic) {
  SceneDiagnostic syntax = read_one_error("scene:\n  name: [a\ntime: {end: 1}\n");
  EXPECT_EQ(syntax.expected, "well-formed YAML");
  EXPECT_EQ(syntax.line, 3);
  SceneDiagnostic second = read_one_error(kMinimal + "---\nscene: {name: other}\n");
  EXPECT_EQ(second.expected, "a single YAML document");
  EXPECT_EQ(second.line, 10);  // the '---' that starts it
}

TEST(SceneFile, UnreadableFileIsADiagnostic) {
  SceneLoadResult r = read_scene_file("/nonexistent/scene.yaml");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].expected, "a readable scene file");
}

// A device or a file far larger than any scene is refused before it is read whole or parsed.
TEST(SceneFile, ADeviceIsRefusedWithoutReadingIt) {
  SceneLoadResult r = read_scene_file("/dev/zero");
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].expected, "a readable scene file");
  EXPECT_NE(r.errors[0].found.find("not a regular file"), std::string::npos) << r.errors[0].format();
}

TEST(SceneFile, AFileAboveTheSizeLimitIsRefused) {
  const auto path = std::filesystem::temp_directory_path() / ("rift_big_scene_" + std::to_string(::getpid()));
  {
    std::ofstream out(path);
    const std::string line = "# a comment line that pads the file\n";
    for (uint64_t n = 0; n <= scene_file_max_bytes / line.size(); ++n) out << line;
  }
  SceneLoadResult r = read_scene_file(path.string());
  std::filesystem::remove(path);
  ASSERT_EQ(r.errors.size(), 1u);
  EXPECT_EQ(r.errors[0].file, path.string());
  EXPECT_NE(r.errors[0].found.find("above the limit of " + std::to_string(scene_file_max_bytes) + " bytes"),
            std::string::npos)
      << r.errors[0].format();
}

}  // namespace
}  // namespace rift
