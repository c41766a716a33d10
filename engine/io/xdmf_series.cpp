#include "engine/io/xdmf_series.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "engine/core/error.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/hdf5_file.hpp"
#include "engine/io/xdmf_index.hpp"

namespace rift {

int nodes_per_cell(Topology topology) {
  switch (topology) {
    case Topology::tetrahedron:
      return 4;
    case Topology::wedge:
      return 6;
    case Topology::triangle:
      return 3;
  }
  return 0;
}

namespace {

bool is_plain_name(const std::string& name) {
  return !name.empty() && name.find('/') == std::string::npos && name.find(':') == std::string::npos;
}

std::string step_file_name(const std::string& basename, int64_t step) {
  char digits[32];
  std::snprintf(digits, sizeof digits, "%08lld", static_cast<long long>(step));
  return basename + "_" + digits + ".h5";
}

std::string mesh_file_name(const std::string& basename, const std::string& grid, uint64_t revision) {
  return basename + "_mesh_" + grid + "_" + std::to_string(revision) + ".h5";
}

}  // namespace

XdmfSeries::XdmfSeries(std::filesystem::path dir, std::string basename)
    : dir_(std::move(dir)), basename_(std::move(basename)) {
  if (!is_plain_name(basename_))
    throw Error("XDMF series basename '" + basename_ + "' must be non-empty and contain no '/' or ':'");
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw Error("cannot create output directory '" + dir_.string() + "': " + ec.message());
}

std::filesystem::path XdmfSeries::index_path() const {
  return dir_ / (basename_ + ".xdmf");
}
std::filesystem::path XdmfSeries::grid_index_path(const std::string& grid) const {
  return dir_ / (basename_ + "_" + grid + ".xdmf");
}
std::filesystem::path XdmfSeries::sidecar_path() const {
  return dir_ / (basename_ + ".series.json");
}

bool XdmfSeries::is_own_file_name(std::string_view name) const {
  if (name == basename_ + ".xdmf" || name == basename_ + ".series.json") return true;
  return name.size() > basename_.size() + 5 && name.starts_with(basename_ + "_") &&
         (name.ends_with(".h5") || name.ends_with(".xdmf"));
}

void XdmfSeries::check_grids(std::span<const XdmfGrid> grids) const {
  std::set<std::string> names;
  for (const XdmfGrid& g : grids) {
    const std::string where = "XDMF series " + basename_ + ", grid '" + g.name + "'";
    if (!is_plain_name(g.name))
      throw Error(where + ": grid names must be non-empty and contain no '/' or ':'");
    if (!names.insert(g.name).second) throw Error(where + ": the same grid is given twice");
    if ((g.point_count && !g.points) || (g.cell_count && !g.cells))
      throw Error(where + ": missing data pointer");
    const size_t n = g.cell_count * nodes_per_cell(g.topology);
    for (size_t i = 0; i < n; ++i)
      if (g.cells[i] < 0 || static_cast<size_t>(g.cells[i]) >= g.point_count)
        throw Error(where + ": cell " + std::to_string(i / nodes_per_cell(g.topology)) + " refers to node " +
                    std::to_string(g.cells[i]) + ", expected a node index below " +
                    std::to_string(g.point_count));
    std::set<std::string> fields;
    for (const XdmfField& f : g.fields) {
      const std::string at = where + ", field '" + f.name + "'";
      if (f.name.empty() || f.name.find('/') != std::string::npos || f.name == "points")
        throw Error(at + ": field names must be non-empty, contain no '/' and not be 'points'");
      if (!fields.insert(f.name).second) throw Error(at + ": the same field is given twice");
      const size_t expected = f.center == Center::node ? g.point_count : g.cell_count;
      if (f.rows != expected)
        throw Error(at + ": has " + std::to_string(f.rows) + " rows, expected " + std::to_string(expected) +
                    (f.center == Center::node ? " (one per node)" : " (one per cell)"));
      if (f.components < 1) throw Error(at + ": needs at least one component");
      if (f.rows && !f.data) throw Error(at + ": missing data pointer");
    }
  }
}

void XdmfSeries::write_mesh_files(std::span<const XdmfGrid> grids) {
  for (const XdmfGrid& g : grids) {
    if (g.cell_count == 0) continue;
    const auto known = mesh_.find(g.name);
    const bool same_revision = known != mesh_.end() && known->second.revision == g.mesh_revision;
    if (same_revision && (g.points_move || known->second.has_points)) continue;
    if (!same_revision)
      for (const Entry& e : entries_)
        for (const GridEntry& ge : e.grids)
          if (ge.name == g.name && ge.mesh_revision == g.mesh_revision)
            throw Error("XDMF series " + basename_ + ", grid '" + g.name + "': mesh_revision " +
                        std::to_string(g.mesh_revision) + " was already used by the output at time " +
                        std::to_string(e.time) + " for another mesh; revisions must keep increasing " +
                        "(restore the counter from the checkpoint on restart)");
    const std::filesystem::path target = dir_ / mesh_file_name(basename_, g.name, g.mesh_revision);
    AtomicPath atomic(target);
    H5File file(atomic.temp(), H5File::Mode::create);
    file.write("/cells", ElementType::i32, g.cells, g.cell_count, nodes_per_cell(g.topology));
    if (!g.points_move) file.write("/points", ElementType::f64, g.points, g.point_count, 3);
    file.set_int_attr("/", "mesh_revision", static_cast<int64_t>(g.mesh_revision));
    file.close();
    atomic.commit();
    mesh_[g.name] = {g.mesh_revision, !g.points_move};
  }
}

XdmfSeries::Entry XdmfSeries::write_step_file(double time, int64_t step,
                                              std::span<const XdmfGrid> grids) const {
  const std::string step_file = step_file_name(basename_, step);
  Entry entry{time, step, {}};
  bool has_data = false;
  for (const XdmfGrid& g : grids) {
    if (g.cell_count == 0) continue;
    const std::string mesh_file = mesh_file_name(basename_, g.name, g.mesh_revision);
    const std::string prefix = "/" + g.name + "/";
    GridEntry ge{g.name, g.topology, g.mesh_revision, {}, {}, {}};
    ge.cells = {mesh_file, "/cells", g.cell_count, nodes_per_cell(g.topology), ElementType::i32};
    ge.points = {g.points_move ? step_file : mesh_file, g.points_move ? prefix + "points" : "/points",
                 g.point_count, 3, ElementType::f64};
    has_data |= g.points_move;
    for (const XdmfField& f : g.fields) {
      ge.fields.push_back({f.name, f.center, {step_file, prefix + f.name, f.rows, f.components, f.type}});
      has_data = true;
    }
    entry.grids.push_back(std::move(ge));
  }
  if (!has_data) return entry;

  AtomicPath atomic(dir_ / step_file);
  H5File file(atomic.temp(), H5File::Mode::create);
  file.set_double_attr("/", "time", time);
  file.set_int_attr("/", "step", step);
  for (const XdmfGrid& g : grids) {
    if (g.cell_count == 0) continue;
    const std::string prefix = "/" + g.name + "/";
    if (g.points_move) file.write(prefix + "points", ElementType::f64, g.points, g.point_count, 3);
    for (const XdmfField& f : g.fields) file.write(prefix + f.name, f.type, f.data, f.rows, f.components);
  }
  file.close();
  atomic.commit();
  return entry;
}

void XdmfSeries::write(double time, int64_t step, std::span<const XdmfGrid> grids) {
  const std::string where = "XDMF series " + (dir_ / basename_).string();
  if (!std::isfinite(time)) throw Error(where + ": output time is not finite");
  if (step < 0) throw Error(where + ": step " + std::to_string(step) + " is negative");
  if (!entries_.empty() && time < entries_.back().time)
    throw Error(where + ": output time " + std::to_string(time) + " is earlier than the last entry's " +
                std::to_string(entries_.back().time) + " (after a restart, call resume(time) first)");
  check_grids(grids);
  while (!entries_.empty() && entries_.back().time == time) entries_.pop_back();  // same time: replace

  write_mesh_files(grids);
  entries_.push_back(write_step_file(time, step, grids));
  save_index();
}

void XdmfSeries::save_index() const {
  // The sidecar first: if the run dies between the two, the old .xdmf is still valid and resume()
  // reads the newer sidecar.
  write_text_atomic(sidecar_path(), xdmf::entries_to_json(entries_).dump(1) + "\n");
  write_text_atomic(index_path(), xdmf::render_index(basename_, entries_));
  std::set<std::string> grids;
  for (const Entry& e : entries_)
    for (const GridEntry& g : e.grids) grids.insert(g.name);
  for (const std::string& g : grids)
    write_text_atomic(grid_index_path(g), xdmf::render_grid_index(g, entries_));
}

void XdmfSeries::load_sidecar() {
  entries_.clear();
  const std::filesystem::path path = sidecar_path();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return;  // no output was written before the checkpoint
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  if (!in) throw Error("cannot read XDMF series index " + path.string());
  const auto json = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded()) throw Error("XDMF series index " + path.string() + " is not valid JSON");
  entries_ = xdmf::entries_from_json(json, path.string());
}

