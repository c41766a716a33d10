#pragma once
// The output folder of a run or a sweep.
#include <filesystem>

namespace rift {

// Creates `dir` and its missing parents, or takes the folder that is there. Throws rift::Error naming
// the folder and the reason when it is something else than a folder (a regular file, a path under a
// regular file), cannot be created (e.g. under /proc) or cannot be written.
void create_output_dir(const std::filesystem::path& dir);

}  // namespace rift
