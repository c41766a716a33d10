#pragma once
// Checkpoints: the whole Store plus the run's clock and scene in one HDF5 file, written atomically.
//
// Layout (format_version 1):
//   /                  attributes format_version, rift_version, scene_hash, step, time, dt
//   /scene             string dataset: the resolved scene YAML the run was built from
//   /scalars           group; one double attribute per entry of CheckpointMeta::scalars
//   /integers          group; one int64 attribute per entry of CheckpointMeta::integers
//   /tables/<table>    group with attribute rows; one dataset per column, named like the column,
//                      with attributes type ("f64" ...) and components; rows x components values
//
// Restoring is strict: the run rebuilds its world from the scene first, so every table and column
// must exist on both sides with the same type and component count. Values come back bit for bit
// (little-endian IEEE/two's complement on both sides, no conversion).
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/table.hpp"

namespace rift {

inline constexpr int64_t checkpoint_format_version = 1;

struct CheckpointMeta {
  int64_t step = 0;
  double time = 0.0;
  double dt = 0.0;
  std::string scene_hash;
  std::string resolved_scene;
  std::string rift_version;
  std::map<std::string, double> scalars;    // run state outside the tables (e.g. energy totals)
  std::map<std::string, int64_t> integers;  // e.g. mesh revision counters, RNG state words
};

// Atomic: a crash leaves the previous `file` (if any) intact. Throws rift::Error.
void write_checkpoint(const std::filesystem::path& file, const Store& store, const CheckpointMeta& meta);

// Every table and column of the checkpoint must already exist in `store` and vice versa; tables are
// resized to the stored row count. On any mismatch nothing in `store` is changed and a rift::Error
// names the file and the table/column.
CheckpointMeta read_checkpoint(const std::filesystem::path& file, Store& store);

// The checkpoints of one run: out_dir/checkpoints/ckpt_<step:010>.h5, pruned to the newest `keep`.
class CheckpointSet {
 public:
  CheckpointSet(std::filesystem::path out_dir, int keep);  // keep >= 1

  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path path_for(int64_t step) const;

  // Writes the checkpoint for meta.step, then deletes all but the newest `keep` checkpoints and the
  // temporary files our writer left for them ("ckpt_<step:010>.h5.tmp-<pid>") whose process no longer
  // exists. Any other file in the folder is left alone.
  std::filesystem::path write(const Store& store, const CheckpointMeta& meta);

  // The newest checkpoint that opens as a Rift checkpoint; temp leftovers and truncated or foreign
  // files are skipped.
  std::optional<std::filesystem::path> latest() const;

  // All ckpt_<step>.h5 files by step, oldest first (readable or not).
  std::vector<std::pair<int64_t, std::filesystem::path>> list() const;

 private:
  void prune() const;

  std::filesystem::path dir_;
  int keep_;
};

}  // namespace rift
