// The SQLite backend: one read-write connection (WAL journal, so a process
// killed mid-transaction leaves the last commit intact and readers never block
// the writer) and, for user queries, a second connection opened read-only.
#include <sqlite3.h>

#include <chrono>
#include <cstring>

#include "store/connection.h"

namespace cellforge::store {

namespace {

// $N parameter markers to SQLite's ?N (our SQL has no '$' in string literals).
std::string to_sqlite(std::string sql) {
  for (std::size_t i = 0; i + 1 < sql.size(); ++i) {
    if (sql[i] == '$' && sql[i + 1] >= '0' && sql[i + 1] <= '9') sql[i] = '?';
  }
  return sql;
}

class Statement {
 public:
  Statement() = default;
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement() { sqlite3_finalize(stmt_); }
  sqlite3_stmt*& get() { return stmt_; }
  sqlite3_stmt* operator->() const { return stmt_; }
  operator sqlite3_stmt*() const { return stmt_; }  // NOLINT: a handle wrapper

 private:
  sqlite3_stmt* stmt_ = nullptr;
};

class SqliteRow final : public Row {
 public:
  explicit SqliteRow(sqlite3_stmt* s) : s_(s) {}
  bool is_null(int c) const override { return sqlite3_column_type(s_, c) == SQLITE_NULL; }
  std::int64_t i(int c) const override { return sqlite3_column_int64(s_, c); }
  double d(int c) const override { return sqlite3_column_double(s_, c); }
  std::string s(int c) const override {
    const auto* p = sqlite3_column_blob(s_, c);
    const int n = sqlite3_column_bytes(s_, c);
    return p ? std::string(static_cast<const char*>(p), static_cast<std::size_t>(n)) : "";
  }

 private:
  sqlite3_stmt* s_;
};

class SqliteWriter final : public RowWriter {
 public:
  explicit SqliteWriter(sqlite3_stmt* s) : s_(s) {}
  void null() override { sqlite3_bind_null(s_, ++col_); }
  void i(std::int64_t v) override { sqlite3_bind_int64(s_, ++col_, v); }
  void d(double v) override { sqlite3_bind_double(s_, ++col_, v); }
  void s(const std::string& v) override {
    sqlite3_bind_text(s_, ++col_, v.data(), static_cast<int>(v.size()), SQLITE_STATIC);
  }

 private:
  sqlite3_stmt* s_;
  int col_ = 0;
};

class SqliteConnection final : public Connection {
 public:
  explicit SqliteConnection(std::string path) : path_(std::move(path)) {}
  ~SqliteConnection() override {
    sqlite3_close_v2(readonly_);
    sqlite3_close_v2(db_);
  }

  Status open() {
    // NOMUTEX: a connection is used by one thread at a time.
    if (sqlite3_open_v2(path_.c_str(), &db_,
                        SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX, nullptr) !=
        SQLITE_OK) {
      return fail(db_, "cannot open " + path_);
    }
    sqlite3_busy_timeout(db_, 60000);
    // 16 kB pages for a new database (an existing one keeps its own): a 10^6-face
    // save went from 13.5-14.8 s to 12.0-12.3 s on a loaded machine (fewer pages
    // and B-tree levels to write; docs/benchmarks.md). Set before WAL mode, which
    // fixes the page size.
    if (Status s = select("PRAGMA page_size = 16384", {}, [](const Row&) {}); !s) return s;
    for (const char* pragma : {"PRAGMA journal_mode = WAL", "PRAGMA synchronous = NORMAL",
                               "PRAGMA cache_size = -65536"}) {
      if (Status s = select(pragma, {}, [](const Row&) {}); !s) return s;
    }
    return Status::Ok();
  }

  std::string backend() const override { return "sqlite"; }
  Result<std::unique_ptr<Connection>> open_another() const override { return open_sqlite(path_); }
  std::string serial_primary_key() const override { return "INTEGER PRIMARY KEY"; }

