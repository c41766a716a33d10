#include "engine/io/output_dir.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>

#include "engine/core/error.hpp"
#include "engine/io/atomic_file.hpp"

namespace rift {

void create_output_dir(const std::filesystem::path& dir) {
  const std::string where = "output folder '" + dir.string() + "'";
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(dir, ec);
  if (std::filesystem::exists(status) && !std::filesystem::is_directory(status))
    throw Error(where + " exists and is not a folder" +
                (std::filesystem::is_regular_file(status) ? " (it is a regular file)" : "") +
                "; give another output folder (--out)");
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("cannot create " + where + ": " + ec.message());
  // The files come later, one by one: a folder they cannot go into is refused before the first.
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw Error("cannot write into " + where + ": " + std::strerror(errno));
}

std::vector<std::string> remove_orphan_temp_files(const std::filesystem::path& dir,
                                                  const std::function<bool(std::string_view name)>& ours) {
  std::vector<std::string> removed;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.symlink_status(ec).type() != std::filesystem::file_type::regular) continue;
    const std::string name = entry.path().filename().string();
    const std::optional<AtomicPath::TempName> temp = AtomicPath::parse_temp_name(name);
    if (!temp || !ours(temp->target) || !AtomicPath::writer_is_gone(temp->pid)) continue;
    if (::unlink(entry.path().c_str()) == 0) removed.push_back(name);  // gone meanwhile is fine
  }
  std::sort(removed.begin(), removed.end());
  return removed;
}

std::vector<std::string> earlier_run_files(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return out;
  static constexpr std::string_view kFiles[] = {"scene.yaml",    "summary.json",     "timeseries.csv",
                                                "fractures.csv", "rift.series.json", "rift.xdmf"};
  const auto regular = [](const std::filesystem::directory_entry& e) {
    std::error_code ignored;
    return e.is_regular_file(ignored) && !e.is_symlink(ignored);
  };
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    bool ours = std::find(std::begin(kFiles), std::end(kFiles), name) != std::end(kFiles);
    ours |= name.starts_with("rift_") && (name.ends_with(".h5") || name.ends_with(".xdmf"));
    if (ours && regular(e)) out.push_back(name);
  }
  if (std::filesystem::is_directory(dir / "checkpoints", ec) &&
      !std::filesystem::is_symlink(dir / "checkpoints", ec))
    for (const auto& e : std::filesystem::directory_iterator(dir / "checkpoints", ec)) {
      const std::string name = e.path().filename().string();
      if (name.starts_with("ckpt_") && name.ends_with(".h5") && regular(e))
        out.push_back("checkpoints/" + name);
    }
  std::sort(out.begin(), out.end());
  return out;
}

void remove_earlier_run(const std::filesystem::path& dir) {
  std::vector<std::string> names = earlier_run_files(dir);
  std::error_code ec;
  for (const char* extra : {"rift.log", "plots"})
    if (std::filesystem::exists(std::filesystem::symlink_status(dir / extra, ec))) names.emplace_back(extra);
  for (const std::string& name : names) {
    std::filesystem::remove_all(dir / name, ec);
    if (ec) throw Error("cannot remove " + (dir / name).string() + " of the earlier run: " + ec.message());
  }
}

}  // namespace rift
