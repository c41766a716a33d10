#pragma once
// A small RAII wrapper over the HDF5 1.10 C API, covering what Rift's outputs and checkpoints need:
// groups, 1-/2-D numeric datasets in the six column element types, string datasets and string /
// double / int64 attributes. Every failure becomes a rift::Error naming the file and the object;
// HDF5's own stderr error printing is switched off (it is per thread in Debian's thread-safe build,
// so every entry point re-checks it).
//
// Shape convention: a dataset holds `rows x components` values. Columns with one component are
// stored rank-1 (`rows`) so that the HDF5 shape equals the XDMF `Dimensions` exactly; readers accept
// both ranks.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/table.hpp"

namespace rift {

struct H5DatasetInfo {
  ElementType type;
  size_t rows;
  int components;  // 1 for rank-1 datasets
};

class H5File {
 public:
  // truncate: creates the file or empties an existing one. create: creates a new file and fails when
  // anything is at the path already, a symbolic link included (O_EXCL semantics), so nothing is ever
  // written through a link: how every temporary file of an AtomicPath is opened.
  enum class Mode { read, truncate, create };

  // Datasets larger than this are chunked and deflate-compressed; smaller ones are contiguous
  // (compression overhead outweighs the gain for a few kilobytes).
  static constexpr size_t compress_above_bytes = 64 * 1024;

  // user_block (create modes only): bytes reserved at the start of the file that HDF5 leaves alone,
  // 0 or a power of two >= 512 (a checkpoint keeps its whole-file checksum there, file_seal.hpp).
  H5File(std::filesystem::path path, Mode mode, size_t user_block = 0);
  H5File(const H5File&) = delete;
  H5File& operator=(const H5File&) = delete;
  H5File(H5File&& other) noexcept;
  H5File& operator=(H5File&& other) noexcept;
  ~H5File();  // closes quietly; call close() to see close errors (e.g. disk full on flush)

  void close();
  const std::filesystem::path& path() const { return path_; }

  // Objects. Paths are absolute ("/a/b") or relative to the root ("a/b").
  bool exists(std::string_view object) const;
  bool is_group(std::string_view object) const;
  bool is_dataset(std::string_view object) const;
  void create_groups(std::string_view group);  // creates every missing level; existing is fine
  std::vector<std::string> children(std::string_view group) const;  // sorted by name

  // Numeric datasets; missing parent groups are created.
  void write(std::string_view dataset, ElementType type, const void* data, size_t rows, int components);
  template <class T>
  void write(std::string_view dataset, std::span<const T> values, int components = 1) {
    write(dataset, element_type_of<T>(), values.data(), values.size() / components, components);
  }
  H5DatasetInfo info(std::string_view dataset) const;
  // Reads into `data`, which holds rows x components values; type and shape must match the file.
  void read(std::string_view dataset, ElementType type, void* data, size_t rows, int components) const;
  template <class T>
  std::vector<T> read(std::string_view dataset) const {
    const H5DatasetInfo i = info(dataset);
    std::vector<T> out(i.rows * i.components);
    read(dataset, element_type_of<T>(), out.data(), i.rows, i.components);
    return out;
  }

  // A scalar string dataset (e.g. a whole YAML document).
  void write_string(std::string_view dataset, std::string_view text);
  std::string read_string(std::string_view dataset) const;

  // Attributes on the root ("/"), a group or a dataset; setting replaces an existing one.
  void set_string_attr(std::string_view object, std::string_view name, std::string_view value);
  void set_double_attr(std::string_view object, std::string_view name, double value);
  void set_int_attr(std::string_view object, std::string_view name, int64_t value);
  bool has_attr(std::string_view object, std::string_view name) const;
  std::string string_attr(std::string_view object, std::string_view name) const;
  double double_attr(std::string_view object, std::string_view name) const;  // ints convert
  int64_t int_attr(std::string_view object, std::string_view name) const;
  std::vector<std::string> attr_names(std::string_view object) const;  // sorted by name

 private:
  [[noreturn]] void fail(std::string_view object, std::string_view what) const;

  std::filesystem::path path_;
  int64_t id_ = -1;  // hid_t (int64_t since HDF5 1.10; checked in the .cpp)
};

// True when `path` exists and HDF5 recognises its signature (does not prove the file is intact).
bool is_hdf5_file(const std::filesystem::path& path);

}  // namespace rift