  Status exec(const std::string& sql, const std::vector<Value>& params) override {
    return select(sql, params, [](const Row&) {});
  }

  Status select(const std::string& sql, const std::vector<Value>& params,
                const RowFn& fn) override {
    Statement st;
    if (sqlite3_prepare_v2(db_, to_sqlite(sql).c_str(), -1, &st.get(), nullptr) != SQLITE_OK) {
      return fail(db_, "prepare");
    }
    return run(st, params, fn);
  }

  Status begin_write(const std::string&) override { return exec("BEGIN IMMEDIATE", {}); }
  Status begin_read() override {
    // A deferred transaction takes its snapshot at the first read.
    return exec("BEGIN", {});
  }
  Status commit() override { return exec("COMMIT", {}); }
  void rollback() override {
    if (!sqlite3_get_autocommit(db_)) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  }

  // Rows go in as multi-row INSERTs of kBatch rows, one prepared statement re-bound
  // per batch (and one for the remainder): far fewer steps through the VDBE.
  Status bulk_insert(const std::string& table, int columns, std::size_t rows, const FillFn& fill,
                     const std::function<void(std::uint64_t)>& progress) override {
    constexpr std::size_t kBatch = 64;
    Statement full, rest;
    std::size_t r = 0;
    auto batch = [&](Statement& st, std::size_t n) -> Status {
      if (!st.get() &&
          sqlite3_prepare_v2(db_, insert_sql(table, columns, n).c_str(), -1, &st.get(), nullptr) !=
              SQLITE_OK) {
        return fail(db_, "prepare " + table);
      }
      SqliteWriter w(st);
      for (std::size_t k = 0; k < n; ++k) fill(r + k, w);
      if (sqlite3_step(st) != SQLITE_DONE) return fail(db_, "insert into " + table);
      sqlite3_reset(st);
      r += n;
      return Status::Ok();
    };
    while (rows - r >= kBatch) {
      if (Status s = batch(full, kBatch); !s) return s;
      if (progress && r % 65536 == 0) progress(r);
    }
    if (r < rows) {
      if (Status s = batch(rest, rows - r); !s) return s;
    }
    if (progress) progress(rows);
    return Status::Ok();
  }

  Status bulk_select(const std::string& sql, const std::vector<std::int64_t>& params,
                     const RowFn& fn) override {
    return select(sql, std::vector<Value>(params.begin(), params.end()), fn);
  }

  Status untrusted_select(const std::string& sql, const std::vector<Value>& params,
                          const RowFn& fn) override {
    Statement st;
    const std::string text = to_sqlite(sql);
    const char* tail = nullptr;
    if (sqlite3_prepare_v2(db_, text.c_str(), static_cast<int>(text.size()), &st.get(), &tail) !=
        SQLITE_OK) {
      return fail(db_, "condition");
    }
    if (!st.get() || (tail && std::strspn(tail, " \t\r\n;") != std::strlen(tail))) {
      return db_error("the condition must be part of one SQL statement");
    }
    if (!sqlite3_stmt_readonly(st)) return db_error("the condition must not write");
    return run(st, params, fn);
  }

  std::string clustered() const override { return " WITHOUT ROWID"; }
  std::string double_type() const override { return ""; }
  std::vector<std::string> spatial_schema() const override {
    return {
        "CREATE VIRTUAL TABLE face_tiles USING rtree(id, min_x, max_x, min_y, max_y, min_z, "
        "max_z, +volume_id, +first_face, +last_face)",
        "CREATE VIRTUAL TABLE volume_boxes USING rtree(id, min_x, max_x, min_y, max_y, min_z, "
        "max_z)",
    };
  }
  // The R*Tree answers comparisons on its own columns.
  std::string overlaps(const std::string& alias, int p) const override {
    return box_test(alias, p);
  }
  std::string tiles_then_faces() const override {
    // CROSS JOIN: SQLite keeps the tiles as the outer loop.
    return "face_tiles t CROSS JOIN faces f ON f.volume_id = t.volume_id AND f.face_key BETWEEN "
           "t.first_face AND t.last_face";
  }
  std::string key_set_query(int param) const override {
    return "SELECT value FROM json_each($" + std::to_string(param) + ")";
  }
  Value key_set(const std::vector<std::uint32_t>& keys) const override {
    std::string s = "[";
    for (std::size_t k = 0; k < keys.size(); ++k) {
      if (k) s += ',';
      s += std::to_string(keys[k]);
    }
    return s + "]";
  }

