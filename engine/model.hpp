#pragma once
// A model is one physics package in a run (the solid, the fluid, their coupling, the fracture flow,
// the mesh conversion, the probes): it creates its tables in the store, owns its systems (which the
// composition root places in the step plan, systems/step_script.cpp), and answers the run loop's questions
// (stable step, health after a step, fields to write, metrics for the time series and the summary). A model
// exists in a run only when its section is in the scene.
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "engine/io/xdmf_series.hpp"
#include "engine/mesh/halo_plan.hpp"
#include "engine/schedule/system.hpp"

namespace rift {

struct SplitJob;  // engine/distributed/split_run.hpp
struct SplitDomain;

class Model {
 public:
  virtual ~Model() = default;
  virtual std::string name() const = 0;
  // Largest step this model is stable with [s] (infinity when it sets no limit).
  virtual double stable_dt() const { return std::numeric_limits<double>::infinity(); }
  // The one step this model runs with [s] (an implicit model's own step, e.g. fluid.dt), if it has one.
  virtual std::optional<double> required_dt() const { return std::nullopt; }
  // After a checkpoint was read into the store: bring state kept outside the store in line with it.
  virtual void restored(const StepContext& at) {}
  // After each step: a diagnosis when the state is no longer physical (NaN, inverted element, ...).
  virtual std::optional<std::string> check_health(const StepContext& after) { return std::nullopt; }
  // Output: append this model's grids with the requested fields (empty list: every field).
  virtual void output_grids(std::vector<XdmfGrid>& grids, const std::vector<std::string>& fields) {}
  // One row of the time series: (name, value) pairs in a fixed order.
  virtual void metrics(double time, std::vector<std::pair<std::string, double>>& row) {}
  virtual void summarize(nlohmann::json& summary) const {}
  // Logs beside the time series (e.g. the fracture log), written atomically whenever it is.
  virtual void write_logs(const std::filesystem::path& dir) const {}

  // Splitting the run across processes (engine/mesh/halo_plan.hpp): one entry per mesh this model
  // computes on, with its tets' work and the elements on its nodes. Models without a mesh of their own add
  // none.
  virtual void partition_work(std::vector<PartitionWork>& domains) const {}
  // A run split between the processes of a job (docs/distributed.md): from the next step on, this model
  // computes only this rank's share of its domains (one per partition_work entry, in its order). A model
  // that does not run split refuses with Error (the default). Before the step graph is built.
  virtual void take_share(const SplitJob& job, std::span<const SplitDomain> domains);
  // In a split run, after each step's graph and stages, on the thread that calls MPI, before the health
  // check: what the ranks exchange and add up (ghosts, energy books, counts). Collective.
  virtual void finish_share_step(const StepContext& ctx) {}
  // In a split run, before rank 0 reads the store (outputs, metrics, checkpoints, the state hash): brings
  // the rows of this model that other ranks computed to rank 0. Collective.
  virtual void gather_to_root() {}

  // Wall times of work done outside the graph's systems (beside and after stages), for the timing table
  // and summary.json.
  virtual std::vector<SystemTiming> timings() const { return {}; }
};

}  // namespace rift
