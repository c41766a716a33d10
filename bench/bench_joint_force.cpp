// Throughput of the 6-node joint force kernel (AVX2 path and scalar reference) on FDEM meshes of ~1e4, 1e5
// and 1e6 joints, 3- and 7-point rules, at 1 and 2 threads.
//
// Mesh: bench_common's perturbed Kuhn mesh (shared layout) gives the tets and which faces they share; every
// tet then gets private copies of its 4 corners (nodes 4t..4t+3, as the engine stores them) and every
// interior face one joint (femdem.md 1b: nodes 0-2 the first tet's face in reversed outward order, 3-5 the
// matching corners of the neighbour). Joints are ordered by their face's grid nodes, so neighbouring joints
// touch neighbouring tets. ~2 joints per tet: 5e3 / 5e4 / 5e5 tet targets give 8262 / 93600 / 1010592 joints.
// State: a smooth strain of 1e-4 (no jump between copies) plus independent noise of 2e-9 m per node copy,
// i.e. jumps of ~op/30: pre-peak, in tension and compression, mixed mode. 10 % of the joints carry D_max in
// [0.05, 0.5] at every point, so the secant branch and z(D) run too. Nothing breaks (checked: "broken").
//
// Byte model (performance.md 3.1, "Joint element"): 324 B per joint for 3 points with node reuse =
// connectivity 24 + integration-point history 3 x 2 x 8 x 2 = 96 + material / area 12 + node data 192.
// For 7 points the history term scales to 7 x 32 = 224: 452 B. roofline_frac uses these.
// The interface here moves a different set (roofline_frac_io): connectivity 24, material id 4, broken flag 1,
// D_max read + write 16 per point, positions 48 (4 private corners x 24 B shared by ~2 joints), corner forces
// 9 x 8 written with write-allocate 144 (side B's corners only: side A's are minus them), and with all
// outputs on 4 doubles written 64: 3 points 333 B (269 forces only), 7 points 397 B (333 forces only); an
// initial offset adds 24 B read. (Until 2026-12-02 the kernel wrote all 18 components: 144 B more.)
#include <algorithm>
#include <array>
#include <atomic>
#include <memory>
#include <random>
#include <span>
#include <vector>

#include "bench/bench_common.hpp"
#include "kernels/joint_forces.hpp"