  // User SQL: a second connection, opened read-only, refusing every statement
  // that could write (sqlite3_stmt_readonly) and the functions that reach
  // outside the database (fts3_tokenizer hands out a heap pointer and, with two
  // arguments, takes one; load_extension loads code), interrupted at the time
  // limit.
  Result<bool> read_only_query(const std::string& sql, const QueryOptions& options,
                               const QueryCallbacks& callbacks) override {
    if (!readonly_) {
      if (sqlite3_open_v2(path_.c_str(), &readonly_, SQLITE_OPEN_READONLY | SQLITE_OPEN_NOMUTEX,
                          nullptr) != SQLITE_OK) {
        Status s = fail(readonly_, "cannot open " + path_ + " read-only");
        sqlite3_close_v2(readonly_);
        readonly_ = nullptr;
        return s.error();
      }
      sqlite3_busy_timeout(readonly_, 60000);
      sqlite3_db_config(readonly_, SQLITE_DBCONFIG_ENABLE_FTS3_TOKENIZER, 0, nullptr);
      sqlite3_db_config(readonly_, SQLITE_DBCONFIG_ENABLE_LOAD_EXTENSION, 0, nullptr);
      sqlite3_db_config(readonly_, SQLITE_DBCONFIG_DEFENSIVE, 1, nullptr);
      sqlite3_set_authorizer(readonly_, authorize_user_sql, nullptr);
    }
    const auto deadline = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(options.timeout));
    sqlite3_progress_handler(
        readonly_, 10000,
        [](void* d) {
          return std::chrono::steady_clock::now() >
                         *static_cast<const std::chrono::steady_clock::time_point*>(d)
                     ? 1
                     : 0;
        },
        const_cast<std::chrono::steady_clock::time_point*>(&deadline));
    auto out = run_user_query(sql, options, callbacks);
    sqlite3_progress_handler(readonly_, 0, nullptr, nullptr);
    return out;
  }

