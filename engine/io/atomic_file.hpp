#pragma once
// Crash-safe file replacement. Every output file (HDF5, XDMF index, JSON) is written to a temporary
// sibling `<target>.tmp-<pid>`, flushed to disk and renamed over the target, so a run killed at any
// moment leaves either the previous complete file or the new complete file, never a torn one.
// rename(2) is atomic only within one file system, which the sibling temp guarantees.
// The temp file is always created exclusively (O_CREAT | O_EXCL | O_NOFOLLOW, or HDF5's H5F_ACC_EXCL),
// so a symbolic link planted at its predictable name can never make a writer truncate the link's target.
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace rift {

class AtomicPath {
 public:
  // Removes whatever is at temp() already: a leftover of a dead process that had our pid, or a planted
  // link (unlink removes the link itself, never its target). The writer then creates temp() exclusively.
  explicit AtomicPath(std::filesystem::path target);
  AtomicPath(const AtomicPath&) = delete;
  AtomicPath& operator=(const AtomicPath&) = delete;
  // Removes the temporary file unless commit() succeeded.
  ~AtomicPath();

  const std::filesystem::path& target() const { return target_; }
  // Where the caller writes. The caller creates it exclusively (create_temp(), or
  // H5File::Mode::create), so that nothing is written through a link someone puts there meanwhile.
  const std::filesystem::path& temp() const { return temp_; }
  // Creates temp() with O_CREAT | O_EXCL | O_NOFOLLOW for writing and returns the descriptor, which the
  // caller closes. Throws rift::Error naming the file and the OS reason.
  int create_temp() const;

  // fsyncs the temp file, renames it over the target and fsyncs the directory (so the rename itself
  // survives a power cut). The temp file must be closed by the writer first. Throws rift::Error.
  void commit();
  bool committed() const { return committed_; }

  // True for names produced by temp(): "anything.tmp-<digits>".
  static bool is_temp_name(const std::filesystem::path& path);
  // The temporary file the process `pid` writes for `target`: exactly what temp() is in that process.
  static std::filesystem::path temp_for(const std::filesystem::path& target, pid_t pid);
  // The target's file name and the writer's pid when `name` is exactly what temp_for makes ("x.tmp-12");
  // nullopt for any other name ("x.tmp-", "x.tmp-+1", "x.tmp-012", "x.tmp-99999999999999999999").
  struct TempName {
    std::string target;
    pid_t pid;
  };
  static std::optional<TempName> parse_temp_name(std::string_view name);
  // The temp file of a process that no longer exists (kill(pid, 0) says ESRCH): a killed writer's
  // leftover, safe to delete. False for this process and any live one.
  static bool writer_is_gone(pid_t pid);

 private:
  std::filesystem::path target_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

// Writes `text` to `path` through an AtomicPath.
void write_text_atomic(const std::filesystem::path& path, std::string_view text);

}  // namespace rift
