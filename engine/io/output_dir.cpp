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

}  // namespace rift
