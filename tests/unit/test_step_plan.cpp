// The step plan (engine/schedule/step_plan.hpp): stages in script order, and the run loop following them
// (graph systems per window, work beside the graph launched at a window's start and joined at its end,
// work after the graph), and the composition root's scripts for the example scenes.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "engine/run_loop.hpp"
#include "engine/scene/load_scene.hpp"
#include "systems/world_builder.hpp"
#include "tests/unit/test_run_support.hpp"

using namespace rift;

namespace {

class Recorder : public System {
 public:
  Recorder(std::string name, Access access, std::vector<std::string>& log)
      : name_(std::move(name)), access_(std::move(access)), log_(log) {}
  std::string name() const override { return name_; }
  Access access() const override { return access_; }
  void run(const StepContext& ctx) override { log_.push_back(name_ + "@" + std::to_string(ctx.step)); }

 private:
  std::string name_;
  Access access_;
  std::vector<std::string>& log_;
};

class RecordedWork : public BackgroundWork {
 public:
  explicit RecordedWork(std::vector<std::string>& log, Access access = {}) : log_(log), access_(access) {}
  void launch(const StepContext& at) override {
    running_ = true;
    log_.push_back("launch@" + std::to_string(at.step));
  }
  void join() override {
    if (running_) log_.push_back("join");
    running_ = false;
  }
  Access access() const override { return access_; }

 private:
  std::vector<std::string>& log_;
  Access access_;
  bool running_ = false;
};

Scene ten_steps() {
  const auto r = read_scene_text(
      "scene: {name: plan}\ntime: {end: 1.0e-6, dt: 1.0e-7}\n"
      "mesh: {generate: {box: [0.02, 0.02, 0.02], size_min: 0.01, size_max: 0.01}}\n",
      "inline", ".");
  if (!r.scene) throw std::runtime_error(r.errors.front().format());
  return *r.scene;
}

}  // namespace

TEST(StepPlan, KeepsScriptOrderDropsAbsentSystemsAndGivesEachItsWindow) {
  std::vector<std::string> log;
  Recorder a("a", {{}, {"t.x"}}, log), b("b", {{"t.x"}, {"t.y"}}, log);
  RecordedWork work(log);
  StepPlan plan;
  plan.graph("forces", {&a, nullptr})
      .graph("nothing here", {nullptr})
      .graph("window", {&b}, 4)
      .beside("beside", work, 4)
      .after("after", 4, [](const StepContext&) {});
  ASSERT_EQ(plan.stages().size(), 4u);  // the empty stage is dropped
  EXPECT_EQ(plan.graph_systems(), (std::vector<System*>{&a, &b}));
  EXPECT_EQ(plan.graph_periods(), (std::vector<int64_t>{1, 4}));
  EXPECT_EQ(plan.background(), (std::vector<BackgroundWork*>{&work}));
  const std::string script = plan.script();
  EXPECT_NE(script.find("1. forces: a"), std::string::npos) << script;
  EXPECT_NE(script.find("2. window: b | every 4 steps"), std::string::npos) << script;
  EXPECT_NE(script.find("3. beside (beside the graph) | every 4 steps"), std::string::npos) << script;
  EXPECT_NE(script.find("4. after (after the graph) | every 4 steps"), std::string::npos) << script;
  EXPECT_THROW(plan.graph("never", {&a}, 0), Error);
}

TEST(StepPlan, TheRunLoopLaunchesBesideWorkAtAWindowsStartAndJoinsItBeforeTheAfterStagesAtItsEnd) {
  for (int threads : {1, 2}) {
    std::vector<std::string> log;
    Recorder every("every", {{}, {"t.x"}}, log), windowed("windowed", {{"t.x"}, {"t.y"}}, log);
    RecordedWork work(log, {{"w.in"}, {"w.out"}});
    RunLoop run(ten_steps(), test::quiet_options(threads), [&](const Scene&) {
      auto world = std::make_unique<World>();
      world->plan.graph("every step", {&every})
          .graph("window", {&windowed}, 5)
          .beside("beside", work, 5)
          .after("after", 5,
                 [&](const StepContext& taken) { log.push_back("after@" + std::to_string(taken.step)); });
      return world;
    });
    ASSERT_TRUE(run.run().completed);
    const std::vector<std::string> expected{
        "launch@0", "every@0", "every@1", "every@2", "every@3", "every@4", "windowed@4", "join", "after@4",
        "launch@5", "every@5", "every@6", "every@7", "every@8", "every@9", "windowed@9", "join", "after@9"};
    EXPECT_EQ(log, expected) << threads << " threads";
  }
}

