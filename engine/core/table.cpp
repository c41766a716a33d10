#include "engine/core/table.hpp"

#include <atomic>
#include <cstring>

namespace rift {

size_t element_size(ElementType type) {
  switch (type) {
    case ElementType::f64:
      return 8;
    case ElementType::f32:
      return 4;
    case ElementType::i64:
      return 8;
    case ElementType::i32:
      return 4;
    case ElementType::u32:
      return 4;
    case ElementType::u8:
      return 1;
  }
  return 0;
}

const char* element_type_name(ElementType type) {
  switch (type) {
    case ElementType::f64:
      return "f64";
    case ElementType::f32:
      return "f32";
    case ElementType::i64:
      return "i64";
    case ElementType::i32:
      return "i32";
    case ElementType::u32:
      return "u32";
    case ElementType::u8:
      return "u8";
  }
  return "?";
}

std::optional<ElementType> element_type_from_name(std::string_view name) {
  for (ElementType t : {ElementType::f64, ElementType::f32, ElementType::i64, ElementType::i32,
                        ElementType::u32, ElementType::u8})
    if (name == element_type_name(t)) return t;
  return std::nullopt;
}

Column& Column::indexes(IndexTarget target) {
  if (type_ != ElementType::i32 && type_ != ElementType::i64)
    throw Error("column " + key() + " holds " + element_type_name(type_) + ", which cannot index rows");
  index_target_ = std::move(target);
  return *this;
}

void Column::move_row(size_t from, size_t to) {
  const size_t row_bytes = components_ * element_size(type_);
  std::memcpy(buffer_.data() + to * row_bytes, buffer_.data() + from * row_bytes, row_bytes);
}

void Column::swap_values(Column& other) {
  if (other.type_ != type_ || other.components_ != components_ || other.rows_ != rows_)
    throw Error("column " + key() + " (" + std::to_string(rows_) + " x " + std::to_string(components_) + " " +
                element_type_name(type_) + ") cannot swap values with " + other.key() + " (" +
                std::to_string(other.rows_) + " x " + std::to_string(other.components_) + " " +
                element_type_name(other.type_) + ")");
  buffer_.swap(other.buffer_);
}

Column& Table::add_column(std::string name, ElementType type, int components) {
  if (find(name)) throw Error("table " + name_ + " already has a column " + name);
  if (components < 1) throw Error("column " + name_ + "." + name + " needs at least one component");
  columns_.push_back(std::make_unique<Column>(name_, std::move(name), type, components));
  columns_.back()->resize(rows_);
  return *columns_.back();
}

Column* Table::find(std::string_view name) const {
  for (const auto& c : columns_)
    if (c->name() == name) return c.get();
  return nullptr;
}

namespace {
std::atomic<ColumnLookupObserver*> lookup_observer{nullptr};
}  // namespace

void set_column_lookup_observer(ColumnLookupObserver* observer) {
  lookup_observer.store(observer);
}

Column& Table::column(std::string_view name) {
  if (Column* c = find(name)) {
    if (ColumnLookupObserver* o = lookup_observer.load(std::memory_order_relaxed)) o->looked_up(*c);
    return *c;
  }
  throw Error("table " + name_ + " has no column " + std::string(name));
}
const Column& Table::column(std::string_view name) const {
  return const_cast<Table*>(this)->column(name);
}

void Table::resize(size_t rows) {
  rows_ = rows;
  for (auto& c : columns_) c->resize(rows);
}
void Table::reserve(size_t rows) {
  for (auto& c : columns_) c->reserve(rows);
}

size_t Table::swap_remove(size_t row) {
  const size_t last = rows_ - 1;
  if (row != last)
    for (auto& c : columns_) c->move_row(last, row);
  resize(last);
  return last;
}

Table& Store::add_table(std::string name) {
  if (find(name)) throw Error("store already has a table " + name);
  tables_.push_back(std::make_unique<Table>(std::move(name)));
  return *tables_.back();
}

Table* Store::find(std::string_view name) const {
  for (const auto& t : tables_)
    if (t->name() == name) return t.get();
  return nullptr;
}

Table& Store::table(std::string_view name) {
  if (Table* t = find(name)) return *t;
  throw Error("no table " + std::string(name));
}
const Table& Store::table(std::string_view name) const {
  return const_cast<Store*>(this)->table(name);
}

Column& Store::column(std::string_view key) {
  const auto dot = key.find('.');
  if (dot == std::string_view::npos) throw Error("column key '" + std::string(key) + "' is not table.column");
  return table(key.substr(0, dot)).column(key.substr(dot + 1));
}
const Column& Store::column(std::string_view key) const {
  return const_cast<Store*>(this)->column(key);
}

}  // namespace rift
