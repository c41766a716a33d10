#include "engine/schedule/step_plan.hpp"

#include <fmt/format.h>

#include "engine/core/error.hpp"

namespace rift {

StepPlan& StepPlan::add(StepStage stage) {
  if (stage.every < 1)
    throw Error(fmt::format("internal: step stage '{}' runs every {} steps", stage.name, stage.every));
  stages_.push_back(std::move(stage));
  return *this;
}

StepPlan& StepPlan::graph(std::string name, std::vector<System*> systems, int64_t every) {
  std::erase(systems, nullptr);
  StepStage stage{StepStage::Kind::graph, std::move(name), every, std::move(systems)};
  if (stage.systems.empty()) return *this;  // the scene has none of them
  return add(std::move(stage));
}

StepPlan& StepPlan::beside(std::string name, BackgroundWork& work, int64_t every) {
  return add({StepStage::Kind::beside, std::move(name), every, {}, &work});
}

StepPlan& StepPlan::after(std::string name, int64_t every, std::function<void(const StepContext&)> run) {
  return add({StepStage::Kind::after, std::move(name), every, {}, nullptr, std::move(run)});
}

std::vector<System*> StepPlan::graph_systems() const {
  std::vector<System*> all;
  for (const auto& s : stages_)
    if (s.kind == StepStage::Kind::graph) all.insert(all.end(), s.systems.begin(), s.systems.end());
  return all;
}

std::vector<int64_t> StepPlan::graph_periods() const {
  std::vector<int64_t> all;
  for (const auto& s : stages_)
    if (s.kind == StepStage::Kind::graph) all.insert(all.end(), s.systems.size(), s.every);
  return all;
}

std::vector<BackgroundWork*> StepPlan::background() const {
  std::vector<BackgroundWork*> all;
  for (const auto& s : stages_)
    if (s.kind == StepStage::Kind::beside) all.push_back(s.work);
  return all;
}

std::string StepPlan::script() const {
  std::string out;
  int number = 0;
  for (const auto& s : stages_) {
    if (!out.empty()) out += "\n";
    out += fmt::format("{:>3}. {}", ++number, s.name);
    if (s.kind == StepStage::Kind::graph) {
      out += ":";
      for (size_t i = 0; i < s.systems.size(); ++i) out += (i ? ", " : " ") + s.systems[i]->name();
    } else {
      out += s.kind == StepStage::Kind::beside ? " (beside the graph)" : " (after the graph)";
    }
    if (s.every > 1) out += fmt::format(" | every {} steps", s.every);
  }
  return out;
}

}  // namespace rift
