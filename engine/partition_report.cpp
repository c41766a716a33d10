#include "engine/partition_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/mesh/tet_partition.hpp"
#include "engine/world.hpp"

namespace rift {

std::vector<PartitionWork> collect_partition_work(const World& world) {
  std::vector<PartitionWork> domains;
  for (const auto& model : world.models) model->partition_work(domains);
  for (const PartitionWork& d : domains)
    if (d.tet_weight.size() != d.graph_tets.size() || d.elements.empty())
      throw Error(fmt::format("partition: the {} gives {} tet weights for {} tets", d.domain,
                              d.tet_weight.size(), d.graph_tets.size()));
  return domains;
}

namespace {

double exchange_seconds(const PartHalo& p, int32_t ranks, int32_t node_bytes, const NetworkModel& net) {
  const double messages = double(std::max(p.receives_from, p.sends_to));
  const double bytes = double(std::max(p.ghost_nodes, p.nodes_sent)) * node_bytes;
  const double reduction = ranks > 1 ? std::ceil(std::log2(double(ranks))) * net.latency : 0.0;
  return messages * net.latency + bytes / net.bandwidth + reduction;
}

}  // namespace

PartitionReport report_partition(const PartitionWork& work, int32_t ranks, const NetworkModel& network) {
  const TetPartition partition = partition_tets(work.graph_tets, ranks, work.tet_weight);
  HaloPlan plan = plan_halo(ranks, partition.part, work.nodes, work.elements, work.node_units);
  PartitionReport r;
  r.domain = work.domain;
  r.timed = work.timed;
  r.ranks = ranks;
  r.tets = int64_t(work.graph_tets.size());
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
  if (!r.timed) return;
  double slowest = 0.0;
  for (const PartHalo& p : r.halo.parts)
    slowest = std::max(
        slowest, double(p.work) * network.unit_seconds + exchange_seconds(p, r.ranks, r.node_bytes, network));
  r.step_seconds_one = double(r.work_total) * network.unit_seconds;
  r.step_seconds = slowest;
  r.efficiency = r.step_seconds_one / (r.ranks * slowest);
}

nlohmann::json to_json(const PartitionReport& r) {
  nlohmann::json j = {{"domain", r.domain},
                      {"ranks", r.ranks},
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
                      {"neighbours_max", r.neighbours_max}};
  if (r.timed) {
    j["step_seconds_one"] = r.step_seconds_one;
    j["step_seconds"] = r.step_seconds;
    j["efficiency"] = r.efficiency;
  }
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
    const std::string step = r.timed ? fmt::format("{:.1f}", 1e6 * r.step_seconds) : "-";
    const std::string efficiency = r.timed ? fmt::format("{:.3f}", r.efficiency) : "-";
    out +=
        fmt::format("{:>6} {:>9} {:>9.3f} {:>9.3f} {:>11} {:>11.0f} {:>10.1f} {:>6} {:>9.2f}% {:>10} {:>6}\n",
                    r.ranks, r.edge_cut, r.weight_imbalance, r.work_imbalance, r.ghost_nodes_max,
                    r.ghost_nodes_mean, double(r.halo_bytes_max) / 1024.0, r.neighbours_max,
                    100.0 * redundant / double(std::max<int64_t>(elements, 1)), step, efficiency);
  }
  return out;
}

}  // namespace rift
