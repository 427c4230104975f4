// Connection: the little a database backend must provide for SqlStore
// (sql_store.cpp), which holds all of the schema and the logic. SQL is written
// once, in the PostgreSQL parameter style ($1, $2, ...); the SQLite connection
// rewrites the markers to ?1, ?2, ... Every value travels as a bound parameter
// (or, for PostgreSQL bulk loads, as COPY data), never as SQL text.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "cellforge/result.h"
#include "cellforge/store/store.h"

namespace cellforge::store {

using Value = std::variant<std::monostate, std::int64_t, double, std::string>;

// One result row; columns by position.
class Row {
 public:
  virtual ~Row() = default;
  virtual bool is_null(int col) const = 0;
  virtual std::int64_t i(int col) const = 0;
  virtual double d(int col) const = 0;
  virtual std::string s(int col) const = 0;
};
using RowFn = std::function<void(const Row&)>;

// Receives the values of one row of a bulk insert, in column order. Strings must
// outlive the bulk_insert call (they are sent without a copy).
class RowWriter {
 public:
  virtual ~RowWriter() = default;
  virtual void null() = 0;
  virtual void i(std::int64_t v) = 0;
  virtual void d(double v) = 0;
  virtual void s(const std::string& v) = 0;
  void opt(std::int64_t v) { v < 0 ? null() : i(v); }
};
using FillFn = std::function<void(std::size_t row, RowWriter&)>;

class Connection {
 public:
  virtual ~Connection() = default;
  virtual std::string backend() const = 0;
  // A second connection to the same database (for reading in parallel).
  virtual Result<std::unique_ptr<Connection>> open_another() const = 0;
  // The column type of an auto-numbered primary key.
  virtual std::string serial_primary_key() const = 0;
  // The column type of a double that must come back bit for bit (SQLite: none,
  // because a column of REAL affinity stores an integral double as an integer and
  // so loses the sign of -0.0; PostgreSQL: DOUBLE PRECISION).
  virtual std::string double_type() const = 0;
  // What ends CREATE TABLE for a table clustered on its primary key (SQLite:
  // WITHOUT ROWID, so rows live in key order in one B-tree; PostgreSQL: nothing).
  virtual std::string clustered() const = 0;
  // The DDL of the spatial index tables face_tiles and volume_boxes
  // (docs/database.md): SQLite R*Tree virtual tables; PostgreSQL tables with a
  // GiST index on a cube (the cube extension).
  virtual std::vector<std::string> spatial_schema() const = 0;
  // The DDL, run after the tables, that lets user SQL read them (PostgreSQL: the
  // role cellforge_reader and its grants).
  virtual std::vector<std::string> reader_schema() const { return {}; }
  // An indexed test that the spatial index row `alias` (face_tiles or
  // volume_boxes) meets the box in parameters $p ... $p+5 (min x y z, max x y z).
  // SQLite's R*Tree holds 32-bit floats rounded outwards, so the test may keep a
  // little more than the exact one, which the caller adds.
  virtual std::string overlaps(const std::string& alias, int p) const = 0;
  // A FROM clause joining each row `t` of face_tiles to the rows `f` of its faces,
  // written so that the planner reads the tiles first.
  virtual std::string tiles_then_faces() const = 0;
  // Called in a read transaction before selects that join with key sets: plans
  // that do not trust row estimates (PostgreSQL's statistics lag behind a bulk
  // save, and a nested loop planned for one row would be quadratic).
  virtual Status before_key_set_reads() { return Status::Ok(); }
  // A subquery giving the integers of a key-set parameter (key_set below) as
  // one column: "SELECT value FROM json_each($N)" or "SELECT unnest($N::bigint[])".
  virtual std::string key_set_query(int param) const = 0;
  // The value of a key-set parameter holding `keys`.
  virtual Value key_set(const std::vector<std::uint32_t>& keys) const = 0;

