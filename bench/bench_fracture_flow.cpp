// The fracture flow's step (systems/fracture_flow/network_flow.hpp) on a planar crack network of n
// triangles (a square of right-isosceles pairs, jittered, every vertex wet, water, the solid's step of
// 1e-7 s): the transmissibilities, the assembly into the fixed pattern, the LDLT factorisation and solve,
// the fluxes and the roles. The budget: at most 25 % of the jointed solid step at 1e5 tets (about
// 9 ms on 2 threads, docs/performance.md) for a network of 1e4 faces. Items are triangle-steps. The step is
// serial (its sums must not depend on the thread count); the factorisation dominates, so it is not
// bandwidth-bound and items/s is the figure. Arguments: triangles (1e3 when tiny), solver.
#include <cmath>
#include <random>
#include <vector>

#include "bench/bench_common.hpp"
#include "systems/fracture_flow/network_flow.hpp"

namespace {

struct PlanarNetwork {
  std::vector<int32_t> tri;
  std::vector<double> tx, aperture, volume, compliance, applied, source, fixed;
  std::vector<double> pressure, mass, wetting, exchanged;
  std::vector<uint8_t> role;
};

PlanarNetwork make_network(size_t triangles) {
  const int n = std::max(2, int(std::lround(std::sqrt(double(triangles) / 2.0))));
  const double h = 1e-2, w = 1e-4;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.2 * h, 0.2 * h);
  std::vector<double> vx;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) vx.insert(vx.end(), {i * h + u(rng), j * h + u(rng), 0.0});
  PlanarNetwork net;
  const size_t nv = vx.size() / 3;
  net.volume.assign(nv, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      const int32_t corners[2][3] = {{a, b, c}, {a, c, d}};
      for (const auto& t : corners) {
        for (int k = 0; k < 3; ++k) {
          net.tri.push_back(t[k]);
          for (int e = 0; e < 3; ++e) net.tx.push_back(vx[3 * size_t(t[k]) + size_t(e)]);
          net.aperture.push_back(w);
          net.volume[size_t(t[k])] += 0.5 * h * h * w / 3.0;
        }
      }
    }
  net.compliance.assign(nv, 1e-18);
  net.applied.assign(nv, 1e6);
  net.source.assign(nv, 0.0);
  net.source[nv / 2] = 1e-3;
  net.fixed.assign(nv, 0.0);
  net.pressure.assign(nv, 1e6);
  net.role.assign(nv, uint8_t(rift::FlowRole::wet));
  net.wetting.assign(nv, 0.0);
  net.exchanged.assign(nv, 0.0);
  net.mass.resize(nv);
  for (size_t v = 0; v < nv; ++v) net.mass[v] = 1000.0 * (1.0 + 1e6 / 2.2e9) * net.volume[v];
  return net;
}

void BM_FractureFlowStep(benchmark::State& state) {
  const size_t wanted = rift::bench::tiny() ? 1000 : size_t(state.range(0));
  PlanarNetwork net = make_network(wanted);
  const size_t nv = net.volume.size(), nt = net.tri.size() / 3;
  const auto solver = state.range(1) ? rift::NetworkSolver::cg : rift::NetworkSolver::direct;
  rift::NetworkFlow flow({1000.0, 0.0, 2.2e9}, 1e-3, 0.0, solver);
  flow.set_network(net.tri, nv);
  rift::NetworkFlowBooks books;
  double t = 0.0;
  for (auto _ : state) {
    t += 1e-7;
    const rift::NetworkFlowStepInput in{1e-7,           t,           net.tx,     net.aperture, net.volume,
                                        net.compliance, net.applied, net.source, net.fixed};
    rift::NetworkFlowState s{net.pressure, net.mass, net.role, net.wetting, net.exchanged};
    const std::string problem = flow.step(in, s, books);
    if (!problem.empty()) state.SkipWithError(problem.c_str());
    benchmark::DoNotOptimize(net.pressure.data());
  }
  state.counters["triangles"] = double(nt);
  state.counters["vertices"] = double(nv);
  state.counters["cg_iterations"] = double(flow.cg_iterations());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(nt));
}
// Arguments: triangles, solver (0 the LDLT factorisation, 1 incomplete-Cholesky CG from the last pressure).
BENCHMARK(BM_FractureFlowStep)->ArgsProduct({{1000, 10000, 100000}, {0, 1}})->Unit(benchmark::kMicrosecond);

}  // namespace
