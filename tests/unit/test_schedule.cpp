// The step graph derived from declared column access: ordering, concurrency, reduction, DOT.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <thread>

#include "engine/core/table.hpp"
#include "engine/schedule/parallel.hpp"
#include "engine/schedule/step_graph.hpp"

using namespace rift;

namespace {

class FakeSystem : public System {
 public:
  FakeSystem(std::string name, Access access, std::function<void()> body = {})
      : name_(std::move(name)), access_(std::move(access)), body_(std::move(body)) {}
  std::string name() const override { return name_; }
  Access access() const override { return access_; }
  void run(const StepContext&) override {
    if (body_) body_();
  }

 private:
  std::string name_;
  Access access_;
  std::function<void()> body_;
};

bool has_edge(const StepGraph& g, int a, int b) {
  const auto& s = g.successors()[a];
  return std::find(s.begin(), s.end(), b) != s.end();
}

}  // namespace

TEST(StepGraph, EdgesFollowReadWriteConflictsAndAreReduced) {
  FakeSystem a("loads", {{"node.x"}, {"face.f"}});
  FakeSystem b("tets", {{"node.x", "node.v"}, {"tet.f"}});
  FakeSystem c("integrate", {{"tet.f", "face.f"}, {"node.x", "node.v"}});
  FakeSystem d("output_probe", {{"node.x", "tet.f"}, {}});
  StepGraph g({&a, &b, &c, &d}, 1);
  EXPECT_FALSE(has_edge(g, 0, 1));  // loads and tets only read shared columns: concurrent
  EXPECT_TRUE(
      has_edge(g, 0, 2));  // integrate reads face.f (read after write) and writes node.x (write after read)
  EXPECT_TRUE(has_edge(g, 1, 2));
  EXPECT_TRUE(has_edge(g, 2, 3));   // probe reads node.x written by integrate
  EXPECT_FALSE(has_edge(g, 1, 3));  // implied through integrate: reduced away
  const std::string dot = g.dot();
  EXPECT_NE(dot.find("s0 -> s2"), std::string::npos);
  EXPECT_NE(dot.find("digraph"), std::string::npos);
}

TEST(StepGraph, TopologyChangeSerialisesEverything) {
  FakeSystem a("a", {{"x.a"}, {"x.b"}});
  Access topo{{}, {"joint.state"}, {}, true};
  FakeSystem b("failure", topo);
  FakeSystem c("c", {{"y.a"}, {"y.b"}});
  StepGraph g({&a, &b, &c}, 2);
  EXPECT_TRUE(has_edge(g, 0, 1));
  EXPECT_TRUE(has_edge(g, 1, 2));
}

TEST(StepGraph, AResizeOrdersOnlyTheTablesUsers) {
  // contact resizes its pair table: ordered against the one that reads a pair column, not the others.
  FakeSystem contact("contact", {{"node.x"}, {"node.contact_force"}, {"pair"}});
  FakeSystem tets("tets", {{"node.x"}, {"tet.f"}});
  FakeSystem probe("pair_probe", {{"pair.force"}, {}});
  StepGraph g({&contact, &tets, &probe}, 2);
  EXPECT_FALSE(has_edge(g, 0, 1));  // tets never touch the pair table: concurrent
  EXPECT_TRUE(has_edge(g, 0, 2));
  EXPECT_EQ(access_conflict(contact.access(), probe.access()), "pair (rows)");
  EXPECT_EQ(access_conflict(contact.access(), tets.access()), "");
}

