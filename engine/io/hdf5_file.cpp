#include "engine/io/hdf5_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstring>
#include <type_traits>

#include "engine/core/error.hpp"

namespace rift {

static_assert(std::is_same_v<hid_t, int64_t>, "H5File stores hid_t as int64_t (HDF5 >= 1.10)");

namespace {

// HDF5 prints its error stack to stderr unless told not to. The setting lives on the calling
// thread's default stack in thread-safe builds, hence once per thread.
// Before the library's first use, it is also told not to clean up at exit: a file whose close failed
// (disk full) stays in its table, and closing it again from the exit handler crashed the process
// (SIGSEGV in H5F__close_cb) after the run had reported the error. The kernel closes the descriptors.
void quiet() {
  static const bool no_exit_cleanup = [] { return H5dont_atexit() >= 0; }();
  (void)no_exit_cleanup;
  thread_local bool done = false;
  if (!done) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    done = true;
  }
}

// The innermost message of HDF5's error stack (the most specific one, e.g. "unable to open file:
// name = ..., errno = 2"), then clears the stack.
std::string hdf5_detail() {
  std::string detail;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* e, void* data) -> herr_t {
        if (n == 0 && e->desc) *static_cast<std::string*>(data) = e->desc;
        return 0;
      },
      &detail);
  H5Eclear2(H5E_DEFAULT);
  // A failed write's message runs over lines (time, file, descriptor, byte counts); its reason is the
  // part "error message = '...'", e.g. 'No space left on device'.
  const std::string reason_key = "error message = '";
  if (const size_t at = detail.find(reason_key); at != std::string::npos) {
    const size_t begin = at + reason_key.size(), end = detail.find('\'', begin);
    if (end != std::string::npos) return "file write failed: " + detail.substr(begin, end - begin);
  }
  std::replace(detail.begin(), detail.end(), '\n', ' ');
  return detail;
}

[[noreturn]] void h5_fail(const std::filesystem::path& file, std::string_view object, std::string_view what) {
  std::string msg = "HDF5 file '" + file.string() + "'";
  if (!object.empty()) msg += ", object '" + std::string(object) + "'";
  msg += ": " + std::string(what);
  const std::string detail = hdf5_detail();
  if (!detail.empty()) msg += " (HDF5: " + detail + ")";
  throw Error(msg);
}

// Owns one hid_t and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(other.id_), closer_(other.closer_) { other.id_ = -1; }
  Handle& operator=(Handle&&) = delete;
  ~Handle() {
    if (id_ >= 0) closer_(id_);
  }
  operator hid_t() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer closer_;
};

hid_t memory_type(ElementType type) {
  switch (type) {
    case ElementType::f64:
      return H5T_NATIVE_DOUBLE;
    case ElementType::f32:
      return H5T_NATIVE_FLOAT;
    case ElementType::i64:
      return H5T_NATIVE_INT64;
    case ElementType::i32:
      return H5T_NATIVE_INT32;
    case ElementType::u32:
      return H5T_NATIVE_UINT32;
    case ElementType::u8:
      return H5T_NATIVE_UINT8;
  }
  return -1;
}

// Explicit little-endian file types: files are the same on every machine; on x86/ARM the
// memory-to-file conversion is a no-op, so values round-trip bit for bit.
hid_t file_type(ElementType type) {
  switch (type) {
    case ElementType::f64:
      return H5T_IEEE_F64LE;
    case ElementType::f32:
      return H5T_IEEE_F32LE;
    case ElementType::i64:
      return H5T_STD_I64LE;
    case ElementType::i32:
      return H5T_STD_I32LE;
    case ElementType::u32:
      return H5T_STD_U32LE;
    case ElementType::u8:
      return H5T_STD_U8LE;
  }
  return -1;
}