  // The DDL that creates model table `table`, given the generic `create_table`
  // statement: PostgreSQL keeps the five large tables (vertices, edges, faces,
  // loops, loop_edges) as blocks of packed rows under views of the same names and
  // columns (docs/database.md, "Storage on PostgreSQL").
  virtual std::vector<std::string> table_ddl(const std::string& table,
                                             const std::string& create_table) const {
    (void)table;
    return {create_table};
  }
  // The table that holds the rows of model table `table` (what a removal deletes from).
  virtual std::string stored_in(const std::string& table) const { return table; }
  // The rows of stored volume `id` in model table `table`, the given `columns`
  // (a comma-separated list of column names) in `order_by` order (its key order).
  // With `keys` (sorted), only the rows whose column `key_column` holds one of them.
  virtual Status read_volume_rows(const std::string& table, const std::string& columns,
                                  const std::string& order_by, std::int64_t id,
                                  const std::string& key_column,
                                  const std::vector<std::uint32_t>* keys, const RowFn& fn) {
    std::string sql = "SELECT " + columns + " FROM " + table + " WHERE volume_id = $1";
    if (keys) sql += " AND " + key_column + " IN (" + key_set_query(2) + ")";
    sql += " ORDER BY " + order_by;
    if (!keys) return bulk_select(sql, {id}, fn);
    return select(sql, {id, key_set(*keys)}, fn);
  }

  // For a schema migration: the statements that fill the storage of model table
  // `table` from `rows_table`, a table of the same columns in the row layout
  // (empty when `table` is stored as rows, which the caller then copies itself).
  virtual std::vector<std::string> pack_rows(const std::string& table,
                                             const std::string& rows_table) const {
    (void)table, (void)rows_table;
    return {};
  }

  virtual Status exec(const std::string& sql, const std::vector<Value>& params = {}) = 0;
  virtual Status select(const std::string& sql, const std::vector<Value>& params,
                        const RowFn& fn) = 0;
  // A select of the store's own SQL (never user text) whose parameters are all
  // integers, for reading many rows: PostgreSQL streams it with COPY ... TO STDOUT
  // (FORMAT binary), which takes no parameters, so the integers are written into
  // the statement; SQLite runs select().
  virtual Status bulk_select(const std::string& sql, const std::vector<std::int64_t>& params,
                             const RowFn& fn) = 0;
  // A select holding user SQL (a condition): refused unless it is one statement
  // that cannot write. Inside a read transaction.
  virtual Status untrusted_select(const std::string& sql, const std::vector<Value>& params,
                                  const RowFn& fn) = 0;

  // A write transaction holding the lock for `lock_name` (SQLite: the database
  // write lock; PostgreSQL: a transaction advisory lock on the name's hash).
  virtual Status begin_write(const std::string& lock_name) = 0;
  // A read transaction: one snapshot for every select until commit().
  virtual Status begin_read() = 0;
  virtual Status commit() = 0;
  virtual void rollback() = 0;

  // Inserts `rows` rows of `columns` values into `table`, inside the current
  // transaction; `progress` (may be empty) is told the rows written so far.
  virtual Status bulk_insert(const std::string& table, int columns, std::size_t rows,
                             const FillFn& fill,
                             const std::function<void(std::uint64_t)>& progress) = 0;

  // One user query, refused unless it is read-only, run so that it can read only
  // the model tables, within options.timeout.
  virtual Result<bool> read_only_query(const std::string& sql, const QueryOptions& options,
                                       const QueryCallbacks& callbacks) = 0;
};

Result<std::unique_ptr<Connection>> open_sqlite(const std::string& path);
Result<std::unique_ptr<Connection>> open_postgresql(const std::string& url);

// A store over any connection (sql_store.cpp).
Result<std::unique_ptr<Store>> make_sql_store(std::unique_ptr<Connection> connection);

inline Error db_error(const std::string& what) { return Error{ErrorCode::kDatabase, what}; }

// The test that the box columns (min_x ... max_z) of `alias` meet the closed box
// in parameters $p ... $p+5 (min x y z, max x y z).
inline std::string box_test(const std::string& alias, int p) {
  std::string out;
  const char* axes[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    out += (k ? " AND " : "") + alias + ".max_" + axes[k] + " >= $" + std::to_string(p + k) +
           " AND " + alias + ".min_" + axes[k] + " <= $" + std::to_string(p + 3 + k);
  }
  return out;
}

}  // namespace cellforge::store