namespace {

using rift::kernels::JointArgs;
using rift::kernels::JointMaterial;

constexpr size_t kGrain = 1024;

struct JointMesh {
  size_t num_joints = 0;
  std::vector<double> x;
  std::vector<int32_t> joint_nodes, material;
  std::vector<JointMaterial> materials;
  std::vector<double> d_max3, d_max7;  // initial histories for the two rules
  std::vector<double> offset;          // initial offsets (3 per joint), for BM_JointForcesWithOffset
};

// The tet's outward faces (femdem.md 1b face table), as corner indices.
constexpr int kFaces[4][3] = {{1, 2, 3}, {3, 2, 0}, {3, 0, 1}, {1, 0, 2}};

struct FaceRecord {
  std::array<int32_t, 3> key;  // sorted grid nodes
  int32_t tet;
  int8_t face;
  bool operator<(const FaceRecord& o) const { return key < o.key || (key == o.key && tet < o.tet); }
};

JointMesh make_joint_mesh(size_t target_joints) {
  using rift::bench::NodeLayout;
  const rift::bench::BenchMesh shared = rift::bench::make_tet_mesh(target_joints / 2, NodeLayout::shared);
  const size_t T = shared.num_tets;
  std::vector<FaceRecord> faces;
  faces.reserve(4 * T);
  for (size_t t = 0; t < T; ++t)
    for (int f = 0; f < 4; ++f) {
      FaceRecord r{{}, static_cast<int32_t>(t), static_cast<int8_t>(f)};
      for (int c = 0; c < 3; ++c) r.key[c] = shared.tet_nodes[4 * t + kFaces[f][c]];
      std::sort(r.key.begin(), r.key.end());
      faces.push_back(r);
    }
  std::sort(faces.begin(), faces.end());

  JointMesh m;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Private corners: the shared grid position under a smooth strain, plus per-copy noise.
  const double strain[3][3] = {{1e-4, 2e-5, 0}, {2e-5, -5e-5, 1e-5}, {0, 1e-5, 3e-5}};
  m.x.resize(12 * T);
  for (size_t t = 0; t < T; ++t)
    for (int a = 0; a < 4; ++a) {
      const double* X = &shared.x0[3 * static_cast<size_t>(shared.tet_nodes[4 * t + a])];
      for (int i = 0; i < 3; ++i)
        m.x[3 * (4 * t + a) + i] =
            X[i] + strain[i][0] * X[0] + strain[i][1] * X[1] + strain[i][2] * X[2] + 2e-9 * unit(rng);
    }
  for (size_t k = 0; k + 1 < faces.size(); ++k) {
    if (faces[k].key != faces[k + 1].key) continue;
    const FaceRecord &a = faces[k], &b = faces[k + 1];
    int32_t nodes[6];
    for (int c = 0; c < 3; ++c) {  // reversed outward order of tet a's face: n points into a
      const int corner = kFaces[a.face][2 - c];
      nodes[c] = 4 * a.tet + corner;
      const int32_t grid = shared.tet_nodes[4 * static_cast<size_t>(a.tet) + corner];
      for (int cb = 0; cb < 4; ++cb)
        if (shared.tet_nodes[4 * static_cast<size_t>(b.tet) + cb] == grid) nodes[c + 3] = 4 * b.tet + cb;
    }
    m.joint_nodes.insert(m.joint_nodes.end(), nodes, nodes + 6);
    ++k;
  }
  m.num_joints = m.joint_nodes.size() / 6;
  // Limestone of femdem.md 1e (p = 10 E) and a weaker variant.
  const double tan35 = 0.7002075382097097;
  m.materials = {{4e11, 5e6, 15e6, tan35, 30.0, 300.0, 0.0}, {2e11, 3.5e6, 10e6, 0.5, 20.0, 200.0, 0.3}};
  m.material.resize(m.num_joints);
  for (auto& id : m.material) id = static_cast<int32_t>(rng() % 2);
  m.d_max3.assign(3 * m.num_joints, 0.0);
  m.d_max7.assign(7 * m.num_joints, 0.0);
  std::uniform_real_distribution<double> damage(0.05, 0.5);
  for (size_t j = 0; j < m.num_joints; ++j)
    if (rng() % 10 == 0) {
      const double d = damage(rng);
      std::fill_n(&m.d_max3[3 * j], 3, d);
      std::fill_n(&m.d_max7[7 * j], 7, d);
    }
  // Offsets of the size of the noise jumps (~op/30): the law's state stays pre-peak.
  m.offset.resize(3 * m.num_joints);
  for (double& o : m.offset) o = 2e-9 * unit(rng);
  return m;
}

const JointMesh& cached_joint_mesh(size_t target_joints) {
  static std::unique_ptr<JointMesh> mesh;
  static size_t cached = 0;
  if (!mesh || cached != target_joints) {
    mesh.reset();
    mesh = std::make_unique<JointMesh>(make_joint_mesh(target_joints));
    cached = target_joints;
  }
  return *mesh;
}

using Kernel = rift::kernels::JointStatus (*)(const JointArgs&, size_t, size_t);

void run(benchmark::State& state, Kernel kernel, bool all_outputs, bool offsets = false,
         bool anchors = false) {
  const size_t target = static_cast<size_t>(state.range(0));
  const int threads = static_cast<int>(state.range(1));
  const int points = static_cast<int>(state.range(2));
  const JointMesh& m = cached_joint_mesh(target);
  const size_t J = m.num_joints;
  std::vector<double> d_max = points == 3 ? m.d_max3 : m.d_max7;
  std::vector<uint8_t> broken(J, 0);
  std::vector<double> force(9 * J, 0.0), opening, slip, damage, energy;
  if (all_outputs) {
    opening.assign(J, 0.0);
    slip.assign(J, 0.0);
    damage.assign(J, 0.0);
    energy.assign(J, 0.0);
  }
  std::vector<rift::kernels::JointBreak> breaks(64);
  std::atomic<size_t> break_count{0};
  JointArgs args{m.x,
                 m.joint_nodes,
                 m.material,
                 m.materials,
                 &rift::kernels::joint_rule(points),
                 rift::kernels::Softening::energy_exact,
                 d_max,
                 broken,
                 force,
                 opening,
                 slip,
                 damage,
                 energy,
                 breaks,
                 &break_count,
                 offsets ? std::span<const double>(m.offset) : std::span<const double>()};
  // Residual friction's slider anchors (3 per point, from 0): the weaker material has mu_res 0.3, so its
  // damaged joints (about 5 % of all) take the scalar path, and every AVX2 group of 4 holding one too.
  std::vector<double> anchor;
  if (anchors) {
    anchor.assign(3 * static_cast<size_t>(points) * J, 0.0);
    args.residual_anchor = anchor;
  }
  for (auto _ : state) {
    rift::bench::parallel_ranges(threads, J, kGrain,
                                 [&](size_t begin, size_t end) { kernel(args, begin, end); });
    benchmark::ClobberMemory();
  }
  const double model = points == 3 ? 324.0 : 452.0;
  // The anchors' own traffic is left out of the io model (at most 48 B per point of the joints that use it).
  const double io =
      (all_outputs ? (points == 3 ? 333.0 : 397.0) : (points == 3 ? 269.0 : 333.0)) + (offsets ? 24.0 : 0.0);
  rift::bench::report_throughput(state, J, model, threads);
  state.counters["roofline_frac_io"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(J) * io /
                             rift::bench::roofline_bytes_per_second(threads),
                         benchmark::Counter::kIsRate);
  state.counters["joints"] = static_cast<double>(J);
  state.counters["avx2"] = kernel == &rift::kernels::joint_forces && rift::kernels::joint_forces_vectorised();
  state.counters["broken"] =
      static_cast<double>(std::count_if(broken.begin(), broken.end(), [](uint8_t b) { return b != 0; }));
}

void joint_args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"joints", "threads", "points"});
  const std::vector<int64_t> sizes =
      rift::bench::tiny() ? std::vector<int64_t>{2000} : std::vector<int64_t>{10000, 100000, 1000000};
  for (int64_t points : {3, 7})
    for (int64_t joints : sizes)
      for (int64_t threads : {1, 2}) b->Args({joints, threads, points});
}

void BM_JointForces(benchmark::State& state) {
  run(state, &rift::kernels::joint_forces, true);
}
void BM_JointForcesScalar(benchmark::State& state) {
  run(state, &rift::kernels::joint_forces_scalar, true);
}
// Optional outputs skipped (empty spans), as a step that writes no output would call it.
void BM_JointForcesOnly(benchmark::State& state) {
  run(state, &rift::kernels::joint_forces, false);
}
// All outputs plus an initial offset per joint (the optional extension on).
void BM_JointForcesWithOffset(benchmark::State& state) {
  run(state, &rift::kernels::joint_forces, true, true);
}

// All outputs with residual friction's anchors (the slider of joint_law.hpp on the damaged joints of the
// weaker material): the cost of its scalar fallback against BM_JointForces.
void BM_JointForcesResidualFriction(benchmark::State& state) {
  run(state, &rift::kernels::joint_forces, true, false, true);
}

BENCHMARK(BM_JointForces)->Apply(joint_args)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JointForcesScalar)->Apply(joint_args)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JointForcesOnly)->Apply(joint_args)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JointForcesWithOffset)->Apply(joint_args)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_JointForcesResidualFriction)->Apply(joint_args)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
