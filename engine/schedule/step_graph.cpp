#include "engine/schedule/step_graph.hpp"

#include <algorithm>
#include <mutex>
#include <set>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/schedule/access_check.hpp"

namespace rift {

namespace {

bool contains(const std::vector<std::string>& list, const std::string& key) {
  return std::find(list.begin(), list.end(), key) != list.end();
}

std::mutex trace_mutex;

// The first column of `a` (reads or writes) in `table`, or "".
std::string column_of(const Access& a, const std::string& table) {
  const std::string prefix = table + ".";
  for (const auto* list : {&a.reads, &a.writes})
    for (const auto& c : *list)
      if (c.rfind(prefix, 0) == 0) return c;
  return "";
}

}  // namespace

std::string access_conflict(const Access& earlier, const Access& later) {
  if (earlier.changes_topology || later.changes_topology) return "topology";
  for (const auto& w : earlier.writes)
    if (contains(later.reads, w) || contains(later.writes, w)) return w;
  for (const auto& w : later.writes)
    if (contains(earlier.reads, w)) return w;
  // A table's rows change under everything that uses any of its columns.
  for (const auto& [one, other] : {std::pair{&earlier, &later}, std::pair{&later, &earlier}})
    for (const auto& t : one->resizes)
      if (contains(other->resizes, t) || !column_of(*other, t).empty()) return t + " (rows)";
  return "";
}

StepGraph::StepGraph(std::vector<System*> systems, int threads, std::vector<int64_t> periods)
    : systems_(std::move(systems)), periods_(std::move(periods)), threads_(threads), arena_(threads) {
  if (threads < 1) throw Error("--threads must be at least 1, found " + std::to_string(threads));
  if (periods_.empty()) periods_.assign(systems_.size(), 1);
  if (periods_.size() != systems_.size())
    throw Error("internal: the step graph was given " + std::to_string(periods_.size()) + " periods for " +
                std::to_string(systems_.size()) + " systems");
  for (size_t i = 0; i < systems_.size(); ++i) {
    access_.push_back(systems_[i]->access());
    timings_.push_back({systems_[i]->name(), 0.0, 0});
    if (periods_[i] < 1)
      throw Error("internal: system " + systems_[i]->name() + " has period " + std::to_string(periods_[i]));
  }
  derive_edges();
  epoch_ = std::chrono::steady_clock::now();
  build_flow_graph();
}

StepGraph::~StepGraph() {
  if (graph_) arena_.execute([&] { graph_->wait_for_all(); });
}

void StepGraph::derive_edges() {
  const int n = static_cast<int>(systems_.size());
  // reach[i] = systems that must follow i (transitively); built from the last system backwards so a
  // direct edge i->j is kept only when j is not already reachable through an earlier-kept successor.
  std::vector<std::set<int>> reach(n);
  successors_.assign(n, {});
  edge_why_.assign(n, {});
  for (int i = n - 1; i >= 0; --i) {
    for (int j = i + 1; j < n; ++j) {
      const std::string why = access_conflict(access_[i], access_[j]);
      if (why.empty() || reach[i].count(j)) continue;
      successors_[i].push_back(j);
      edge_why_[i].push_back(why);
      reach[i].insert(j);
      reach[i].insert(reach[j].begin(), reach[j].end());
    }
  }
}

void StepGraph::build_flow_graph() {
  using namespace tbb::flow;
  arena_.execute([&] {
    graph_ = std::make_unique<graph>();
    start_ = std::make_unique<broadcast_node<continue_msg>>(*graph_);
    for (size_t i = 0; i < systems_.size(); ++i) {
      nodes_.push_back(std::make_unique<continue_node<continue_msg>>(*graph_, [this, i](const continue_msg&) {
        if (!runs_at(periods_[i], *current_)) return continue_msg();
        const auto t0 = std::chrono::steady_clock::now();
        systems_[i]->run(*current_);
        const auto t1 = std::chrono::steady_clock::now();
        timings_[i].seconds += std::chrono::duration<double>(t1 - t0).count();
        timings_[i].calls += 1;
        if (tracing_) {
          std::lock_guard lock(trace_mutex);
          intervals_.push_back({static_cast<int>(i), std::chrono::duration<double>(t0 - epoch_).count(),
                                std::chrono::duration<double>(t1 - epoch_).count()});
        }
        return continue_msg();
      }));
    }
    std::vector<bool> has_predecessor(systems_.size(), false);
    for (size_t i = 0; i < systems_.size(); ++i)
      for (int j : successors_[i]) {
        make_edge(*nodes_[i], *nodes_[j]);
        has_predecessor[j] = true;
      }
    for (size_t i = 0; i < systems_.size(); ++i)
      if (!has_predecessor[i]) make_edge(*start_, *nodes_[i]);
  });
}

void StepGraph::run_step(const StepContext& ctx) {
  if (checked_store_) return run_checked(ctx);
  current_ = &ctx;
  // Isolated: while it waits for the step, this thread runs only the step's own tasks, never a task a
  // stage of the step plan left running beside the graph (a `beside` stage). Otherwise it could pick up a
  // whole concurrent fluid solve and hold the solid's next step back until it ends.
  arena_.execute([&] {
    tbb::this_task_arena::isolate([&] {
      start_->try_put(tbb::flow::continue_msg());
      graph_->wait_for_all();
    });
  });
  current_ = nullptr;
}

void StepGraph::run_checked(const StepContext& ctx) {
  arena_.execute([&] {
    for (size_t i = 0; i < systems_.size(); ++i) {
      if (!runs_at(periods_[i], ctx)) continue;
      const StoreFingerprint before = fingerprint(*checked_store_);
      std::vector<std::string> looked_up;
      {
        LookupRecorder recorder;
        systems_[i]->run(ctx);
        looked_up = recorder.keys();
      }
      timings_[i].calls += 1;
      const std::string report =
          undeclared_changes(*checked_store_, before, access_[i], systems_[i]->name()) +
          undeclared_lookups(looked_up, access_[i], systems_[i]->name());
      if (!report.empty())
        throw Error("step " + std::to_string(ctx.step) + ": a system used what it did not declare " +
                    "(its access() is what the step graph orders it by):\n" + report);
    }
  });
}

std::string StepGraph::dot() const {
  std::ostringstream out;
  out << "digraph step {\n  rankdir=TB;\n  node [shape=box, style=rounded, fontname=\"Helvetica\"];\n";
  out << "  start [shape=circle, label=\"step\"];\n";
  std::vector<bool> has_predecessor(systems_.size(), false);
  for (size_t i = 0; i < systems_.size(); ++i)
    for (int j : successors_[i]) has_predecessor[j] = true;
  for (size_t i = 0; i < systems_.size(); ++i) {
    out << "  s" << i << " [label=\"" << systems_[i]->name() << "\\nreads " << access_[i].reads.size()
        << ", writes " << access_[i].writes.size() << " columns"
        << (periods_[i] > 1 ? "\\nevery " + std::to_string(periods_[i]) + " steps" : std::string())
        << "\"];\n";
    if (!has_predecessor[i]) out << "  start -> s" << i << ";\n";
  }
  for (size_t i = 0; i < systems_.size(); ++i)
    for (size_t k = 0; k < successors_[i].size(); ++k)
      out << "  s" << i << " -> s" << successors_[i][k] << " [label=\"" << edge_why_[i][k] << "\"];\n";
  out << "}\n";
  return out.str();
}

}  // namespace rift
