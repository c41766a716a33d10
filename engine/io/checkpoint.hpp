#pragma once
// Checkpoints: the whole Store plus the run's clock and scene in one HDF5 file, written atomically.
//
// Layout (format_version 3):
//   bytes 0 - 511      the seal: FNV-1a 64 and length of the rest of the file (file_seal.hpp), checked
//                      before HDF5 opens the file; HDF5's user block, so HDF5 itself skips it
//   /                  attributes format_version, rift_version, scene_hash, step, time, dt, meta_fnv1a64
//   /scene             string dataset: the resolved scene YAML the run was built from
//   /scalars           group; one double attribute per entry of CheckpointMeta::scalars
//   /integers          group; one int64 attribute per entry of CheckpointMeta::integers
//   /tables/<table>    group with attribute rows; one dataset per column, named like the column,
//                      with attributes type ("f64" ...), components and fnv1a64; rows x components values
//
// Integrity: fnv1a64 (16 hex digits) is the FNV-1a 64 of a column's values as stored (little-endian);
// meta_fnv1a64 covers everything else: the attributes above, the scene text, the scalars and integers,
// every table's row count and every column's type, components and fnv1a64. A reader recomputes both,
// so one changed byte anywhere in the data or the metadata is reported instead of restored. The seal
// comes first: it finds a changed byte in HDF5's own structure too, before HDF5 parses it, and the
// per-column sums then name the column when HDF5's structure is intact but a value is not (a file
// resealed after the change, or written wrong).
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

inline constexpr int64_t checkpoint_format_version = 3;

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

// Checks that `file` is an intact checkpoint this build reads, without any store: it opens, has this
// format_version, and its metadata and the data of every column match their checksums (every value
// is read once). Returns the metadata; throws rift::Error naming the file and what is wrong with it.
CheckpointMeta verify_checkpoint(const std::filesystem::path& file);

// Every table and column of the checkpoint must already exist in `store` and vice versa; tables are
// resized to the stored row count. On any mismatch of tables or columns nothing in `store` is changed
// and a rift::Error names the file and the table/column. Each column's checksum is checked as it is
// read: a damaged column throws after the columns before it were restored (verify_checkpoint first
// tells whether a file is intact without touching a store). Then every column that declares an
// IndexTarget is checked against it: an index out of range throws, naming the column, row and value.
CheckpointMeta read_checkpoint(const std::filesystem::path& file, Store& store);

// A checkpoint a restart could not use, and why.
struct CheckpointProblem {
  std::filesystem::path file;
  std::string reason;
};

// The checkpoints of one run: out_dir/checkpoints/ckpt_<step:010>.h5, pruned to the newest `keep`.
class CheckpointSet {
 public:
  CheckpointSet(std::filesystem::path out_dir, int keep);  // keep >= 1; refuses a `checkpoints` link

  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path path_for(int64_t step) const;

  // Writes the checkpoint for meta.step, then deletes all but the newest `keep` checkpoints and the
  // temporary files our writer left for them ("ckpt_<step:010>.h5.tmp-<pid>") whose process no longer
  // exists. Only regular files of exactly these names, inside the folder itself, are deleted: links
  // and any other file are left alone.
  std::filesystem::path write(const Store& store, const CheckpointMeta& meta);

  // The newest checkpoint that verify_checkpoint accepts. Each newer one that it rejects (truncated,
  // foreign, another format_version, a checksum that does not match) is appended to `skipped`, newest
  // first, with the reason.
  std::optional<std::filesystem::path> latest(std::vector<CheckpointProblem>* skipped = nullptr) const;

  // All ckpt_<step>.h5 regular files by step, oldest first (intact or not).
  std::vector<std::pair<int64_t, std::filesystem::path>> list() const;

 private:
  // The folder must not be a symbolic link: checkpoints are written, and old ones deleted, inside the
  // output folder only. Throws rift::Error when it is one.
  void check_not_link() const;
  void prune() const;

  std::filesystem::path dir_;
  int keep_;
};

}  // namespace rift
