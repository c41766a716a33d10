#pragma once
// Entity-component storage: one Table per entity kind (solid node, tet, joint, contact pair, ...),
// each a set of structure-of-arrays columns with dense row indices. A column holds `components`
// values per row, interleaved (x0 y0 z0 x1 y1 z1 ...), in one aligned allocation; kernels see spans.
// Columns are created at set-up; rows change only through the table (resize / swap-remove), which the
// schedule grants to topology-changing systems alone.
#include <complex>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "engine/core/aligned_buffer.hpp"
#include "engine/core/error.hpp"

namespace rift {

enum class ElementType : uint8_t { f64, f32, i64, i32, u32, u8 };

size_t element_size(ElementType type);
const char* element_type_name(ElementType type);
// Inverse of element_type_name ("f64" ...); nullopt for anything else.
std::optional<ElementType> element_type_from_name(std::string_view name);

template <class T>
constexpr ElementType element_type_of();
template <>
constexpr ElementType element_type_of<double>() {
  return ElementType::f64;
}
template <>
constexpr ElementType element_type_of<float>() {
  return ElementType::f32;
}
template <>
constexpr ElementType element_type_of<int64_t>() {
  return ElementType::i64;
}
template <>
constexpr ElementType element_type_of<int32_t>() {
  return ElementType::i32;
}
template <>
constexpr ElementType element_type_of<uint32_t>() {
  return ElementType::u32;
}
template <>
constexpr ElementType element_type_of<uint8_t>() {
  return ElementType::u8;
}

// What the values of an integer column index: rows of a table, or entries of a list fixed at set-up
// (materials, boundary conditions, mesh vertices). Restoring a checkpoint checks every value against it
// before any system reads the column: checksums prove a file intact, not that Rift wrote it.
struct IndexTarget {
  std::string table;  // rows of this table; empty for a list of `count` entries
  int64_t count = 0;  // the list's length, when `table` is empty
  bool none = false;  // -1 stands for "none"
  bool end = false;   // one past the last index is allowed (the end of a range)

  static IndexTarget rows_of(std::string table) { return {std::move(table), 0, false, false}; }
  static IndexTarget list_of(size_t count) { return {"", static_cast<int64_t>(count), false, false}; }
  IndexTarget or_none() && {
    none = true;
    return std::move(*this);
  }
  IndexTarget or_end() && {
    end = true;
    return std::move(*this);
  }
};

class Column {
 public:
  Column(std::string table, std::string name, ElementType type, int components)
      : table_(std::move(table)), name_(std::move(name)), type_(type), components_(components) {}

  const std::string& table() const { return table_; }
  const std::string& name() const { return name_; }
  std::string key() const { return table_ + "." + name_; }  // how systems name it: "solid_node.x"
  ElementType type() const { return type_; }
  int components() const { return components_; }
  size_t rows() const { return rows_; }
  size_t value_count() const { return rows_ * static_cast<size_t>(components_); }
  size_t bytes() const { return buffer_.size(); }
  std::byte* data() { return buffer_.data(); }
  const std::byte* data() const { return buffer_.data(); }

  // All values of the column, rows x components, row-major.
  template <class T>
  std::span<T> values() {
    check_type<T>();
    return {reinterpret_cast<T*>(buffer_.data()), value_count()};
  }
  template <class T>
  std::span<const T> values() const {
    check_type<T>();
    return {reinterpret_cast<const T*>(buffer_.data()), value_count()};
  }

  void resize(size_t rows) {
    rows_ = rows;
    buffer_.resize(rows * components_ * element_size(type_));
  }
  void reserve(size_t rows) { buffer_.reserve(rows * components_ * element_size(type_)); }
  // Declares what the values index (integer columns only).
  Column& indexes(IndexTarget target);
  const std::optional<IndexTarget>& index_target() const { return index_target_; }
  // Moves row `from` onto row `to` (used by swap-remove).
  void move_row(size_t from, size_t to);
  // Exchanges the values with a column of the same type, width and rows (names and index targets stay):
  // a solver that computes a step into a spare column makes it the store's without copying a value.
  void swap_values(Column& other);

 private:
  template <class T>
  void check_type() const {
    using V = std::remove_cv_t<T>;
    if (element_type_of<V>() != type_)
      throw Error("column " + key() + " holds " + element_type_name(type_) + ", accessed as " +
                  element_type_name(element_type_of<V>()));
  }

  std::string table_;
  std::string name_;
  ElementType type_;
  int components_;
  size_t rows_ = 0;
  AlignedBuffer buffer_;
  std::optional<IndexTarget> index_target_;
};

class Table {
 public:
  explicit Table(std::string name) : name_(std::move(name)) {}
  Table(const Table&) = delete;
  Table& operator=(const Table&) = delete;

  const std::string& name() const { return name_; }
  size_t size() const { return rows_; }

  // Adds a column sized to the current row count; names are unique within a table.
  Column& add_column(std::string name, ElementType type, int components = 1);
  template <class T>
  Column& add(std::string name, int components = 1) {
    return add_column(std::move(name), element_type_of<T>(), components);
  }

  bool has(std::string_view column) const { return find(column) != nullptr; }
  Column& column(std::string_view name);
  const Column& column(std::string_view name) const;
  template <class T>
  std::span<T> span(std::string_view name) {
    return column(name).values<T>();
  }
  template <class T>
  std::span<const T> span(std::string_view name) const {
    return column(name).values<T>();
  }

  std::span<const std::unique_ptr<Column>> columns() const { return columns_; }

  void resize(size_t rows);
  void reserve(size_t rows);
  // Removes row `row` by moving the last row into its place; returns the index that moved (or
  // `row` itself when it was last). Callers that keep handles update them (see HandleMap).
  size_t swap_remove(size_t row);

 private:
  Column* find(std::string_view name) const;

  std::string name_;
  size_t rows_ = 0;
  std::vector<std::unique_ptr<Column>> columns_;  // unique_ptr: column addresses survive add_column
};

// Receives every column lookup (Table::column, and so span) while it is installed: the access check
// (engine/schedule/access_check.hpp) records what a system looks up. At most one at a time, process-wide.
class ColumnLookupObserver {
 public:
  virtual ~ColumnLookupObserver() = default;
  virtual void looked_up(const Column& column) = 0;
};
void set_column_lookup_observer(ColumnLookupObserver* observer);  // nullptr: none

// All tables of a run. Table addresses are stable for the life of the store.
class Store {
 public:
  Table& add_table(std::string name);
  bool has(std::string_view table) const { return find(table) != nullptr; }
  Table& table(std::string_view name);
  const Table& table(std::string_view name) const;
  std::span<const std::unique_ptr<Table>> tables() const { return tables_; }

  // "table.column" lookup, as systems declare access.
  Column& column(std::string_view key);
  const Column& column(std::string_view key) const;

 private:
  Table* find(std::string_view name) const;
  std::vector<std::unique_ptr<Table>> tables_;
};

}  // namespace rift
