#pragma once
// The output folder of a run or a sweep.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace rift {

// Creates `dir` and its missing parents, or takes the folder that is there. Throws rift::Error naming
// the folder and the reason when it is something else than a folder (a regular file, a path under a
// regular file), cannot be created (e.g. under /proc) or cannot be written.
void create_output_dir(const std::filesystem::path& dir);

// The files in `dir` that show an earlier run there, by Rift's own names (regular files only): scene.yaml,
// summary.json, timeseries.csv, fractures.csv, the field series (rift.xdmf, rift_*.xdmf, rift_*.h5,
// rift.series.json) and checkpoints/ckpt_*.h5. Sorted; empty when there are none or no `dir`.
std::vector<std::string> earlier_run_files(const std::filesystem::path& dir);

// Deletes what earlier_run_files names, and the earlier run's rift.log and plots/ (regular files and a
// folder of that name; links are removed, never followed). Throws rift::Error on failure.
void remove_earlier_run(const std::filesystem::path& dir);

// Deletes the leftovers of killed writers in `dir` (not below it): regular files named
// `<name>.tmp-<pid>` exactly as AtomicPath names its temp files, whose <name> `ours` recognises as one
// of the run's outputs and whose writer process is gone. Links, other names, live writers' files and
// this process's are left alone. Returns the names deleted, sorted.
std::vector<std::string> remove_orphan_temp_files(const std::filesystem::path& dir,
                                                  const std::function<bool(std::string_view name)>& ours);

}  // namespace rift
