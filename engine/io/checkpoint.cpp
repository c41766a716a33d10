#include "engine/io/checkpoint.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <set>

#include "engine/core/error.hpp"
#include "engine/core/fnv1a.hpp"
#include "engine/io/atomic_file.hpp"
#include "engine/io/file_seal.hpp"
#include "engine/io/hdf5_file.hpp"

namespace rift {
namespace {

// HDF5 link names cannot contain '/', and "." names the group itself.
void check_name(const std::string& kind, const std::string& name) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos)
    throw Error("cannot checkpoint " + kind + " '" + name +
                "': names must be non-empty, not '.', and contain no '/'");
}

std::string table_group(const std::string& table) {
  return "/tables/" + table;
}

std::string describe(ElementType type, int components) {
  return std::string(element_type_name(type)) + " x " + std::to_string(components);
}

std::string damaged(const std::filesystem::path& file) {
  return "checkpoint " + file.string() + " is damaged: ";
}

std::string bits_hex(double value) {
  return hex16(std::bit_cast<uint64_t>(value));
}

// What the metadata checksum says about one column and one table.
struct ColumnDigest {
  std::string type;
  int64_t components;
  std::string checksum;  // fnv1a64 of the column's bytes
};
struct TableDigest {
  int64_t rows;
  std::map<std::string, ColumnDigest> columns;
};

// The text meta_fnv1a64 hashes. Tables and columns come in name order (the order HDF5 lists them in,
// whatever order the store has them in), doubles as their bit patterns, every value length-prefixed.
std::string meta_text(const CheckpointMeta& meta, const std::map<std::string, TableDigest>& tables) {
  std::string text;
  auto line = [&](const std::string& key, const std::string& value) {
    text += key + " " + std::to_string(value.size()) + ":" + value + "\n";
  };
  line("format_version", std::to_string(checkpoint_format_version));
  line("rift_version", meta.rift_version);
  line("scene_hash", meta.scene_hash);
  line("step", std::to_string(meta.step));
  line("time", bits_hex(meta.time));
  line("dt", bits_hex(meta.dt));
  line("scene", meta.resolved_scene);
  for (const auto& [key, value] : meta.scalars) line("scalar " + key, bits_hex(value));
  for (const auto& [key, value] : meta.integers) line("integer " + key, std::to_string(value));
  for (const auto& [name, table] : tables) {
    line("table " + name, std::to_string(table.rows));
    for (const auto& [column, c] : table.columns)
      line("column " + name + "." + column, c.type + " " + std::to_string(c.components) + " " + c.checksum);
  }
  return text;
}

std::string meta_checksum(const CheckpointMeta& meta, const std::map<std::string, TableDigest>& tables) {
  const std::string text = meta_text(meta, tables);
  return hex16(fnv1a64(text.data(), text.size()));
}

// An open checkpoint whose metadata matched its checksum.
struct CheckedFile {
  H5File h5;
  CheckpointMeta meta;
  std::map<std::string, TableDigest> tables;
};