// Maps a stored HDF5 type back to an ElementType; nullopt for anything Rift does not write.
std::optional<ElementType> element_type_from(hid_t type) {
  const size_t size = H5Tget_size(type);
  const H5T_class_t cls = H5Tget_class(type);
  if (cls == H5T_FLOAT) {
    if (size == 8) return ElementType::f64;
    if (size == 4) return ElementType::f32;
  } else if (cls == H5T_INTEGER) {
    const bool is_signed = H5Tget_sign(type) == H5T_SGN_2;
    if (is_signed && size == 8) return ElementType::i64;
    if (is_signed && size == 4) return ElementType::i32;
    if (!is_signed && size == 4) return ElementType::u32;
    if (!is_signed && size == 1) return ElementType::u8;
  }
  return std::nullopt;
}

// Fixed-length, NUL-terminated UTF-8: readable by h5py/h5dump as a plain string.
hid_t make_string_type(size_t length) {
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, length + 1);
  H5Tset_strpad(type, H5T_STR_NULLTERM);
  H5Tset_cset(type, H5T_CSET_UTF8);
  return type;
}

// Reads a scalar string (fixed or variable length) through `read(mem_type, buffer)`.
template <class Read>
bool read_string_value(hid_t stored, Read read, std::string& out) {
  if (H5Tget_class(stored) != H5T_STRING) return false;
  if (H5Tis_variable_str(stored) > 0) {
    Handle mem(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(mem, H5T_VARIABLE);
    char* value = nullptr;
    if (read(hid_t(mem), static_cast<void*>(&value)) < 0) return false;
    out = value ? value : "";
    H5free_memory(value);
    return true;
  }
  const size_t size = H5Tget_size(stored);
  std::string buffer(size + 1, '\0');
  Handle mem(H5Tcopy(stored), H5Tclose);
  if (read(hid_t(mem), static_cast<void*>(buffer.data())) < 0) return false;
  out.assign(buffer.c_str(), strnlen(buffer.c_str(), size));
  return true;
}

std::string parent_of(std::string_view path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string_view::npos ? std::string() : std::string(path.substr(0, slash));
}

// Group/dataset creation properties: no modification times in object headers, so writing the same
// data twice gives byte-identical files.
Handle untimed(hid_t cls) {
  Handle plist(H5Pcreate(cls), H5Pclose);
  H5Pset_obj_track_times(plist, false);
  return plist;
}

}  // namespace

H5File::H5File(std::filesystem::path path, Mode mode, size_t user_block) : path_(std::move(path)) {
  quiet();
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  // Closing the file closes every object still open in it, so the file is complete on disk when
  // close() returns (the atomic rename relies on that).
  H5Pset_fclose_degree(fapl, H5F_CLOSE_STRONG);
#if H5_VERSION_GE(1, 10, 7)
  // Lock when the file system can, carry on when it cannot (NFS/Lustre without flock).
  H5Pset_file_locking(fapl, true, true);
#endif
  if (mode == Mode::read) {
    std::error_code ec;
    if (!std::filesystem::exists(path_, ec)) h5_fail(path_, "", "file does not exist");
    id_ = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, fapl);
    if (id_ < 0) h5_fail(path_, "", "cannot open for reading (not an HDF5 file, or truncated)");
  } else {
    const unsigned flags = mode == Mode::create ? H5F_ACC_EXCL : H5F_ACC_TRUNC;
    Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
    if (user_block > 0 && H5Pset_userblock(fcpl, user_block) < 0)
      h5_fail(path_, "", "cannot reserve a user block of " + std::to_string(user_block) + " bytes");
    id_ = H5Fcreate(path_.c_str(), flags, fcpl, fapl);
    if (id_ < 0)
      h5_fail(path_, "",
              mode == Mode::create ? "cannot create (something is at that path already)" : "cannot create");
  }
}

H5File::H5File(H5File&& other) noexcept : path_(std::move(other.path_)), id_(other.id_) {
  other.id_ = -1;
}

H5File& H5File::operator=(H5File&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0) H5Fclose(id_);
    path_ = std::move(other.path_);
    id_ = other.id_;
    other.id_ = -1;
  }
  return *this;
}

H5File::~H5File() {
  if (id_ >= 0) {
    quiet();
    H5Fclose(id_);
    H5Eclear2(H5E_DEFAULT);
  }
}

