// Every file in scenes/bad/ holds known mistakes; each must be reported at its exact place with the
// key path and a recognisable expected/found text, and nothing else may be reported.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/core/error.hpp"
#include "engine/scene/load_scene.hpp"

namespace rift {
namespace {

struct Expect {
  int line, column;  // column 0: not checked
  std::string key_path, expected, found, hint;
};

struct BadScene {
  std::string file;
  std::vector<Expect> errors;
};

std::string bad_path(const std::string& name) {
  return std::string(RIFT_SOURCE_DIR) + "/scenes/bad/" + name;
}

// Lines and columns are 1-based, counted in the files as committed.
const std::vector<BadScene> kBadScenes = {
    {"unknown_key.yaml",
     {{17, 7, "solid.materials[0].dampng", "one of the keys name, regions, density, young, poisson, damping",
       "unknown key 'dampng'", "did you mean 'damping'?"}}},
    {"misspelt_section.yaml",
     {{11, 1, "soild",
       "one of the keys scene, time, mesh, solid, fluid, fluid_solid, fracture_flow, output, checkpoint",
       "unknown key 'soild'", "did you mean 'solid'?"}}},
    {"wrong_type.yaml", {{12, 12, "solid.gravity", "a list of 3 numbers", "'-9.81'", ""}}},
    {"negative_density.yaml", {{14, 16, "solid.materials[0].density", "kg/m^3, > 0", "'-2700'", ""}}},
    {"negative_mass_damping.yaml",
     {{12, 3, "solid.mass_damping", "a damping >= 0 1/s at every time", "", ""}}},
    {"poisson_half.yaml", {{16, 16, "solid.materials[0].poisson", "in [0, 0.5)", "'0.5'", ""}}},
    {"missing_mesh_file.yaml",
     {{7, 9, "mesh.file", "an existing Gmsh MSH file", "'does_not_exist.msh'",
       "scenes/bad/does_not_exist.msh"}}},
    // The position is where yaml-cpp notices the list was never closed: the next line.
    {"malformed_yaml.yaml", {{13, 12, "", "well-formed YAML", "end of sequence flow not found", ""}}},
    {"stray_comma.yaml",
     {{3, 1, "", "well-formed YAML", "a syntax error: a ',' outside a flow list [..] or mapping {..}", ""}}},
    {"ill_formed_number.yaml",
     {{15, 14, "solid.materials[0].young", "a number in Pa", "'6.0e10.5', which is not a number", ""}}},
    {"file_and_generate.yaml", {{8, 3, "mesh", "exactly one of mesh.file or mesh.generate", "both", ""}}},
    {"fracture_keys.yaml",
     {{21, 25, "solid.materials[0].fracture.friction_angle", "in [0, 90)", "'90'", ""},
      {25, 14, "solid.fracture.box_min", "box_min and box_max together (or neither)", "a list of 3 items",
       ""},
      {26, 25, "solid.fracture.integration_points", "3 or 7", "'5'", ""}}},
    {"in_situ_without_stress.yaml",
     {{19, 13, "solid.boundaries[0].type", "in_situ only with a solid.initial_stress section", "'in_situ'",
       "add solid.initial_stress"}}},
    {"box_and_cylinder.yaml",
     {{9, 5, "mesh.generate",
       "exactly one of mesh.generate.box, mesh.generate.cylinder or mesh.generate.blocks", "more than one",
       ""}}},
    {"missing_required.yaml", {{4, 1, "time.end", "(required)", "the key is missing", ""}}},
    {"joint_strength_round_off.yaml",
     {{19, 27, "solid.materials[0].fracture.tensile_strength", "at least 5e-13 x the penalty (0.2 Pa)",
       "'1.0e-300'", "lower the penalty or raise the strength"}}},
    {"block_cells_and_element_size.yaml",
     {{12, 23, "mesh.generate.blocks[0].element_size", "either cells or element_size, not both", "'0.005'",
       ""}}},
    {"boolean_yes.yaml", {{12, 12, "output.surface", "true or false", "'yes'", ""}}},
    {"unknown_boundary_type.yaml",
     {{19, 13, "solid.boundaries[0].type", "one of fixed, velocity, traction, pressure", "'fix'",
       "did you mean 'fixed'?"}}},
    {"notch_outside_box.yaml",
     {{15, 17, "mesh.generate.notches[0].center", "inside the box along y, in (0, 0.1)", "'0.15'", ""}}},
    {"duplicate_key.yaml",
     {{17, 7, "solid.materials[0].density", "each key at most once", "again (first at line 14)", ""}}},
    {"table_decreasing.yaml",
     {{20, 49, "solid.boundaries[0].value.table[2][0]", "a time > 2e-05 s", "'1.0e-5'", ""}}},
    {"three_errors.yaml",
     {{6, 11, "time.safety", "in (0, 1]", "'1.5'", ""},
      {16, 14, "solid.materials[0].young", "Pa, > 0", "'0'", ""},
      {19, 26, "output.fields[1]", "one of displacement, velocity", "'stres'", "did you mean 'stress'?"}}},
    {"forbidden_key.yaml",
     {{20, 7, "solid.boundaries[0].direction", "no 'direction' key for type pressure", "one", ""}}},
    {"fluid_unknown_key.yaml",
     {{10, 1, "fluid.viscosity", "(required)", "the key is missing", ""},
      {12, 3, "fluid.viscosty", "one of the keys mesh, density, viscosity, dt", "unknown key 'viscosty'",
       "did you mean 'viscosity'?"}}},
    {"fluid_boundaries.yaml",
     {{17, 13, "fluid.boundaries[0].type", "one of no_slip, velocity, free_slip, pressure, outflow",
       "'noslip'", "did you mean 'no_slip'?"},
      {20, 7, "fluid.boundaries[1].direction", "no 'direction' key for type no_slip", "one", ""},
      {21, 7, "fluid.boundaries[2].value", "a time function in Pa", "the key is missing", ""},
      {23, 16, "fluid.boundaries[3].surface",
       "a surface no other fluid boundary names (also in fluid.boundaries[1])", "'xmin'", ""}}},
    {"fluid_with_solid.yaml",
     {{17, 1, "fluid", "a fluid.mesh when the scene also has a solid", "a mapping",
       "the top-level mesh is the solid's"}}},
    {"fluid_pressure_without_fluid.yaml",
     {{10, 1, "solid", "no boundary of type fluid_pressure in a scene without a fluid section", "a mapping",
       "surface 'xmin' is fluid_pressure"}}},
    {"fluid_pressure_with_volume_force.yaml",
     {{11, 1, "solid", "fluid_solid.force: wetted_faces when a solid boundary is of type fluid_pressure",
       "a mapping", "would count twice"}}},
    {"fluid_solid_without_fluid.yaml",
     {{16, 1, "fluid_solid", "a fluid_solid section only in a scene with both a solid and a fluid section",
       "a mapping", "a scene with a solid only"}}},
    {"fluid_solid_coupling.yaml",
     {{28, 13, "fluid_solid.coupling", "one of sequential, concurrent", "'concurent'",
       "did you mean 'concurrent'?"}}},
    {"fluid_solid_beta_and_relaxation_time.yaml",
     {{28, 3, "fluid_solid.beta",
       "no 'beta' key with fluid_solid.relaxation_time, which sets the absorption itself (beta = fluid.dt / "
       "relaxation_time)",
       "one", ""}}},
    {"fluid_scheme_and_theta.yaml",
     {{10, 14, "fluid.mesh.generate.cells", "three whole numbers of cells >= 1", "a list of 3 items", ""},
      {15, 11, "fluid.scheme", "either theta or scheme, not both", "'crank_nicolson'", ""}}},
    {"probes.yaml",
     {{19, 12, "probes[0].field", "a field of a model in the scene (fluid.pressure needs a fluid section)",
       "'fluid.pressure'", ""},
      {24, 16, "probes[1].component", "one of xx, yy, zz, xy, yz, zx for solid.stress", "'x'", ""},
      {27, 11, "probes[2].name", "letters, digits and '_' only", "'tip.opening'", ""},
      {31, 11, "probes[3].name", "a name no other probe has", "'gauge'", "'gauge' is taken"},
      {39, 5, "probes[4].line", "either points or line, not both", "a mapping", ""},
      {39, 59, "probes[4].line.count", "an integer in [2, 100000]", "'1'", ""}}},
    {"empty.yaml",
     {{1, 1, "scene", "a section", "the key is missing", ""},
      {1, 1, "time", "a section", "the key is missing", ""},
      {1, 1, "mesh", "a section", "the key is missing", ""}}},
};

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, ReportsEveryMistakeWhereItIs) {
  const BadScene& bad = GetParam();
  const SceneLoadResult r = read_scene_file(bad_path(bad.file));
  EXPECT_FALSE(r.scene.has_value());
  ASSERT_EQ(r.errors.size(), bad.errors.size()) << (r.errors.empty() ? "" : r.errors[0].format());
  for (size_t i = 0; i < bad.errors.size(); ++i) {
    const SceneDiagnostic& got = r.errors[i];
    const Expect& want = bad.errors[i];
    SCOPED_TRACE(got.format());
    EXPECT_EQ(got.file, bad_path(bad.file));
    EXPECT_EQ(got.line, want.line);
    if (want.column) {
      EXPECT_EQ(got.column, want.column);
    }
    EXPECT_EQ(got.key_path, want.key_path);
    EXPECT_NE(got.expected.find(want.expected), std::string::npos);
    EXPECT_NE(got.found.find(want.found), std::string::npos);
    if (!want.hint.empty()) {
      EXPECT_NE(got.hint.find(want.hint), std::string::npos);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllBadScenes, BadSceneTest, ::testing::ValuesIn(kBadScenes), [](const auto& info) {
  std::string name = info.param.file.substr(0, info.param.file.find('.'));
  return name;
});

// Every file in scenes/bad/ is covered above, so a new bad scene cannot be added untested.
TEST(BadScenes, EveryFileIsChecked) {
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(bad_path(""))) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    const std::string name = entry.path().filename().string();
    const bool listed =
        std::any_of(kBadScenes.begin(), kBadScenes.end(), [&](const BadScene& b) { return b.file == name; });
    EXPECT_TRUE(listed) << name;
  }
  EXPECT_EQ(files, kBadScenes.size());
  EXPECT_GE(files, 14u);
}

TEST(BadScenes, LoadSceneThrowsWithOneLinePerDiagnostic) {
  try {
    load_scene(bad_path("three_errors.yaml"));
    FAIL() << "no exception";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 2);
    EXPECT_NE(
        msg.find(bad_path("three_errors.yaml") + ":6:11: time.safety: expected a number, in (0, 1], found "
                                                 "'1.5'"),
        std::string::npos)
        << msg;
    EXPECT_NE(msg.find("found 'stres' (did you mean 'stress'?)"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace rift