CheckedFile open_checked(const std::filesystem::path& file) {
  // HDF5 sees only the bytes that were written (file_seal.hpp says why).
  check_file_seal(file, damaged(file));
  H5File h5(file, H5File::Mode::read);
  if (!h5.has_attr("/", "format_version"))
    throw Error("checkpoint " + file.string() + " is not a Rift checkpoint (no format_version attribute)");
  const int64_t version = h5.int_attr("/", "format_version");
  if (version != checkpoint_format_version)
    throw Error("checkpoint " + file.string() + " has format_version " + std::to_string(version) +
                ", this build of Rift reads format_version " + std::to_string(checkpoint_format_version));

  CheckpointMeta meta;
  meta.step = h5.int_attr("/", "step");
  meta.time = h5.double_attr("/", "time");
  meta.dt = h5.double_attr("/", "dt");
  meta.scene_hash = h5.string_attr("/", "scene_hash");
  meta.rift_version = h5.string_attr("/", "rift_version");
  meta.resolved_scene = h5.read_string("/scene");
  for (const std::string& key : h5.attr_names("/scalars"))
    meta.scalars[key] = h5.double_attr("/scalars", key);
  for (const std::string& key : h5.attr_names("/integers"))
    meta.integers[key] = h5.int_attr("/integers", key);
  std::map<std::string, TableDigest> tables;
  for (const std::string& name : h5.children("/tables")) {
    const std::string group = table_group(name);
    TableDigest& t = tables[name];
    t.rows = h5.int_attr(group, "rows");
    for (const std::string& column : h5.children(group)) {
      const std::string dataset = group + "/" + column;
      t.columns[column] = {h5.string_attr(dataset, "type"), h5.int_attr(dataset, "components"),
                           h5.string_attr(dataset, "fnv1a64")};
    }
  }
  if (h5.string_attr("/", "meta_fnv1a64") != meta_checksum(meta, tables))
    throw Error(
        damaged(file) +
        "its metadata (clock, scene, scalars, integers, table and column descriptions) does not match "
        "the checksum stored with it");
  return {std::move(h5), std::move(meta), std::move(tables)};
}

void check_column(const CheckedFile& f, const std::string& table, const std::string& column, const void* data,
                  size_t bytes) {
  const std::string& stored = f.tables.at(table).columns.at(column).checksum;
  const std::string actual = hex16(fnv1a64(data, bytes));
  if (actual != stored)
    throw Error(damaged(f.h5.path()) + "the data of column '" + table + "." + column +
                "' does not match its checksum (stored " + stored + ", the data gives " + actual + ")");
}

// What read_checkpoint will do to one table, decided before anything in the store changes.
struct TablePlan {
  Table* table;
  size_t rows;
};

std::vector<TablePlan> plan_restore(const H5File& h5, Store& store) {
  const std::string file = h5.path().string();
  const std::vector<std::string> stored_tables = h5.children("/tables");
  const std::set<std::string> stored(stored_tables.begin(), stored_tables.end());
  for (const auto& t : store.tables())
    if (!stored.count(t->name()))
      throw Error("checkpoint " + file + " has no table '" + t->name() +
                  "', which this run defines (was the checkpoint written from another scene?)");

  std::vector<TablePlan> plan;
  for (const std::string& name : stored_tables) {
    if (!store.has(name))
      throw Error("checkpoint " + file + " holds table '" + name + "', which this run does not define");
    Table& table = store.table(name);
    const std::string group = table_group(name);
    const int64_t rows = h5.int_attr(group, "rows");
    if (rows < 0) throw Error("checkpoint " + file + ": table '" + name + "' has a negative row count");

    const std::vector<std::string> stored_columns = h5.children(group);
    const std::set<std::string> columns(stored_columns.begin(), stored_columns.end());
    for (const auto& c : table.columns())
      if (!columns.count(c->name()))
        throw Error("checkpoint " + file + " has no column '" + c->key() + "', which this run defines");
    for (const std::string& column : stored_columns) {
      const std::string key = name + "." + column;
      if (!table.has(column))
        throw Error("checkpoint " + file + " holds column '" + key + "', which this run does not define");
      const Column& c = table.column(column);
      const std::string dataset = group + "/" + column;
      const H5DatasetInfo info = h5.info(dataset);
      const auto declared = element_type_from_name(h5.string_attr(dataset, "type"));
      const int64_t declared_components = h5.int_attr(dataset, "components");
      if (!declared || *declared != info.type || declared_components != info.components)
        throw Error("checkpoint " + file + ": column '" + key + "' is inconsistent (attributes say " +
                    h5.string_attr(dataset, "type") + " x " + std::to_string(declared_components) +
                    ", data is " + describe(info.type, info.components) + ")");
      if (info.type != c.type() || info.components != c.components())
        throw Error("checkpoint " + file + ": column '" + key + "' is " +
                    describe(info.type, info.components) + " in the checkpoint but " +
                    describe(c.type(), c.components()) +
                    " in this run (the engine or scene changed since the checkpoint was written)");
      if (info.rows != static_cast<size_t>(rows))
        throw Error("checkpoint " + file + ": column '" + key + "' has " + std::to_string(info.rows) +
                    " rows, its table says " + std::to_string(rows));
    }
    plan.push_back({&table, static_cast<size_t>(rows)});
  }
  return plan;
}