void H5File::close() {
  if (id_ < 0) return;
  quiet();
  const herr_t status = H5Fclose(id_);
  id_ = -1;
  if (status < 0) h5_fail(path_, "", "cannot close (data may not have reached the disk)");
}

void H5File::fail(std::string_view object, std::string_view what) const {
  h5_fail(path_, object, what);
}

bool H5File::exists(std::string_view object) const {
  quiet();
  if (id_ < 0) fail(object, "file is closed");
  // H5Lexists fails rather than answering "no" when an intermediate level is missing, so walk down.
  std::string prefix;
  size_t start = 0;
  while (start < object.size()) {
    size_t end = object.find('/', start);
    if (end == std::string_view::npos) end = object.size();
    if (end > start) {
      prefix += "/" + std::string(object.substr(start, end - start));
      const htri_t found = H5Lexists(id_, prefix.c_str(), H5P_DEFAULT);
      if (found < 0) fail(prefix, "cannot check existence");
      if (found == 0) return false;
    }
    start = end + 1;
  }
  return true;
}

namespace {
H5I_type_t object_kind(hid_t file, std::string_view object) {
  Handle obj(H5Oopen(file, std::string(object).c_str(), H5P_DEFAULT), H5Oclose);
  return obj.valid() ? H5Iget_type(obj) : H5I_BADID;
}
}  // namespace

bool H5File::is_group(std::string_view object) const {
  return exists(object) && object_kind(id_, object) == H5I_GROUP;
}

bool H5File::is_dataset(std::string_view object) const {
  return exists(object) && object_kind(id_, object) == H5I_DATASET;
}