TEST(StepPlan, ARunRefusesWorkBesideTheGraphThatAGraphSystemAlsoWrites) {
  std::vector<std::string> log;
  Recorder writer("writer", {{}, {"w.in"}}, log);
  RecordedWork work(log, {{"w.in"}, {"w.out"}});
  try {
    RunLoop run(ten_steps(), test::quiet_options(), [&](const Scene&) {
      auto world = std::make_unique<World>();
      world->plan.graph("writes what the work reads", {&writer}).beside("beside", work, 5);
      return world;
    });
    FAIL() << "expected the conflict to be refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'beside'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("w.in"), std::string::npos) << e.what();
  }
}

// The composition root's scripts: what a newcomer reads in the log, for a dry solid, the sequential and
// the concurrent coupling. A change to the order of a step shows here first.
TEST(StepPlan, TheCompositionRootScriptsEachConfiguration) {
  auto script_of = [](const std::string& file, std::vector<std::string> overrides = {}) {
    return build_world(load_scene(std::string(RIFT_SOURCE_DIR) + "/scenes/" + file, overrides))
        ->plan.script();
  };
  const std::string dry = script_of("examples/elastic_bar.yaml");
  EXPECT_EQ(dry,
            "  1. forces on the solid: surface loads, tets, joints (and fracture), contact: surface_loads, "
            "tet_forces\n"
            "  2. the node pass: gather the forces, integrate: node_integration");  // no fluid, no joints
  const std::string sequential = script_of("validation/immersed_block_adaptive.yaml");
  EXPECT_NE(sequential.find("3. fluid window: the solid to the fluid, the fluid's step, the fluid's force to "
                            "the solid: solid_to_fluid, fluid_step, fluid_to_solid | every"),
            std::string::npos)
      << sequential;
  EXPECT_NE(sequential.find("4. the fluid's mesh remade around the solid (after the graph)"),
            std::string::npos)
      << sequential;
  EXPECT_NE(sequential.find("5. the solid to the new fluid mesh (after the graph)"), std::string::npos)
      << sequential;
  const std::string concurrent =
      script_of("validation/immersed_block_adaptive.yaml", {"fluid_solid.coupling=concurrent"});
  for (const char* stage : {"3. the fluid's step, beside the window's solid steps (beside the graph)",
                            "4. the fluid's force to the solid (after the graph)",
                            "5. the fluid's mesh remade around the solid (after the graph)",
                            "6. the solid to the fluid (after the graph)"})
    EXPECT_NE(concurrent.find(stage), std::string::npos) << stage << "\n" << concurrent;
  EXPECT_EQ(concurrent.find("fluid_step"), std::string::npos) << concurrent;  // not in the graph
}

// docs/architecture.md quotes the step script from the source: every line of its C++ blocks under "The
// step" is a line of systems/step_script.cpp, so the quote cannot drift from the code.
TEST(StepPlan, TheArchitectureDocQuotesTheScriptAsTheSourceHasIt) {
  auto read = [](const std::string& path) {
    std::ifstream in(std::string(RIFT_SOURCE_DIR) + "/" + path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string doc = read("docs/architecture.md");
  const std::string source = read("systems/step_script.cpp");
  const size_t section = doc.find("## The step\n");
  ASSERT_NE(section, std::string::npos);
  const std::string text = doc.substr(section, doc.find("\n## ", section + 1) - section);
  size_t quoted = 0;
  for (size_t open = text.find("```cpp\n"); open != std::string::npos; open = text.find("```cpp\n", open)) {
    const size_t begin = open + 7, end = text.find("```", begin);
    std::istringstream block(text.substr(begin, end - begin));
    for (std::string line; std::getline(block, line);) {
      EXPECT_NE(source.find(line + "\n"), std::string::npos) << "not in systems/step_script.cpp: " << line;
      ++quoted;
    }
    open = end + 3;
  }
  EXPECT_GT(quoted, 30u);
}