TEST(StepGraph, ReaderAlwaysRunsAfterWriter) {
  std::atomic<int> counter{0};
  std::vector<int> seen(3);
  auto work = [] {
    volatile double s = 0;
    for (int i = 0; i < 20000; ++i) s = s + i;
  };
  FakeSystem w("writer", {{}, {"t.c"}}, [&] {
    work();
    seen[0] = counter++;
  });
  FakeSystem other("independent", {{"u.a"}, {"u.b"}}, [&] {
    work();
    seen[1] = counter++;
  });
  FakeSystem r("reader", {{"t.c"}, {}}, [&] { seen[2] = counter++; });
  StepGraph g({&w, &other, &r}, 2);
  g.set_tracing(true);
  for (int step = 0; step < 200; ++step) {
    g.run_step({step, 0.0, 1.0});
    EXPECT_LT(seen[0], seen[2]) << "step " << step;
  }
  for (size_t i = 0; i + 2 < g.intervals().size(); i += 3) {
    // Within each step the writer's interval ends before the reader's begins.
    double w_end = -1, r_begin = -1;
    for (size_t k = i; k < i + 3; ++k) {
      if (g.intervals()[k].system == 0) w_end = g.intervals()[k].end;
      if (g.intervals()[k].system == 2) r_begin = g.intervals()[k].begin;
    }
    EXPECT_LE(w_end, r_begin);
  }
  EXPECT_EQ(g.timings()[0].calls, 200);
}

TEST(StepGraph, IndependentSystemsOverlapOnTwoThreads) {
  // Each system waits (bounded) until the other has started: they can only both finish early if the
  // graph runs them at the same time. The recorded intervals must overlap.
  std::atomic<int> started{0};
  auto rendezvous = [&] {
    started++;
    const auto t0 = std::chrono::steady_clock::now();
    while (started.load() < 2 && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(5))
      std::this_thread::yield();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  };
  FakeSystem a("tets", {{"n.x"}, {"tet.f"}}, rendezvous);
  FakeSystem b("loads", {{"n.x"}, {"face.f"}}, rendezvous);
  StepGraph g({&a, &b}, 2);
  g.set_tracing(true);
  g.run_step({0, 0.0, 1.0});
  ASSERT_EQ(g.intervals().size(), 2u);
  const auto& i0 = g.intervals()[0];
  const auto& i1 = g.intervals()[1];
  EXPECT_LT(i0.begin, i1.end);
  EXPECT_LT(i1.begin, i0.end);
  EXPECT_EQ(started.load(), 2);
}

TEST(Parallel, SumIsIdenticalOnAnyThreadCount) {
  std::vector<double> values(100003);
  for (size_t i = 0; i < values.size(); ++i) values[i] = 1.0 / (1.0 + double(i) * 0.37);
  double reference = 0;
  for (int threads : {1, 2, 8}) {
    tbb::task_arena arena(threads);
    double total = 0;
    std::vector<double> partials;
    arena.execute([&] {
      total = parallel_sum<double>(values.size(), 1000, partials, [&](size_t b, size_t e) {
        double s = 0;
        for (size_t i = b; i < e; ++i) s += values[i];
        return s;
      });
    });
    if (threads == 1) reference = total;
    EXPECT_EQ(total, reference) << threads << " threads";
  }
}

namespace {
// A system that records the steps it ran at.
class WindowSystem : public FakeSystem {
 public:
  explicit WindowSystem(std::vector<int64_t>& ran)
      : FakeSystem("window", {{"fluid.u"}, {"fluid.p"}}), ran_(ran) {}
  void run(const StepContext& ctx) override { ran_.push_back(ctx.step); }

 private:
  std::vector<int64_t>& ran_;
};
}  // namespace

TEST(StepGraph, APeriodicSystemRunsOnlyAtTheEndOfEachWindow) {
  for (int threads : {1, 2}) {
    std::vector<int64_t> ran;
    WindowSystem w(ran);
    FakeSystem every("every_step", {{"fluid.p"}, {"node.x"}});
    StepGraph g({&w, &every}, threads, {4, 1});
    for (int64_t step = 0; step < 10; ++step) g.run_step({step, 0.0, 1.0});
    EXPECT_EQ(ran, (std::vector<int64_t>{3, 7}));  // steps 0-3 and 4-7 end a window; 8-9 do not
    EXPECT_EQ(g.timings()[0].calls, 2);
    EXPECT_EQ(g.timings()[1].calls, 10);
    EXPECT_NE(g.dot().find("every 4 steps"), std::string::npos);
  }
}