// The range an index column's values must lie in, and how the message names it.
struct IndexRange {
  int64_t lo, hi;  // inclusive
  std::string what;
};

IndexRange index_range(const Store& store, const IndexTarget& target) {
  const int64_t count =
      target.table.empty() ? target.count : static_cast<int64_t>(store.table(target.table).size());
  std::string what = target.table.empty() ? "a list of " + std::to_string(count) + " entries"
                                          : std::to_string(count) + " rows of " + target.table;
  if (target.none) what += ", or -1 for none";
  if (target.end) what += ", or the end of a range";
  return {target.none ? -1 : 0, count - (target.end ? 0 : 1), what};
}

template <class T>
void check_index_values(const std::filesystem::path& file, const Column& column, const IndexRange& range) {
  const auto values = column.values<const T>();
  const size_t per_row = static_cast<size_t>(column.components());
  for (size_t i = 0; i < values.size(); ++i) {
    const int64_t v = static_cast<int64_t>(values[i]);
    if (v < range.lo || v > range.hi)
      throw Error("checkpoint " + file.string() + ": column '" + column.key() + "' holds " +
                  std::to_string(v) + " at row " + std::to_string(i / per_row) + ", which is no index into " +
                  range.what +
                  " (the file passes its checksums, so it was written wrong, not damaged later)");
  }
}

// After every table is restored, since a column may index a table stored after its own.
void check_index_columns(const std::filesystem::path& file, const Store& store) {
  for (const auto& table : store.tables())
    for (const auto& column : table->columns()) {
      if (!column->index_target()) continue;
      const IndexRange range = index_range(store, *column->index_target());
      if (column->type() == ElementType::i32)
        check_index_values<int32_t>(file, *column, range);
      else
        check_index_values<int64_t>(file, *column, range);
    }
}

}  // namespace

void write_checkpoint(const std::filesystem::path& file, const Store& store, const CheckpointMeta& meta) {
  AtomicPath atomic(file);
  H5File h5(atomic.temp(), H5File::Mode::create, kSealBytes);
  h5.set_int_attr("/", "format_version", checkpoint_format_version);
  h5.set_string_attr("/", "rift_version", meta.rift_version);
  h5.set_string_attr("/", "scene_hash", meta.scene_hash);
  h5.set_int_attr("/", "step", meta.step);
  h5.set_double_attr("/", "time", meta.time);
  h5.set_double_attr("/", "dt", meta.dt);
  h5.write_string("/scene", meta.resolved_scene);
  h5.create_groups("/scalars");
  for (const auto& [key, value] : meta.scalars) h5.set_double_attr("/scalars", key, value);
  h5.create_groups("/integers");
  for (const auto& [key, value] : meta.integers) h5.set_int_attr("/integers", key, value);

  h5.create_groups("/tables");
  std::map<std::string, TableDigest> tables;
  for (const auto& table : store.tables()) {
    check_name("table", table->name());
    const std::string group = table_group(table->name());
    h5.create_groups(group);
    h5.set_int_attr(group, "rows", static_cast<int64_t>(table->size()));
    TableDigest& digest = tables[table->name()];
    digest.rows = static_cast<int64_t>(table->size());
    for (const auto& column : table->columns()) {
      check_name("column of table " + table->name(), column->name());
      const std::string dataset = group + "/" + column->name();
      h5.write(dataset, column->type(), column->data(), column->rows(), column->components());
      const ColumnDigest c{element_type_name(column->type()), column->components(),
                           hex16(fnv1a64(column->data(), column->bytes()))};
      h5.set_string_attr(dataset, "type", c.type);
      h5.set_int_attr(dataset, "components", c.components);
      h5.set_string_attr(dataset, "fnv1a64", c.checksum);
      digest.columns[column->name()] = c;
    }
  }
  h5.set_string_attr("/", "meta_fnv1a64", meta_checksum(meta, tables));
  h5.close();
  seal_file(atomic.temp());
  atomic.commit();
}

