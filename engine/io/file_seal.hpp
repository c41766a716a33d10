#pragma once
// A whole-file checksum kept in the file's own first bytes, checked before any library parses the rest.
// Checkpoints use it: HDF5 1.10 does not read damaged metadata safely (a byte changed in an attribute
// message gave a heap-use-after-free inside H5Aopen_by_name under AddressSanitizer), so a checkpoint's
// bytes are verified before HDF5 sees them. The file is created with `kSealBytes` reserved at its start
// (HDF5's user block, which HDF5 never reads or writes); after the writer closes it, seal() writes there
//   "rift-seal fnv1a64 <16 hex digits> bytes <n>\n"
// for the FNV-1a 64 and the length of everything after the block, then zeros. The seal is written to
// the temp file before the atomic rename, so a file at its final name is sealed or absent.
#include <cstddef>
#include <filesystem>
#include <string>

namespace rift {

inline constexpr size_t kSealBytes = 512;  // HDF5's smallest user block

// Writes the seal of `file`, whose first kSealBytes are reserved. Throws rift::Error naming the file.
void seal_file(const std::filesystem::path& file);

// Throws rift::Error starting with `damaged` (e.g. "checkpoint <file> is damaged: ") when `file` has no
// seal or its bytes after the block do not match it (changed, cut short or grown).
void check_file_seal(const std::filesystem::path& file, const std::string& damaged);

}  // namespace rift
