#pragma once
// Damages a written checkpoint the way a bad disk or a stray write would: one byte of a dataset's
// stored values changed in place, everything else in the file (HDF5's own structure included) intact.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace rift::test {

// Where `dataset`'s values start in `file` and how many bytes they take; the dataset must be stored
// contiguously (Rift's checkpoints store columns below H5File::compress_above_bytes that way).
inline std::pair<uint64_t, uint64_t> dataset_bytes(const std::filesystem::path& file,
                                                   const std::string& dataset) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  const hid_t d = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  EXPECT_GE(d, 0) << dataset;
  const haddr_t offset = H5Dget_offset(d);
  const hsize_t size = H5Dget_storage_size(d);
  H5Dclose(d);
  H5Fclose(f);
  EXPECT_NE(offset, HADDR_UNDEF) << dataset << " is not stored contiguously";
  return {offset, size};
}

// A column of the checkpoint whose values are stored contiguously and are not empty, as a dataset path.
inline std::string contiguous_column(const std::filesystem::path& file) {
  std::string found;
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << file;
  H5Ovisit(
      f, H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t root, const char* name, const H5O_info_t* info, void* out) -> herr_t {
        const std::string path = std::string("/") + name;
        if (info->type != H5O_TYPE_DATASET || !path.starts_with("/tables/")) return 0;
        const hid_t d = H5Dopen2(root, name, H5P_DEFAULT);
        const bool usable = H5Dget_offset(d) != HADDR_UNDEF && H5Dget_storage_size(d) > 0;
        H5Dclose(d);
        if (!usable) return 0;
        *static_cast<std::string*>(out) = path;
        return 1;
      },
      &found);
  H5Fclose(f);
  EXPECT_FALSE(found.empty()) << "no contiguous column in " << file;
  return found;
}

// Flips the bits of byte `index` of `dataset`'s stored values.
inline void flip_dataset_byte(const std::filesystem::path& file, const std::string& dataset, uint64_t index) {
  const auto [offset, size] = dataset_bytes(file, dataset);
  ASSERT_LT(index, size) << dataset;
  std::fstream io(file, std::ios::in | std::ios::out | std::ios::binary);
  io.seekg(static_cast<std::streamoff>(offset + index));
  const char c = static_cast<char>(io.get());
  io.seekp(static_cast<std::streamoff>(offset + index));
  io.put(static_cast<char>(~c));
  ASSERT_TRUE(io.good()) << file;
}

}  // namespace rift::test