CheckpointMeta verify_checkpoint(const std::filesystem::path& file) {
  const CheckedFile f = open_checked(file);
  std::vector<std::byte> buffer;
  for (const auto& [table, digest] : f.tables)
    for (const auto& [column, c] : digest.columns) {
      const std::string dataset = table_group(table) + "/" + column;
      const H5DatasetInfo info = f.h5.info(dataset);
      // The shape comes from HDF5's headers, which the checksums do not cover: it must be the one the
      // checksummed description gives before anything is allocated for it.
      if (static_cast<int64_t>(info.rows) != digest.rows || info.components != c.components ||
          element_type_name(info.type) != c.type)
        throw Error(damaged(file) + "column '" + table + "." + column + "' holds " +
                    std::to_string(info.rows) + " rows of " + describe(info.type, info.components) +
                    ", its description says " + std::to_string(digest.rows) + " rows of " + c.type + " x " +
                    std::to_string(c.components));
      buffer.resize(info.rows * info.components * element_size(info.type));
      f.h5.read(dataset, info.type, buffer.data(), info.rows, info.components);
      check_column(f, table, column, buffer.data(), buffer.size());
    }
  return f.meta;
}

CheckpointMeta read_checkpoint(const std::filesystem::path& file, Store& store) {
  const CheckedFile f = open_checked(file);
  for (const TablePlan& p : plan_restore(f.h5, store)) {
    p.table->resize(p.rows);
    for (const auto& column : p.table->columns()) {
      f.h5.read(table_group(p.table->name()) + "/" + column->name(), column->type(), column->data(), p.rows,
                column->components());
      check_column(f, p.table->name(), column->name(), column->data(), column->bytes());
    }
  }
  check_index_columns(file, store);
  return f.meta;
}

CheckpointSet::CheckpointSet(std::filesystem::path out_dir, int keep)
    : dir_(std::move(out_dir) / "checkpoints"), keep_(keep) {
  if (keep < 1)
    throw Error(
        "checkpoints: keep must be at least 1 (the newest checkpoint is what a restart reads), found " +
        std::to_string(keep));
  check_not_link();
}

namespace {

std::string checkpoint_name(int64_t step) {
  char name[48];
  std::snprintf(name, sizeof name, "ckpt_%010lld.h5", static_cast<long long>(step));
  return name;
}

// "ckpt_<step:010>.h5" as checkpoint_name writes it -> step; anything else (temp files, other zero
// padding, more digits than a step has) -> -1, so that pruning deletes only files of our own naming.
int64_t step_of(const std::string& name) {
  constexpr std::string_view prefix = "ckpt_", suffix = ".h5";
  if (name.size() < prefix.size() + 10 + suffix.size() || !name.starts_with(prefix) ||
      !name.ends_with(suffix))
    return -1;
  const char* first = name.data() + prefix.size();
  const char* last = name.data() + name.size() - suffix.size();
  if (!std::all_of(first, last, [](char c) { return c >= '0' && c <= '9'; })) return -1;
  int64_t step = -1;
  const auto [end, ec] = std::from_chars(first, last, step);
  return ec == std::errc() && end == last && checkpoint_name(step) == name ? step : -1;
}

// One of our checkpoints' temp files ("ckpt_<step:010>.h5.tmp-<pid>", exactly as AtomicPath names it)
// whose writer process is gone; any other name, our own temp files and live writers' are left alone, so
// that pruning never touches a file some other program (or a person) put there.
bool is_orphan_temp(const std::string& name) {
  const std::optional<AtomicPath::TempName> temp = AtomicPath::parse_temp_name(name);
  return temp && step_of(temp->target) >= 0 && AtomicPath::writer_is_gone(temp->pid);
}

}  // namespace

