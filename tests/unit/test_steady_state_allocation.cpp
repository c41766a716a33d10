// Once a run is in steady state a step allocates nothing on the C++ heap: systems size their scratch
// at set-up. Counted through a replaced global operator new (oneTBB's own task pool is outside it, as
// is the output path, which this test switches off).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "engine/scene/load_scene.hpp"
#include "engine/simulation.hpp"

namespace {
std::atomic<long> allocations{0};
}

// Every replaceable form goes through malloc/free, so pairs always match (the library's temporary
// buffers use the nothrow form, for example).
namespace {
void* counted_malloc(std::size_t n) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
}  // namespace

#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
  if (void* p = counted_malloc(n)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) {
  if (void* p = counted_malloc(n)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  return counted_malloc(n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return counted_malloc(n);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}

TEST(SteadyState, StepsAllocateNothing) {
  const std::string path = std::string(RIFT_SOURCE_DIR) + "/scenes/examples/quickstart.yaml";
  rift::RunOptions o;
  o.write_output = false;
  o.progress = false;
  for (int threads : {1, 2}) {
    o.threads = threads;
    rift::Simulation sim(rift::load_scene(path), o);
    for (int i = 0; i < 20; ++i) sim.step_once();  // warm-up
    const long before = allocations.load();
    for (int i = 0; i < 200; ++i) sim.step_once();
    EXPECT_EQ(allocations.load() - before, 0) << threads << " thread(s)";
  }
}
