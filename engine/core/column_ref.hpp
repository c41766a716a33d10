#pragma once
// A column declared once: its table, its name, its element type and its width (values per row). A
// table's schema lists its columns as ColumnRefs (systems/solid_tables.hpp); set-up creates each column
// from its ref, and systems look it up and declare access through the same ref. A name is then spelled in
// one place, a lookup with the wrong element type does not compile, and one with the wrong width or in the
// wrong table throws at the lookup instead of reading the wrong values.
//
//   inline constexpr ColumnRef<double, 3> x{"solid_node", "x"};
//   x.create(store);                         // set-up
//   std::span<double> positions = x.in(store);
//   Access{{x.key()}, {}};                   // "solid_node.x"
//
// Width kVariableWidth: the width is the scene's (a joint's integration points), given at creation and not
// checked at lookup.
#include <span>
#include <string>

#include "engine/core/error.hpp"
#include "engine/core/table.hpp"

namespace rift {

inline constexpr int kVariableWidth = 0;

template <class T, int Width = 1>
struct ColumnRef {
  using value_type = T;
  static constexpr int width = Width;

  const char* table;
  const char* name;

  // "table.name", as systems declare access.
  std::string key() const { return std::string(table) + "." + name; }

  // Adds the column to its table (sized to the table's rows); a column has one creator, so adding it twice
  // throws (Table::add_column).
  Column& create(Table& t) const requires(Width != kVariableWidth) {
    check_table(t);
    return t.add<T>(name, Width);
  }
  Column& create(Store& s) const requires(Width != kVariableWidth) { return create(s.table(table)); }
  Column& create(Table& t, int components) const requires(Width == kVariableWidth) {
    check_table(t);
    return t.add<T>(name, components);
  }

  bool exists(const Store& s) const { return s.has(table) && s.table(table).has(name); }

  // The column itself (for what takes a Column: a solver's state, a swap of values).
  Column& column(Store& s) const { return checked(s.table(table)); }
  const Column& column(const Store& s) const { return checked(s.table(table)); }

  std::span<T> in(Table& t) const { return checked(t).template values<T>(); }
  std::span<const T> in(const Table& t) const { return checked(t).template values<T>(); }
  std::span<T> in(Store& s) const { return in(s.table(table)); }
  std::span<const T> in(const Store& s) const { return in(s.table(table)); }
  // Read-only, whatever the table's constness.
  std::span<const T> read(const Table& t) const { return in(t); }
  std::span<const T> read(const Store& s) const { return in(s); }

 private:
  void check_table(const Table& t) const {
    if (t.name() != table) throw Error("column " + key() + " looked up in table " + t.name());
  }
  template <class TableT>
  auto& checked(TableT& t) const {
    check_table(t);
    auto& column = t.column(name);
    if (Width != kVariableWidth && column.components() != Width)
      throw Error("column " + key() + " holds " + std::to_string(column.components()) +
                  " values per row, looked up as " + std::to_string(Width));
    return column;
  }
};

}  // namespace rift
