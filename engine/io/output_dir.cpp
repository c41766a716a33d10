#include "engine/io/output_dir.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "engine/core/error.hpp"

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

}  // namespace rift
