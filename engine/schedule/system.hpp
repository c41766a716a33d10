#pragma once
// A system owns one piece of physics. It declares which columns it reads and which it writes
// ("table.column" keys); the engine derives the step's task graph from those declarations, so no one
// writes dependency counts by hand. run() is called from one graph node on each step its stage of the step
// plan runs (engine/schedule/step_plan.hpp); data
// parallelism inside it goes through parallel_for (engine/schedule/parallel.hpp).
#include <cstdint>
#include <string>
#include <vector>

namespace rift {

struct Access {
  std::vector<std::string> reads;
  std::vector<std::string> writes;     // a written column counts as read too
  std::vector<std::string> resizes{};  // tables whose rows it adds or removes (every column of them changes)
  bool changes_topology = false;       // may change anything: ordered against every other system
};

// Wall time of one system (or of work a model runs beside the graph), for the timing table and summary.
struct SystemTiming {
  std::string name;
  double seconds = 0.0;  // accumulated wall time inside run()
  int64_t calls = 0;
};

// The column that forces `later` to wait for `earlier` (both in one step), or "" when they may run at the
// same time: a write of one that the other reads or writes, or a topology change.
std::string access_conflict(const Access& earlier, const Access& later);

struct StepContext {
  int64_t step = 0;   // index of the step being taken (0 for the first)
  double time = 0;    // simulated time at the start of the step [s]
  double dt = 0;      // step size [s]
  bool last = false;  // after the run's final step (health checks that sample every few steps run here too)
  // Whether anything reads this step's derived fields after it (outputs, metrics, the energy checks every
  // kObservedEvery steps, the run's last step). Systems skip what only those read (stress, strain
  // energy, the joints' opening, slip, damage and stored energy, the nodes' total force) on other steps;
  // the state a step depends on is always updated, so results do not depend on it.
  bool observed = true;
};

// Health checks that read the derived fields (energies) run after every step whose index + 1 is a multiple
// of this, and after the last; such steps are observed.
inline constexpr int64_t kObservedEvery = 16;

class System {
 public:
  virtual ~System() = default;
  virtual std::string name() const = 0;
  virtual Access access() const = 0;
  virtual void run(const StepContext& ctx) = 0;
};

// Whether a system or stage that runs once per window of `period` steps runs at the step `ctx` describes:
// the step that ends the window (its index + 1 a multiple of the period). The step plan gives each stage
// its window (engine/schedule/step_plan.hpp).
inline bool runs_at(int64_t period, const StepContext& ctx) {
  return (ctx.step + 1) % period == 0;
}

}  // namespace rift
