#pragma once
// Time series output for ParaView: HDF5 files for the numbers, one XDMF index for their meaning.
//
//   dir/basename.xdmf                  the index ParaView opens (rewritten atomically after each output)
//   dir/basename_<grid>.xdmf           one grid alone (solid, joints, surface, fluid): XDMF 3.0, what
//                                      meshio reads; in ParaView one block that keeps its name
//   dir/basename.series.json           the same entries as data, so a restart can rebuild the index
//   dir/basename_mesh_<grid>_<rev>.h5  /cells (and /points when the grid's points do not move),
//                                      written only when the grid's mesh_revision changes
//   dir/basename_<step:08>.h5          /<grid>/<field> for every field, /<grid>/points for moving grids
//
// XDMF version 2.0: ParaView 5.11 offers three readers for .xdmf ("XDMF Reader", built on libXdmf 2,
// and "Xdmf3ReaderS"/"Xdmf3ReaderT", built on libXdmf 3). libXdmf 3 reads version-2 files (checked
// with Debian's libxdmf3), while the libXdmf 2 reader predates the 3.0 format; 2.0 restricted to what
// both know (Temporal and Spatial collections, Uniform grids, HDF DataItems, no XInclude) opens with
// whichever reader the user picks, and is what deal.II writes. <Time> sits on each spatial collection
// and is repeated on its grids, so a reader taking the time from either level sees the same value.
//
// A grid with no cells (e.g. joints before the first crack) is left out of that output's index
// entry: there is nothing to draw, and zero-size HDF DataItems are an edge case best kept from readers.
#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/table.hpp"

namespace rift {

enum class Topology { tetrahedron, wedge, triangle };  // 4, 6, 3 nodes per cell; wedge node order = VTK_WEDGE
enum class Center { node, cell };

int nodes_per_cell(Topology topology);

struct XdmfField {
  std::string name;
  Center center;
  int components;  // 1 scalar, 3 vector, 6 symmetric tensor (XDMF Tensor6: xx xy xz yy yz zz), 9 tensor, else
                   // matrix
  ElementType type;
  const void* data;  // rows x components, row-major
  size_t rows;       // must equal the grid's point_count (node) or cell_count (cell)
};

struct XdmfGrid {
  std::string name;  // "solid", "joints", "surface" ...
  Topology topology;
  const double* points;  // xyz interleaved
  size_t point_count;
  const int32_t* cells;  // connectivity, 0-based
  size_t cell_count;
  uint64_t mesh_revision;  // the series rewrites connectivity only when this changes
  bool points_move;        // true: geometry written with every output; false: with the mesh, so the
                           // points may then change only together with mesh_revision
  std::vector<XdmfField> fields;
};

class XdmfSeries {
 public:
  // Creates `dir` when missing. A new series starts empty: the first write() replaces any index
  // left in `dir` by an earlier run (call resume() instead to continue one).
  XdmfSeries(std::filesystem::path dir, std::string basename);

  // Appends one output. `time` must not be earlier than the last entry's; an entry at the same time
  // is replaced (a restarted run writing its first output again). Throws rift::Error.
  void write(double time, int64_t step, std::span<const XdmfGrid> grids);

  // Restart: reloads the entries from the sidecar JSON, drops those later than `time`, deletes the
  // files only they referenced and rewrites the index. mesh_revision counters must be restored by the
  // caller (e.g. from the checkpoint): reusing an earlier revision number for a different mesh is
  // refused rather than silently overwriting the file older entries point to.
  void resume(double time);

  size_t entries() const { return entries_.size(); }
  std::filesystem::path index_path() const;  // dir/basename.xdmf
  // dir/basename_<grid>.xdmf: the index of one grid alone (xdmf_index.hpp), rewritten with the index.
  std::filesystem::path grid_index_path(const std::string& grid) const;
  std::filesystem::path sidecar_path() const;  // dir/basename.series.json
  // A name this series writes: the index, the sidecar, or a data file "basename_<...>.h5".
  bool is_own_file_name(std::string_view name) const;

  // Where one array lives: `file` is relative to the series directory.
  struct DataRef {
    std::string file;
    std::string path;
    size_t rows = 0;
    int components = 1;
    ElementType type = ElementType::f64;
  };
  struct FieldEntry {
    std::string name;
    Center center;
    DataRef data;
  };
  struct GridEntry {
    std::string name;
    Topology topology;
    uint64_t mesh_revision;
    DataRef points;
    DataRef cells;
    std::vector<FieldEntry> fields;
  };
  struct Entry {
    double time;
    int64_t step;
    std::vector<GridEntry> grids;
  };

 private:
  // What the current mesh file of a grid holds.
  struct MeshState {
    uint64_t revision;
    bool has_points;
  };

  void check_grids(std::span<const XdmfGrid> grids) const;
  void write_mesh_files(std::span<const XdmfGrid> grids);
  Entry write_step_file(double time, int64_t step, std::span<const XdmfGrid> grids) const;
  void save_index() const;
  void load_sidecar();
  void rebuild_mesh_state();

  std::filesystem::path dir_;
  std::string basename_;
  std::vector<Entry> entries_;
  std::map<std::string, MeshState> mesh_;  // by grid name
};

}  // namespace rift
