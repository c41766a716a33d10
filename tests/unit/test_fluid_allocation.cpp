// A fluid step allocates nothing on the C++ heap once set up (matrices keep their pattern, work vectors
// are sized in the constructor), for both pressure couplings, with convection, SUPG and absorption on.
// Counted through a replaced global operator new; hypre's own C allocations (malloc inside the AMG
// solve and set-up) are outside the count.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "engine/mesh/structured_box.hpp"
#include "systems/fluid/fluid_solver.hpp"
#include "tests/unit/test_allocation_counter.hpp"

#if defined(__SANITIZE_ADDRESS__)
// LeakSanitizer's exit-time scan crashes in this executable (Open MPI's threads are still running, as
// sanitizer builds skip MPI_Finalize, engine/linear/hypre_pcg.cpp); leaks are checked by the other fluid
// tests, this one only counts allocations.
extern "C" const char* __lsan_default_options() {
  return "detect_leaks=0";
}
#endif

TEST(FluidAllocation, StepsAllocateNothing) {
  using namespace rift;
  using namespace rift::fluid;
  for (const PressureCoupling coupling : {PressureCoupling::schur_gmres, PressureCoupling::projection}) {
    StructuredBoxSpec spec;
    spec.cells = {4, 3, 3};
    FluidSettings st;
    st.dt = 0.05;
    st.coupling = coupling;
    std::vector<FluidBoundary> bcs{{"xmin",
                                    BoundaryKind::velocity,
                                    [](const Vec3& x, double t) {
                                      return Vec3{x[1] * (1 - x[1]) * (1 + t), 0, 0};
                                    },
                                    {}},
                                   {"xmax", BoundaryKind::outflow, {}, {}},
                                   {"ymin", BoundaryKind::no_slip, {}, {}},
                                   {"ymax", BoundaryKind::no_slip, {}, {}},
                                   {"zmin", BoundaryKind::free_slip, {}, {}},
                                   {"zmax", BoundaryKind::free_slip, {}, {}}};
    FluidSolver s(structured_box(spec), st, bcs);
    s.set_body_force([](const Vec3& x, double) { return Vec3{0.0, 0.0, -x[2]}; });
    for (size_t t = 0; t < s.own_sigma().size(); ++t) s.own_sigma()[t] = t % 3 == 0 ? 10.0 : 0.0;
    s.absorption_changed();
    s.step();
    s.step();
    const long before = allocations.load();
    for (int i = 0; i < 3; ++i) s.step();
    EXPECT_EQ(allocations.load() - before, 0)
        << (coupling == PressureCoupling::projection ? "projection" : "schur");
  }
}
