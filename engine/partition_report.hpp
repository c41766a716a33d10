#pragma once
// How a run would split across processes: METIS parts of each of its meshes (the solid's, the fluid's),
// weighted by the models' work (Model::partition_work), the owner-computes halo of each part
// (engine/mesh/halo_plan.hpp), and, where the work is timed (the solid's), the time per step and parallel
// efficiency that predicts on a stated network. `rift partition` prints it for
// a scene; bench/halo_study.cpp tabulates it for blocks of 1e6 and 1e7 tets (docs/performance.md,
// "Beyond one machine").
#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "engine/mesh/halo_plan.hpp"

namespace rift {

struct World;

// The cost of a step on one rank: work units at unit_seconds each, then the halo exchange (one message
// per neighbour each way, at latency each, and its bytes at bandwidth) and one reduction of a flag over
// all ranks (the health guard: latency times log2 of the ranks), with no overlap of the two, so the
// prediction is a lower bound of the efficiency the exchange allows.
struct NetworkModel {
  double latency = 1.5e-6;      // s per message
  double bandwidth = 12.5e9;    // B/s of one rank's link
  double unit_seconds = 25e-9;  // one work unit on one core
};

struct PartitionReport {
  std::string domain;
  bool timed = false;  // step times and efficiency are predicted
  int32_t ranks = 1;
  int64_t tets = 0, nodes = 0;
  std::vector<std::string> element_sets;
  std::vector<int64_t> elements;  // per set
  std::vector<double> redundant;  // per set: elements computed by more than one rank, over the set
  int64_t edge_cut = 0;           // shared faces between ranks
  double weight_imbalance = 1.0;  // METIS's, on the tet weights
  int64_t work_total = 0;         // every element once
  int64_t work_max = 0;           // the busiest rank's, ghosts included
  double work_imbalance = 1.0;    // work_max over work_total / ranks
  int64_t ghost_nodes_max = 0;
  double ghost_nodes_mean = 0.0;
  int64_t halo_bytes_max = 0;     // per step, the larger of a rank's receive and send
  int32_t neighbours_max = 0;     // messages per step, the larger of a rank's receive and send
  double step_seconds_one = 0.0;  // the whole work on one rank
  double step_seconds = 0.0;      // the slowest rank's work and exchange
  double efficiency = 1.0;        // step_seconds_one / (ranks step_seconds)
  HaloPlan halo;                  // per rank, for predictions on other networks
  int32_t node_bytes = 0;
};

// The models' contributions, one per mesh; throws Error when a model's tet weights do not match its tets.
std::vector<PartitionWork> collect_partition_work(const World& world);

PartitionReport report_partition(const PartitionWork& work, int32_t ranks, const NetworkModel& network);

// Sets the report's step times and efficiency for `network` (report_partition does it for its own).
void predict_step(PartitionReport& report, const NetworkModel& network);

nlohmann::json to_json(const PartitionReport& report);
// One line per report under a header, for a terminal (one domain's reports).
std::string partition_table(std::span<const PartitionReport> reports);

}  // namespace rift
