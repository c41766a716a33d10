// Fluid benchmarks: (1) the lid-driven cavity at Re = 100 run to steady state at 16^2 and 32^2 cells
// (the finer resolution of issue 6, target max |du| <= 0.01 against Ghia), with the errors, steps and
// time per step as counters; (2) the pressure solver alone: BoomerAMG-PCG on the 3-D P1 Poisson matrix
// of n^3-cell structured meshes, set-up + solve to 1e-8, iterations as a counter (should stay flat).
// (3) the default cavity step at 32^2 in arenas of 1 and 2 threads.
// RIFT_BENCH_TINY=1: 8^2 cavity and 8^3 Poisson. RIFT_CAVITY_SIZES=24,48 replaces the cavity sizes.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "bench/bench_common.hpp"
#include "engine/linear/hypre_pcg.hpp"
#include "tests/validation/fluid_cavity.hpp"

namespace {

void cavity(benchmark::State& state, rift::fluid_test::CavityOptions opt) {
  const int n = rift::bench::tiny() ? 8 : static_cast<int>(state.range(0));
  const double dt = n <= 16 ? 0.1 : 0.2;
  rift::fluid_test::CavityResult r;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    r = rift::fluid_test::run_cavity(n, dt, opt);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  state.counters["max_du"] = r.max_du;
  state.counters["max_dv"] = r.max_dv;
  state.counters["steps"] = r.steps;
  state.counters["nodes"] = static_cast<double>(r.nodes);
  state.counters["ms_per_step"] = 1e3 * seconds / std::max(r.steps, 1);
  // The march alone (bench/openfoam_cavity.py compares these with icoFoam's per-step times).
  state.counters["march_ms_per_step"] = 1e3 * r.march_seconds / std::max(r.steps, 1);
  state.counters["march_cpu_ms_per_step"] = 1e3 * r.march_cpu_seconds / std::max(r.steps, 1);
  state.counters["march_seconds"] = r.march_seconds;
  state.counters["dt"] = dt;
}
// Sizes 16 and 32, or the comma-separated list in RIFT_CAVITY_SIZES (bench/openfoam_cavity.py).
const int cavity_registered = [] {
  std::vector<int> sizes{16, 32};
  if (const char* env = std::getenv("RIFT_CAVITY_SIZES")) {
    sizes.clear();
    for (const char* c = env; *c;) {
      char* end = nullptr;
      const long v = std::strtol(c, &end, 10);
      if (end == c) break;
      if (v > 0) sizes.push_back(static_cast<int>(v));
      c = *end == ',' ? end + 1 : end;
    }
  }
  // The default per-step solve (fluid_cavity.hpp), 2 inexact Picard iterations per step, and the earlier
  // solve: 3 Picard iterations, every inner solve to its full tolerance (for before/after figures).
  using rift::fluid_test::CavityOptions;
  for (const auto& [name, opt] : {std::pair{"BM_FluidCavityRe100", CavityOptions{}},
                                  std::pair{"BM_FluidCavityRe100_2Picard", CavityOptions{2, 0.1, 1e-3}},
                                  std::pair{"BM_FluidCavityRe100_3Picard", CavityOptions{3, 0.0, 0.0}}}) {
    auto* b = benchmark::RegisterBenchmark(name, cavity, opt);
    for (int n : sizes) b->Arg(n);
    b->Iterations(1)->Unit(benchmark::kSecond);
  }
  return 0;
}();

// The cavity against Ghia at Re = 100, 400, 1000 with the default (orthogonal-subscale) convection
// stabilisation: BM_FluidCavityGhia/Re/n/clustering in %, dt = 0.2, five Picard iterations of full inner
// solves per step (Picard to 1e-9), to a per-step change below 1e-6 dt or t = 300. The mesh study of
// docs/validation.md (--benchmark_filter=BM_FluidCavityGhia); suspect_dv is Ghia's misprinted point
// (tests/validation/ghia1982.hpp), change_per_time what the last step still moved.
void cavity_ghia(benchmark::State& state) {
  rift::fluid_test::CavityOptions opt;
  opt.reynolds = static_cast<int>(state.range(0));
  const int n = rift::bench::tiny() ? 8 : static_cast<int>(state.range(1));
  opt.wall_clustering = 0.01 * static_cast<double>(state.range(2));
  opt.supg = true;
  opt.picard_iterations = 5;
  opt.picard_tol = 1e-9;
  opt.velocity_forcing = 0.0;
  opt.projection_forcing = 0.0;
  opt.max_steps = rift::bench::tiny() ? 20 : 1500;
  rift::fluid_test::CavityResult r;
  for (auto _ : state) r = rift::fluid_test::run_cavity(n, 0.2, opt);
  state.counters["max_du"] = r.max_du;
  state.counters["max_dv"] = r.max_dv;
  state.counters["suspect_dv"] = r.suspect_dv;
  state.counters["change_per_time"] = r.change_per_time;
  state.counters["steps"] = r.steps;
  state.counters["nodes"] = static_cast<double>(r.nodes);
  state.counters["march_seconds"] = r.march_seconds;
}
BENCHMARK(cavity_ghia)
    ->Name("BM_FluidCavityGhia")
    ->ArgsProduct({{100, 400, 1000}, {24, 32, 48}, {0, 50}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// The default cavity step inside an arena of 1 or 2 threads (the fluid assembly's parallel loops;
// docs/performance.md "Fluid kernels"): BM_FluidCavityRe100_Threads/n/threads, same counters.
void cavity_threads(benchmark::State& state) {
  rift::bench::arena(static_cast<int>(state.range(1))).execute([&] { cavity(state, {}); });
}
BENCHMARK(cavity_threads)
    ->Name("BM_FluidCavityRe100_Threads")
    ->Args({32, 1})
    ->Args({32, 2})
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

void BM_PressureAmgPcg(benchmark::State& state) {
  const int n = rift::bench::tiny() ? 8 : static_cast<int>(state.range(0));
  rift::StructuredBoxSpec spec;
  spec.cells = {n, n, n};
  const rift::TetMesh mesh = rift::structured_box(spec);
  const size_t nn = mesh.nodes.size(), nt = mesh.tets.size();
  std::vector<double> x, vol(nt), grad(12 * nt), h(nt);
  for (const auto& p : mesh.nodes) x.insert(x.end(), p.begin(), p.end());
  std::vector<int32_t> tn;
  for (const auto& t : mesh.tets) tn.insert(tn.end(), t.begin(), t.end());
  rift::kernels::p1_prepare(x, tn, vol, grad, h);
  rift::CsrMatrix a = rift::p1_pattern(static_cast<int32_t>(nn), tn);
  const auto slot = rift::p1_tet_slots(a, tn);
  const auto diag = rift::diagonal_slots(a);
  std::vector<uint8_t> fixed(nn, 0);
  std::vector<double> value(nn, 0.0), rhs(nn, 1.0), ones(nt, 1.0), u(nn, 0.0);
  for (size_t i = 0; i < nn; ++i)
    for (int d = 0; d < 3; ++d) fixed[i] |= (mesh.nodes[i][d] == 0.0 || mesh.nodes[i][d] == 1.0) ? 1 : 0;
  rift::kernels::scalar_laplacian_assemble({tn, vol, grad, ones, slot, diag, fixed, value, a.val, rhs});
  rift::HypreAmgPcg amg;
  rift::AmgPcgResult res;
  for (auto _ : state) {
    std::fill(u.begin(), u.end(), 0.0);
    amg.set_matrix(a);
    res = amg.solve(rhs, u);
  }
  state.counters["unknowns"] = static_cast<double>(nn);
  state.counters["pcg_iterations"] = res.iterations;
}
BENCHMARK(BM_PressureAmgPcg)->Arg(16)->Arg(32)->Arg(64)->Unit(benchmark::kMillisecond);

}  // namespace
