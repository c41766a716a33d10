// Splitting a jointed block across processes (docs/performance.md, "Beyond one machine"): METIS parts of a
// Kuhn lattice whose every tet is in the fracture zone (4 private nodes per tet, a joint on every interior
// face, the solid's work units: engine/partition_report.hpp, systems/solid_partition_work.hpp), the
// owner-computes halo of each part, and the efficiency that predicts on two stated networks.
//
// Items are tets partitioned and planned per second (METIS and the halo plan together: what a run's
// set-up or a repartition on restart costs). The counters are the study's figures, per rank and step:
//   edge_cut, weight_imb (METIS's balance of the tet weights), work_imb (the busiest rank's work, ghosts
//   included, over the mean), ghost_max / ghost_mean (ghost nodes), halo_KB_max (the larger of a rank's
//   receive and send, 48 B a node), msgs_max (neighbour ranks), redundant (joints computed twice, over all
//   joints), step_us_ib / eff_ib on InfiniBand HDR100 (1.5 us a message, 12.5 GB/s), step_us_eth /
//   eff_eth on 10 Gb Ethernet with TCP (25 us, 1.25 GB/s); 25 ns a work unit on one core per rank.
// Args: cells per edge (6 n^3 tets: 55 -> 1.0e6, 119 -> 1.0e7), parts.
#include <benchmark/benchmark.h>

#include <memory>

#include "bench_common.hpp"
#include "engine/mesh/discontinuous_mesh.hpp"
#include "engine/mesh/lattice_box.hpp"
#include "engine/partition_report.hpp"
#include "systems/solid_partition_work.hpp"

namespace {

struct JointedBlock {
  int cells = 0;
  rift::DiscontinuousMesh dm;
  rift::PartitionWork work;  // points into dm
};

// The block of the last size asked for, kept while the size stays: the 1e7 block takes a minute and ~4 GB.
const JointedBlock& block(int cells) {
  static std::unique_ptr<JointedBlock> b;
  if (b && b->cells == cells) return *b;
  b.reset();
  b = std::make_unique<JointedBlock>();
  b->cells = cells;
  const rift::TetMesh mesh = rift::generate_lattice_box({cells, cells, cells}, {0.1, 0.1, 0.1});
  b->dm = rift::make_discontinuous(mesh, [](size_t) { return true; });
  const auto& dm = b->dm;
  b->work = rift::solid_partition_work({dm.tets.front().data(), 4 * dm.tets.size()}, dm.node_vertex,
                                       {dm.joints.front().data(), 6 * dm.joints.size()},
                                       {dm.joint_tets.front().data(), 2 * dm.joint_tets.size()});
  return *b;
}

void BM_PartitionJointedBlock(benchmark::State& state) {
  const auto cells = int(state.range(0));
  const auto parts = int32_t(state.range(1));
  const JointedBlock& b = block(cells);
  const rift::NetworkModel infiniband{1.5e-6, 12.5e9, 25e-9}, ethernet{25e-6, 1.25e9, 25e-9};
  rift::PartitionReport r;
  for (auto _ : state) {
    r = rift::report_partition(b.work, parts, infiniband);
    benchmark::DoNotOptimize(r.edge_cut);
  }
  state.SetItemsProcessed(state.iterations() * int64_t(b.dm.tets.size()));
  state.counters["tets"] = double(b.dm.tets.size());
  state.counters["edge_cut"] = double(r.edge_cut);
  state.counters["weight_imb"] = r.weight_imbalance;
  state.counters["work_imb"] = r.work_imbalance;
  state.counters["ghost_max"] = double(r.ghost_nodes_max);
  state.counters["ghost_mean"] = r.ghost_nodes_mean;
  state.counters["halo_KB_max"] = double(r.halo_bytes_max) / 1024.0;
  state.counters["msgs_max"] = r.neighbours_max;
  state.counters["redundant"] = r.redundant.size() > 1 ? r.redundant[1] : 0.0;
  state.counters["step_us_ib"] = 1e6 * r.step_seconds;
  state.counters["eff_ib"] = r.efficiency;
  rift::predict_step(r, ethernet);
  state.counters["step_us_eth"] = 1e6 * r.step_seconds;
  state.counters["eff_eth"] = r.efficiency;
}

void partition_args(benchmark::internal::Benchmark* b) {
  if (rift::bench::tiny()) {
    b->Args({6, 2})->Args({6, 4});
    return;
  }
  for (int cells : {55, 119})
    for (int parts : {2, 4, 8, 16, 32, 64, 128, 256, 512, 1024}) b->Args({cells, parts});
}

BENCHMARK(BM_PartitionJointedBlock)->Apply(partition_args)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