void XdmfSeries::rebuild_mesh_state() {
  mesh_.clear();
  for (const Entry& e : entries_)
    for (const GridEntry& g : e.grids) mesh_[g.name] = {g.mesh_revision, g.points.file == g.cells.file};
}

void XdmfSeries::resume(double time) {
  load_sidecar();
  // Only files this series wrote for the dropped entries are deleted: the step file and mesh files named
  // exactly as write() names them, in dir_. The sidecar is a file anyone can edit; a name in it such as
  // "/home/x" or "../x" is never deleted.
  std::set<std::string> kept, dropped;
  auto files_of = [](const Entry& e, std::set<std::string>& out) {
    for (const GridEntry& g : e.grids) {
      out.insert(g.points.file);
      out.insert(g.cells.file);
      for (const FieldEntry& f : g.fields) out.insert(f.data.file);
    }
  };
  auto own_files_of = [&](const Entry& e, std::set<std::string>& out) {
    std::set<std::string> named;
    files_of(e, named);
    std::set<std::string> own{step_file_name(basename_, e.step)};
    for (const GridEntry& g : e.grids)
      if (is_plain_name(g.name)) own.insert(mesh_file_name(basename_, g.name, g.mesh_revision));
    for (const std::string& file : named)
      if (own.count(file) && is_plain_name(file)) out.insert(file);
  };
  while (!entries_.empty() && entries_.back().time > time) {
    own_files_of(entries_.back(), dropped);
    entries_.pop_back();
  }
  for (const Entry& e : entries_) files_of(e, kept);
  for (const std::string& file : dropped) {
    if (kept.count(file)) continue;
    std::error_code ignored;  // already gone is fine; remove() deletes a link itself, not its target
    std::filesystem::remove(dir_ / file, ignored);
  }
  rebuild_mesh_state();
  save_index();
}

}  // namespace rift