void H5File::create_groups(std::string_view group) {
  quiet();
  std::string prefix;
  size_t start = 0;
  while (start < group.size()) {
    size_t end = group.find('/', start);
    if (end == std::string_view::npos) end = group.size();
    if (end > start) {
      prefix += "/" + std::string(group.substr(start, end - start));
      if (!exists(prefix)) {
        Handle gcpl = untimed(H5P_GROUP_CREATE);
        Handle g(H5Gcreate2(id_, prefix.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose);
        if (!g.valid()) fail(prefix, "cannot create group");
      } else if (!is_group(prefix)) {
        fail(prefix, "exists but is not a group");
      }
    }
    start = end + 1;
  }
}

std::vector<std::string> H5File::children(std::string_view group) const {
  quiet();
  Handle g(H5Gopen2(id_, std::string(group).c_str(), H5P_DEFAULT), H5Gclose);
  if (!g.valid()) fail(group, "cannot open group");
  std::vector<std::string> names;
  const herr_t status = H5Literate(
      g, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names);
  if (status < 0) fail(group, "cannot list group members");
  return names;
}

void H5File::write(std::string_view dataset, ElementType type, const void* data, size_t rows,
                   int components) {
  quiet();
  if (components < 1) fail(dataset, "a dataset needs at least one component");
  const std::string parent = parent_of(dataset);
  if (!parent.empty()) create_groups(parent);

  const int rank = components == 1 ? 1 : 2;
  const hsize_t dims[2] = {rows, static_cast<hsize_t>(components)};
  Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  Handle dcpl = untimed(H5P_DATASET_CREATE);
  const size_t row_bytes = components * element_size(type);
  if (rows * row_bytes > compress_above_bytes) {
    // ~256 KiB chunks: well inside HDF5's default 1 MiB chunk cache, large enough for deflate.
    // Shuffle (byte transposition) before deflate roughly doubles the gain on floating point data.
    const hsize_t chunk_rows = std::clamp<hsize_t>(256 * 1024 / row_bytes, 1, rows);
    const hsize_t chunk[2] = {chunk_rows, static_cast<hsize_t>(components)};
    H5Pset_chunk(dcpl, rank, chunk);
    H5Pset_shuffle(dcpl);
    H5Pset_deflate(dcpl, 1);
  }
  Handle ds(
      H5Dcreate2(id_, std::string(dataset).c_str(), file_type(type), space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
      H5Dclose);
  if (!ds.valid()) fail(dataset, "cannot create dataset");
  if (rows > 0 && H5Dwrite(ds, memory_type(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(dataset, "cannot write dataset");
}

H5DatasetInfo H5File::info(std::string_view dataset) const {
  quiet();
  Handle ds(H5Dopen2(id_, std::string(dataset).c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail(dataset, "cannot open dataset");
  Handle type(H5Dget_type(ds), H5Tclose);
  const auto element = element_type_from(type);
  if (!element) fail(dataset, "holds a type that is not one of f64 f32 i64 i32 u32 u8");
  H5DatasetInfo out{*element, 0, 1};
  Handle space(H5Dget_space(ds), H5Sclose);
  hsize_t dims[2] = {0, 1};
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank != 1 && rank != 2) fail(dataset, "has rank " + std::to_string(rank) + ", expected 1 or 2");
  H5Sget_simple_extent_dims(space, dims, nullptr);
  out.rows = dims[0];
  out.components = static_cast<int>(dims[1]);
  return out;
}

void H5File::read(std::string_view dataset, ElementType type, void* data, size_t rows, int components) const {
  const H5DatasetInfo stored = info(dataset);
  if (stored.type != type)
    fail(dataset,
         std::string("holds ") + element_type_name(stored.type) + ", expected " + element_type_name(type));
  if (stored.rows != rows || stored.components != components)
    fail(dataset, "has shape " + std::to_string(stored.rows) + " x " + std::to_string(stored.components) +
                      ", expected " + std::to_string(rows) + " x " + std::to_string(components));
  if (rows == 0) return;
  Handle ds(H5Dopen2(id_, std::string(dataset).c_str(), H5P_DEFAULT), H5Dclose);
  if (H5Dread(ds, memory_type(type), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(dataset, "cannot read dataset");
}

void H5File::write_string(std::string_view dataset, std::string_view text) {
  quiet();
  const std::string parent = parent_of(dataset);
  if (!parent.empty()) create_groups(parent);
  const std::string value(text);
  Handle type(make_string_type(value.size()), H5Tclose);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle dcpl = untimed(H5P_DATASET_CREATE);
  Handle ds(H5Dcreate2(id_, std::string(dataset).c_str(), type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
            H5Dclose);
  if (!ds.valid()) fail(dataset, "cannot create string dataset");
  if (H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, value.c_str()) < 0)
    fail(dataset, "cannot write string dataset");
}

std::string H5File::read_string(std::string_view dataset) const {
  quiet();
  Handle ds(H5Dopen2(id_, std::string(dataset).c_str(), H5P_DEFAULT), H5Dclose);
  if (!ds.valid()) fail(dataset, "cannot open dataset");
  Handle stored(H5Dget_type(ds), H5Tclose);
  std::string out;
  auto read = [&](hid_t mem, void* buf) { return H5Dread(ds, mem, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf); };
  if (!read_string_value(stored, read, out)) fail(dataset, "is not a readable string dataset");
  return out;
}

namespace {

// Opens `object`, removes an existing attribute `name` and creates a scalar one of `type`.
template <class Fail>
void write_attr(hid_t file, std::string_view object, std::string_view name, hid_t type, const void* value,
                Fail fail) {
  const std::string obj_path(object.empty() ? "/" : object);
  const std::string attr_name(name);
  Handle obj(H5Oopen(file, obj_path.c_str(), H5P_DEFAULT), H5Oclose);
  if (!obj.valid()) fail("cannot open object to set attribute '" + attr_name + "'");
  if (H5Aexists(obj, attr_name.c_str()) > 0 && H5Adelete(obj, attr_name.c_str()) < 0)
    fail("cannot replace attribute '" + attr_name + "'");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj, attr_name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  if (!attr.valid() || H5Awrite(attr, type, value) < 0) fail("cannot write attribute '" + attr_name + "'");
}

}  // namespace

void H5File::set_string_attr(std::string_view object, std::string_view name, std::string_view value) {
  quiet();
  const std::string v(value);
  Handle type(make_string_type(v.size()), H5Tclose);
  write_attr(id_, object, name, type, v.c_str(), [&](const std::string& what) { fail(object, what); });
}

void H5File::set_double_attr(std::string_view object, std::string_view name, double value) {
  quiet();
  write_attr(id_, object, name, H5T_NATIVE_DOUBLE, &value,
             [&](const std::string& what) { fail(object, what); });
}

void H5File::set_int_attr(std::string_view object, std::string_view name, int64_t value) {
  quiet();
  write_attr(id_, object, name, H5T_NATIVE_INT64, &value,
             [&](const std::string& what) { fail(object, what); });
}

bool H5File::has_attr(std::string_view object, std::string_view name) const {
  quiet();
  const htri_t found = H5Aexists_by_name(id_, std::string(object.empty() ? "/" : object).c_str(),
                                         std::string(name).c_str(), H5P_DEFAULT);
  if (found < 0) fail(object, "cannot look up attribute '" + std::string(name) + "'");
  return found > 0;
}

namespace {

// Opens attribute `name` of `object`; the caller checks validity.
hid_t open_attr(hid_t file, std::string_view object, std::string_view name) {
  return H5Aopen_by_name(file, std::string(object.empty() ? "/" : object).c_str(), std::string(name).c_str(),
                         H5P_DEFAULT, H5P_DEFAULT);
}

bool is_single_value(hid_t attr) {
  Handle space(H5Aget_space(attr), H5Sclose);
  return H5Sget_simple_extent_npoints(space) == 1;
}

}  // namespace

std::string H5File::string_attr(std::string_view object, std::string_view name) const {
  quiet();
  const std::string label = "attribute '" + std::string(name) + "'";
  Handle attr(open_attr(id_, object, name), H5Aclose);
  if (!attr.valid()) fail(object, "has no " + label);
  Handle stored(H5Aget_type(attr), H5Tclose);
  std::string out;
  auto read = [&](hid_t mem, void* buf) { return H5Aread(attr, mem, buf); };
  if (!is_single_value(attr) || !read_string_value(stored, read, out))
    fail(object, label + " is not a string");
  return out;
}

double H5File::double_attr(std::string_view object, std::string_view name) const {
  quiet();
  const std::string label = "attribute '" + std::string(name) + "'";
  Handle attr(open_attr(id_, object, name), H5Aclose);
  if (!attr.valid()) fail(object, "has no " + label);
  Handle stored(H5Aget_type(attr), H5Tclose);
  const H5T_class_t cls = H5Tget_class(stored);
  double value = 0;
  if ((cls != H5T_FLOAT && cls != H5T_INTEGER) || !is_single_value(attr))
    fail(object, label + " is not a number");
  if (H5Aread(attr, H5T_NATIVE_DOUBLE, &value) < 0) fail(object, "cannot read " + label);
  return value;
}

int64_t H5File::int_attr(std::string_view object, std::string_view name) const {
  quiet();
  const std::string label = "attribute '" + std::string(name) + "'";
  Handle attr(open_attr(id_, object, name), H5Aclose);
  if (!attr.valid()) fail(object, "has no " + label);
  Handle stored(H5Aget_type(attr), H5Tclose);
  int64_t value = 0;
  if (H5Tget_class(stored) != H5T_INTEGER || !is_single_value(attr))
    fail(object, label + " is not an integer");
  if (H5Aread(attr, H5T_NATIVE_INT64, &value) < 0) fail(object, "cannot read " + label);
  return value;
}

std::vector<std::string> H5File::attr_names(std::string_view object) const {
  quiet();
  Handle obj(H5Oopen(id_, std::string(object.empty() ? "/" : object).c_str(), H5P_DEFAULT), H5Oclose);
  if (!obj.valid()) fail(object, "cannot open object");
  std::vector<std::string> names;
  const herr_t status = H5Aiterate2(
      obj, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
        static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names);
  if (status < 0) fail(object, "cannot list attributes");
  return names;
}

bool is_hdf5_file(const std::filesystem::path& path) {
  quiet();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return false;
  const htri_t result = H5Fis_hdf5(path.c_str());
  H5Eclear2(H5E_DEFAULT);
  return result > 0;
}

}  // namespace rift
