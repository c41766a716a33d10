#include "engine/partition_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/mesh/tet_partition.hpp"
#include "engine/world.hpp"

namespace rift {

PartitionWork collect_partition_work(const World& world) {
  PartitionWork work;
  for (const auto& model : world.models) model->partition_work(work);
  if (work.elements.empty())
    throw Error("partition: the scene has no solid; the split follows the solid's tets and nodes");
  if (work.tet_weight.size() != world.mesh.tets.size())
    throw Error(fmt::format("partition: {} tet weights for a mesh of {} tets", work.tet_weight.size(),
                            world.mesh.tets.size()));
  return work;
}

namespace {

double exchange_seconds(const PartHalo& p, int32_t ranks, int32_t node_bytes, const NetworkModel& net) {
  const double messages = double(std::max(p.receives_from, p.sends_to));
  const double bytes = double(std::max(p.ghost_nodes, p.nodes_sent)) * node_bytes;
  const double reduction = ranks > 1 ? std::ceil(std::log2(double(ranks))) * net.latency : 0.0;
  return messages * net.latency + bytes / net.bandwidth + reduction;
}

}  // namespace

PartitionReport report_partition(const TetMesh& mesh, const PartitionWork& work, int32_t ranks,
                                 const NetworkModel& network) {
  const TetPartition partition = partition_tets(mesh, ranks, work.tet_weight);
  HaloPlan plan = plan_halo(ranks, partition.part, work.nodes, work.elements);
  PartitionReport r;
  r.ranks = ranks;
  r.tets = int64_t(mesh.tets.size());
  r.nodes = work.nodes;
  r.edge_cut = partition.edge_cut;
  r.weight_imbalance = partition.imbalance;
  r.element_sets = plan.element_sets;
  for (size_t s = 0; s < work.elements.size(); ++s) {
    const ElementNodes& set = work.elements[s];
    const auto count = int64_t(set.nodes.size() / size_t(set.width));
    int64_t computed = 0;
    for (const PartHalo& p : plan.parts) computed += p.computed[s];
    r.elements.push_back(count);
    r.redundant.push_back(count > 0 ? double(computed - count) / double(count) : 0.0);
    r.work_total += count * set.weight;
  }
  for (const PartHalo& p : plan.parts) {
    r.work_max = std::max(r.work_max, p.work);
    r.ghost_nodes_max = std::max(r.ghost_nodes_max, p.ghost_nodes);
    r.ghost_nodes_mean += double(p.ghost_nodes) / ranks;
    r.halo_bytes_max =
        std::max(r.halo_bytes_max, std::max(p.ghost_nodes, p.nodes_sent) * int64_t(work.node_bytes));
    r.neighbours_max = std::max({r.neighbours_max, p.receives_from, p.sends_to});
  }
  r.work_imbalance = double(r.work_max) * ranks / double(r.work_total);
  r.halo = std::move(plan);
  r.node_bytes = work.node_bytes;
  predict_step(r, network);
  return r;
}

void predict_step(PartitionReport& r, const NetworkModel& network) {
  double slowest = 0.0;
  for (const PartHalo& p : r.halo.parts)
    slowest = std::max(
        slowest, double(p.work) * network.unit_seconds + exchange_seconds(p, r.ranks, r.node_bytes, network));
  r.step_seconds_one = double(r.work_total) * network.unit_seconds;
  r.step_seconds = slowest;
  r.efficiency = r.step_seconds_one / (r.ranks * slowest);
}

nlohmann::json to_json(const PartitionReport& r) {
  nlohmann::json j = {{"ranks", r.ranks},
                      {"tets", r.tets},
                      {"nodes", r.nodes},
                      {"edge_cut", r.edge_cut},
                      {"weight_imbalance", r.weight_imbalance},
                      {"work_total", r.work_total},
                      {"work_max", r.work_max},
                      {"work_imbalance", r.work_imbalance},
                      {"ghost_nodes_max", r.ghost_nodes_max},
                      {"ghost_nodes_mean", r.ghost_nodes_mean},
                      {"halo_bytes_max", r.halo_bytes_max},
                      {"neighbours_max", r.neighbours_max},
                      {"step_seconds_one", r.step_seconds_one},
                      {"step_seconds", r.step_seconds},
                      {"efficiency", r.efficiency}};
  for (size_t s = 0; s < r.element_sets.size(); ++s)
    j["elements"][r.element_sets[s]] = {{"count", r.elements[s]}, {"redundant", r.redundant[s]}};
  return j;
}

std::string partition_table(std::span<const PartitionReport> reports) {
  std::string out = fmt::format("{:>6} {:>9} {:>9} {:>9} {:>11} {:>11} {:>10} {:>6} {:>10} {:>10} {:>6}\n",
                                "ranks", "edge cut", "weights", "work", "ghost max", "ghost mean", "halo KB",
                                "msgs", "redundant", "step us", "eff.");
  for (const PartitionReport& r : reports) {
    double redundant = 0.0;  // of the work, computed more than once
    for (size_t s = 0; s < r.elements.size(); ++s) redundant += r.redundant[s] * double(r.elements[s]);
    int64_t elements = 0;
    for (int64_t e : r.elements) elements += e;
    out += fmt::format(
        "{:>6} {:>9} {:>9.3f} {:>9.3f} {:>11} {:>11.0f} {:>10.1f} {:>6} {:>9.2f}% {:>10.1f} {:>6.3f}\n",
        r.ranks, r.edge_cut, r.weight_imbalance, r.work_imbalance, r.ghost_nodes_max, r.ghost_nodes_mean,
        double(r.halo_bytes_max) / 1024.0, r.neighbours_max,
        100.0 * redundant / double(std::max<int64_t>(elements, 1)), 1e6 * r.step_seconds, r.efficiency);
  }
  return out;
}

}  // namespace rift