  // Steps the statement and hands each row over as it comes: nothing is held.
  Result<bool> run_user_query(const std::string& sql, const QueryOptions& options,
                              const QueryCallbacks& callbacks) {
    Statement st;
    const char* tail = nullptr;
    if (sqlite3_prepare_v2(readonly_, sql.c_str(), static_cast<int>(sql.size()), &st.get(),
                           &tail) != SQLITE_OK) {
      return fail(readonly_, "query").error();
    }
    if (!st.get()) return db_error("the query is empty");
    if (tail && std::strspn(tail, " \t\r\n;") != std::strlen(tail)) {
      return db_error("only one SQL statement may be run at a time");
    }
    if (!sqlite3_stmt_readonly(st)) return db_error("only read-only statements may be run");
    const int n = sqlite3_column_count(st);
    std::vector<std::string> columns;
    for (int c = 0; c < n; ++c) columns.emplace_back(sqlite3_column_name(st, c));
    if (callbacks.columns) callbacks.columns(columns);
    QueryRow row;
    std::size_t rows = 0;
    for (;;) {
      const int rc = sqlite3_step(st);
      if (rc == SQLITE_DONE) break;
      if (rc == SQLITE_INTERRUPT) {
        return db_error("sqlite: the query ran past its time limit of " +
                        std::to_string(options.timeout) + " s and was interrupted");
      }
      if (rc != SQLITE_ROW) return fail(readonly_, "query").error();
      if (options.max_rows && rows == options.max_rows) return true;
      ++rows;
      row.values.clear();
      row.kinds.clear();
      for (int c = 0; c < n; ++c) {
        const int type = sqlite3_column_type(st, c);
        row.kinds.push_back(type == SQLITE_INTEGER ? ValueKind::kInteger
                            : type == SQLITE_FLOAT ? ValueKind::kReal
                            : type == SQLITE_BLOB  ? ValueKind::kBlob
                                                   : ValueKind::kText);
        if (type == SQLITE_NULL) {
          row.values.emplace_back();
        } else if (type == SQLITE_FLOAT) {
          char buf[32];
          std::snprintf(buf, sizeof buf, "%.17g", sqlite3_column_double(st, c));
          row.values.emplace_back(buf);
        } else if (type == SQLITE_BLOB) {
          const auto* p = static_cast<const unsigned char*>(sqlite3_column_blob(st, c));
          const auto bytes = static_cast<std::size_t>(sqlite3_column_bytes(st, c));
          static constexpr char kHex[] = "0123456789abcdef";
          std::string hex = "\\x";
          for (std::size_t k = 0; k < bytes; ++k) {
            hex += kHex[p[k] >> 4];
            hex += kHex[p[k] & 15];
          }
          row.values.emplace_back(std::move(hex));
        } else {
          const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(st, c));
          row.values.emplace_back(
              std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(st, c))));
        }
      }
      if (callbacks.row && !callbacks.row(row)) break;
    }
    return false;
  }

 private:
  // For SQLITE_FUNCTION the function's name is the second argument.
  static int authorize_user_sql(void*, int action, const char*, const char* name, const char*,
                                const char*) {
    if (action != SQLITE_FUNCTION || !name) return SQLITE_OK;
    for (const char* refused : {"fts3_tokenizer", "load_extension"}) {
      if (sqlite3_stricmp(name, refused) == 0) return SQLITE_DENY;
    }
    return SQLITE_OK;
  }

  static std::string insert_sql(const std::string& table, int columns, std::size_t rows) {
    std::string one = "(";
    for (int c = 0; c < columns; ++c) one += c ? ", ?" : "?";
    one += ")";
    std::string sql = "INSERT INTO " + table + " VALUES ";
    for (std::size_t r = 0; r < rows; ++r) sql += (r ? ", " : "") + one;
    return sql;
  }

  Status run(sqlite3_stmt* st, const std::vector<Value>& params, const RowFn& fn) {
    for (std::size_t k = 0; k < params.size(); ++k) bind(st, static_cast<int>(k + 1), params[k]);
    const SqliteRow row(st);
    for (;;) {
      const int rc = sqlite3_step(st);
      if (rc == SQLITE_DONE) return Status::Ok();
      if (rc != SQLITE_ROW) return fail(db_, "step");
      fn(row);
    }
  }

  static void bind(sqlite3_stmt* st, int k, const Value& v) {
    if (const auto* i = std::get_if<std::int64_t>(&v)) {
      sqlite3_bind_int64(st, k, *i);
    } else if (const auto* d = std::get_if<double>(&v)) {
      sqlite3_bind_double(st, k, *d);
    } else if (const auto* s = std::get_if<std::string>(&v)) {
      sqlite3_bind_text(st, k, s->data(), static_cast<int>(s->size()), SQLITE_TRANSIENT);
    } else {
      sqlite3_bind_null(st, k);
    }
  }

  static Status fail(sqlite3* db, const std::string& what) {
    return db_error("sqlite: " + what + ": " + (db ? sqlite3_errmsg(db) : "out of memory"));
  }

  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3* readonly_ = nullptr;
};

}  // namespace

Result<std::unique_ptr<Connection>> open_sqlite(const std::string& path) {
  auto c = std::make_unique<SqliteConnection>(path);
  if (Status s = c->open(); !s) return s.error();
  return std::unique_ptr<Connection>(std::move(c));
}

}  // namespace cellforge::store