std::filesystem::path CheckpointSet::path_for(int64_t step) const {
  return dir_ / checkpoint_name(step);
}

void CheckpointSet::check_not_link() const {
  std::error_code ec;
  if (std::filesystem::symlink_status(dir_, ec).type() == std::filesystem::file_type::symlink)
    throw Error("checkpoint folder '" + dir_.string() +
                "' is a symbolic link: Rift writes and prunes checkpoints only in a folder of its own inside "
                "the output folder and does not follow links out of it; remove the link");
}

std::vector<std::pair<int64_t, std::filesystem::path>> CheckpointSet::list() const {
  check_not_link();
  std::vector<std::pair<int64_t, std::filesystem::path>> out;
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator(dir_, ec);
       !ec && it != std::filesystem::directory_iterator(); it.increment(ec)) {
    const int64_t step = step_of(it->path().filename().string());
    std::error_code type_ec;
    if (step >= 0 && it->symlink_status(type_ec).type() == std::filesystem::file_type::regular)
      out.emplace_back(step, it->path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::filesystem::path CheckpointSet::write(const Store& store, const CheckpointMeta& meta) {
  if (meta.step < 0) throw Error("checkpoint step " + std::to_string(meta.step) + " is negative");
  check_not_link();
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw Error("cannot create checkpoint directory '" + dir_.string() + "': " + ec.message());
  const std::filesystem::path file = path_for(meta.step);
  write_checkpoint(file, store, meta);
  prune();
  return file;
}

// Works on the folder through one descriptor opened with O_NOFOLLOW and deletes with unlinkat: even a
// folder swapped for a link while the run goes on cannot lead a deletion out of the output folder.
void CheckpointSet::prune() const {
  const int fd = ::open(dir_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) throw Error("cannot open checkpoint folder '" + dir_.string() + "': " + std::strerror(errno));
  DIR* folder = ::fdopendir(fd);
  if (!folder) {
    const int err = errno;
    ::close(fd);
    throw Error("cannot list checkpoint folder '" + dir_.string() + "': " + std::strerror(err));
  }
  std::vector<std::pair<int64_t, std::string>> checkpoints;
  std::vector<std::string> orphans;
  while (const dirent* entry = ::readdir(folder)) {
    const std::string name = entry->d_name;
    struct stat st {};
    if (::fstatat(fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode)) continue;
    if (const int64_t step = step_of(name); step >= 0)
      checkpoints.emplace_back(step, name);
    else if (is_orphan_temp(name))
      orphans.push_back(name);
  }
  std::sort(checkpoints.begin(), checkpoints.end());
  std::string failure;
  for (size_t i = 0; i + keep_ < checkpoints.size(); ++i)
    if (::unlinkat(fd, checkpoints[i].second.c_str(), 0) != 0 && errno != ENOENT && failure.empty())
      failure = "cannot delete old checkpoint '" + (dir_ / checkpoints[i].second).string() +
                "': " + std::strerror(errno);
  for (const std::string& name : orphans) ::unlinkat(fd, name.c_str(), 0);  // gone meanwhile is fine
  ::closedir(folder);
  if (!failure.empty()) throw Error(failure);
}

std::optional<std::filesystem::path> CheckpointSet::latest(std::vector<CheckpointProblem>* skipped) const {
  const auto all = list();
  for (auto it = all.rbegin(); it != all.rend(); ++it) {
    try {
      verify_checkpoint(it->second);
      return it->second;
    } catch (const Error& e) {
      if (skipped) skipped->push_back({it->second, e.what()});
    }
  }
  return std::nullopt;
}

}  // namespace rift
