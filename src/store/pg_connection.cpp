// The PostgreSQL backend over libpq. Statements go through PQexecParams (the
// extended protocol: bound parameters, one statement per call); large results
// of the store's own reads stream through COPY (...) TO STDOUT (FORMAT binary);
// other selects are planned with their parameter values (the unnamed statement),
// so that a key set bound as an array is planned at its real size; bulk inserts use COPY ... FROM STDIN
// (FORMAT binary): integers and IEEE doubles travel as their bytes (big-endian),
// so nothing is formatted or parsed and every double comes back bit for bit.
// Writers serialize per volume name on a transaction-scoped advisory lock;
// versions are also UNIQUE.
#include <libpq-fe.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "cellforge/geom/shared_library.h"
#include "store/connection.h"

namespace cellforge::store {

namespace {

// libpq is loaded by the first PostgreSQL connection (dlopen of libpq.so.5, Debian's
// libpq5) rather than linked: linking it, and the twenty libraries it needs (GnuTLS,
// Kerberos, LDAP, ...), added 14 ms to the start of every run of cellforge on this
// machine (a small OpenSCAD file builds in about as much), for a backend that few
// runs use. The functions keep their names, as members of one table.
#define CELLFORGE_LIBPQ_FUNCTIONS(X) \
  X(PQcancel) \
  X(PQclear) \
  X(PQconnectdb) \
  X(PQconninfoFree) \
  X(PQconninfoParse) \
  X(PQerrorMessage) \
  X(PQexec) \
  X(PQexecParams) \
  X(PQfinish) \
  X(PQfname) \
  X(PQfreeCancel) \
  X(PQfreemem) \
  X(PQftype) \
  X(PQgetCancel) \
  X(PQgetCopyData) \
  X(PQgetResult) \
  X(PQgetisnull) \
  X(PQgetlength) \
  X(PQgetvalue) \
  X(PQnfields) \
  X(PQntuples) \
  X(PQputCopyData) \
  X(PQputCopyEnd) \
  X(PQresultErrorField) \
  X(PQresultErrorMessage) \
  X(PQresultStatus) \
  X(PQsendQueryParams) \
  X(PQsetClientEncoding) \
  X(PQsetNoticeProcessor) \
  X(PQsetSingleRowMode) \
  X(PQstatus)

struct Libpq {
#define CELLFORGE_LIBPQ_MEMBER(f) decltype(&::f) f = nullptr;
  CELLFORGE_LIBPQ_FUNCTIONS(CELLFORGE_LIBPQ_MEMBER)
#undef CELLFORGE_LIBPQ_MEMBER
};

// The table, loaded once; nullptr with the reason in `why` when libpq cannot be.
const Libpq* load_libpq(std::string& why) {
  static const std::pair<const Libpq*, std::string> loaded = []() -> std::pair<const Libpq*, std::string> {
    static Libpq table;
    SharedLibrary lib("libpq.so.5");
#define CELLFORGE_LIBPQ_LOAD(f) table.f = reinterpret_cast<decltype(&::f)>(lib.symbol(#f));
    CELLFORGE_LIBPQ_FUNCTIONS(CELLFORGE_LIBPQ_LOAD)
#undef CELLFORGE_LIBPQ_LOAD
    if (!lib.problems().empty()) return {nullptr, lib.problems() + " (Debian's libpq5)"};
    return {&table, ""};
  }();
  why = loaded.second;
  return loaded.first;
}

// The loaded table: every caller is past a connection's open(), which loaded it.
const Libpq& pq() {
  static std::string why;
  static const Libpq* table = load_libpq(why);
  return *table;
}

struct ResultGuard {
  PGresult* r;
  ~ResultGuard() { pq().PQclear(r); }
};

class PgRow final : public Row {
 public:
  PgRow(PGresult* r, int row) : r_(r), row_(row) {}
  bool is_null(int c) const override { return pq().PQgetisnull(r_, row_, c) != 0; }
  std::int64_t i(int c) const override {
    return std::strtoll(pq().PQgetvalue(r_, row_, c), nullptr, 10);
  }
  double d(int c) const override { return std::strtod(pq().PQgetvalue(r_, row_, c), nullptr); }
  std::string s(int c) const override {
    return std::string(pq().PQgetvalue(r_, row_, c), static_cast<std::size_t>(pq().PQgetlength(r_, row_, c)));
  }

 private:
  PGresult* r_;
  int row_;
};

// Big-endian integers of the binary COPY format.
void put_be(std::string& buf, std::uint64_t v, int bytes) {
  for (int k = bytes - 1; k >= 0; --k) buf += static_cast<char>((v >> (8 * k)) & 0xFF);
}
std::uint64_t get_be(const char* p, int bytes) {
  std::uint64_t v = 0;
  for (int k = 0; k < bytes; ++k) v = (v << 8) | static_cast<unsigned char>(p[k]);
  return v;
}

constexpr char kCopySignature[] = "PGCOPY\n\377\r\n";  // + its NUL: 11 bytes
constexpr std::size_t kCopyHeader = 11 + 4 + 4;         // signature, flags, extension length

// One row of COPY (FORMAT binary): per column a 4-byte width (the column's type:
// int2, int4, int8, float8, text); `widths` gives each column's width, 0 for text.
class BinaryCopyWriter final : public RowWriter {
 public:
  explicit BinaryCopyWriter(const std::vector<int>& widths) : widths_(widths) {
    buf.append(kCopySignature, 11);
    put_be(buf, 0, 4);
    put_be(buf, 0, 4);
  }
  std::string buf;
  void start_row() {
    col_ = 0;
    put_be(buf, widths_.size(), 2);
  }
  void null() override {
    put_be(buf, 0xFFFFFFFFu, 4);
    ++col_;
  }
  void i(std::int64_t v) override {
    const int w = col_ < widths_.size() ? widths_[col_] : 8;
    put_be(buf, static_cast<std::uint64_t>(w), 4);
    put_be(buf, static_cast<std::uint64_t>(v), w);
    ++col_;
  }
  void d(double v) override {
    put_be(buf, 8, 4);
    put_be(buf, std::bit_cast<std::uint64_t>(v), 8);
    ++col_;
  }
  void s(const std::string& v) override {
    put_be(buf, v.size(), 4);
    buf += v;
    ++col_;
  }

 private:
  const std::vector<int>& widths_;
  std::size_t col_ = 0;
};

// One row of COPY (FORMAT binary) output, fields by position.
class BinaryRow final : public Row {
 public:
  bool parse(const char* p, std::size_t n) {
    fields_.clear();
    if (n < 2) return false;
    const auto count = static_cast<std::int16_t>(get_be(p, 2));
    std::size_t at = 2;
    for (int c = 0; c < count; ++c) {
      if (at + 4 > n) return false;
      const auto len = static_cast<std::int32_t>(get_be(p + at, 4));
      at += 4;
      if (len > 0 && at + static_cast<std::size_t>(len) > n) return false;
      fields_.push_back({p + at, len});
      if (len > 0) at += static_cast<std::size_t>(len);
    }
    return at == n;
  }
  bool is_null(int c) const override { return fields_[c].len < 0; }
  const char* bytes(int c) const { return fields_[c].p; }
  std::int32_t length(int c) const { return fields_[c].len; }
  std::int64_t i(int c) const override {
    const Span& f = fields_[c];
    if (f.len == 2) return static_cast<std::int16_t>(get_be(f.p, 2));
    if (f.len == 4) return static_cast<std::int32_t>(get_be(f.p, 4));
    return f.len == 8 ? static_cast<std::int64_t>(get_be(f.p, 8)) : 0;
  }
  double d(int c) const override {
    const Span& f = fields_[c];
    if (f.len == 8) return std::bit_cast<double>(get_be(f.p, 8));
    if (f.len == 4) return std::bit_cast<float>(static_cast<std::uint32_t>(get_be(f.p, 4)));
    return 0;
  }
  std::string s(int c) const override {
    const Span& f = fields_[c];
    return f.len > 0 ? std::string(f.p, static_cast<std::size_t>(f.len)) : std::string();
  }

 private:
  struct Span {
    const char* p;
    std::int32_t len;
  };
  std::vector<Span> fields_;
};

// The five large model tables are kept as blocks: one row of `<name>_blocks`
// (volume_id, block, data) holds up to `per_block` consecutive rows of the table
// (block b holds rows b * per_block ...), packed in `data` as fixed-size records of
// big-endian int4 and float8 fields. A view with the table's name and columns
// unpacks them for SQL (docs/database.md, "Storage on PostgreSQL"). Each saved
// volume then costs the server one heap row and one B-tree entry per ~7.5 kB
// instead of per entity.
enum class Field : char {
  kKey,      // the table's dense key: not stored, block * per_block + index in the block
  kInt,      // int4
  kOptInt,   // int4, -1 for NULL (keys are below 2^31)
  kDouble,   // float8
  kOne,      // the constant 1 (edges.edge_type): not stored
  kLoopKind  // 'outer' when the column ord is 0, else 'inner' (loops.kind): not stored
};

struct PackedColumn {
  const char* name;
  Field field;
  int offset = -1;  // in the record; -1 when not stored
};

struct PackedTable {
  const char* name;                   // the view
  const char* blocks;                 // the table of blocks
  std::vector<PackedColumn> columns;  // after volume_id, in the table's column order
  int record = 0;                     // bytes per row
  int per_block = 0;                  // rows per block
  int ord_offset = -1;                // of column ord (kLoopKind)
};

constexpr int kBlockBytes = 7680;  // a block and its row header fit a page uncompressed

const std::vector<PackedTable>& packed_tables() {
  static const std::vector<PackedTable> tables = [] {
    using F = Field;
    std::vector<PackedTable> t = {
        {"vertices",
         "vertex_blocks",
         {{"vertex_key", F::kKey},
          {"x", F::kDouble},
          {"y", F::kDouble},
          {"z", F::kDouble},
          {"group_key", F::kInt}}},
        {"edges",
         "edge_blocks",
         {{"edge_key", F::kKey},
          {"start_vertex", F::kInt},
          {"end_vertex", F::kInt},
          {"edge_type", F::kOne},
          {"uses", F::kInt}}},
        {"faces",
         "face_blocks",
         {{"face_key", F::kKey},
          {"group_key", F::kInt},
          {"front_cell", F::kOptInt},
          {"back_cell", F::kOptInt},
          {"surface_key", F::kOptInt},
          {"nx", F::kDouble},
          {"ny", F::kDouble},
          {"nz", F::kDouble},
          {"d", F::kDouble},
          {"min_x", F::kDouble},
          {"min_y", F::kDouble},
          {"min_z", F::kDouble},
          {"max_x", F::kDouble},
          {"max_y", F::kDouble},
          {"max_z", F::kDouble}}},
        {"loops",
         "loop_blocks",
         {{"loop_key", F::kKey},
          {"face_key", F::kInt},
          {"ord", F::kInt},
          {"kind", F::kLoopKind},
          {"point_vertex", F::kOptInt}}},
        {"loop_edges",
         "loop_edge_blocks",
         {{"loop_key", F::kInt},
          {"ord", F::kInt},
          {"edge_key", F::kInt},
          {"reversed", F::kInt},
          {"radial_ord", F::kInt}}},
    };
    for (PackedTable& p : t) {
      for (PackedColumn& c : p.columns) {
        if (c.field == F::kInt || c.field == F::kOptInt || c.field == F::kDouble) {
          c.offset = p.record;
          p.record += c.field == F::kDouble ? 8 : 4;
        }
        if (std::strcmp(c.name, "ord") == 0) p.ord_offset = c.offset;
      }
      p.per_block = kBlockBytes / p.record;
    }
    return t;
  }();
  return tables;
}

const PackedTable* find_packed(const std::string& table) {
  for (const PackedTable& p : packed_tables()) {
    if (table == p.name) return &p;
  }
  return nullptr;
}

void append_be32(std::string& buf, std::uint32_t v) {
  v = __builtin_bswap32(v);
  buf.append(reinterpret_cast<const char*>(&v), 4);
}
void append_be64(std::string& buf, std::uint64_t v) {
  v = __builtin_bswap64(v);
  buf.append(reinterpret_cast<const char*>(&v), 8);
}
std::uint32_t load_be32(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);
  return __builtin_bswap32(v);
}
std::uint64_t load_be64(const char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return __builtin_bswap64(v);
}

// Packs the values of one row of a packed table (volume_id first, then its
// columns in table order) into the record of the current block.
class PackedWriter final : public RowWriter {
 public:
  explicit PackedWriter(const PackedTable& t) : t_(t) {}
  std::string data;  // the records of the current block
  std::int64_t volume_id = 0;
  bool wrong = false;  // a value of the wrong kind for its column
  void start_row() { col_ = 0; }
  void null() override {
    if (const PackedColumn* c = next(); c && c->field == Field::kOptInt) {
      append_be32(data, 0xFFFFFFFFu);
    } else if (c) {
      wrong = true;
    }
  }
  void i(std::int64_t v) override {
    if (col_ == 0) {
      volume_id = v;
      ++col_;
      return;
    }
    const PackedColumn* c = next();
    if (!c) return;
    if (c->field == Field::kInt || c->field == Field::kOptInt) {
      wrong = wrong || v < -1 || v > 0x7FFFFFFF || (c->field == Field::kInt && v < 0);
      append_be32(data, static_cast<std::uint32_t>(v));
    } else if (c->field == Field::kOne) {
      wrong = wrong || v != 1;
    } else if (c->field != Field::kKey) {
      wrong = true;
    }
  }
  void d(double v) override {
    const PackedColumn* c = next();
    if (c && c->field == Field::kDouble) {
      append_be64(data, std::bit_cast<std::uint64_t>(v));
    } else if (c) {
      wrong = true;
    }
  }
  void s(const std::string&) override {
    const PackedColumn* c = next();
    if (c && c->field != Field::kLoopKind) wrong = true;
  }

 private:
  const PackedColumn* next() {
    if (col_ == 0 || col_ > t_.columns.size()) {
      wrong = true;
      ++col_;
      return nullptr;
    }
    return &t_.columns[col_++ - 1];
  }
  const PackedTable& t_;
  std::size_t col_ = 0;
};

// One row of a packed table read from its block: the columns a read asked for.
class PackedRow final : public Row {
 public:
  PackedRow(const PackedTable& t, const std::vector<int>& columns) : t_(t), columns_(columns) {}
  void at(std::int64_t volume_id, std::int64_t block, int index, const char* record) {
    volume_id_ = volume_id, block_ = block, index_ = index, rec_ = record;
  }
  bool is_null(int c) const override {
    const PackedColumn* col = column(c);
    return col && col->field == Field::kOptInt && load_be32(rec_ + col->offset) == 0xFFFFFFFFu;
  }
  std::int64_t i(int c) const override {
    const PackedColumn* col = column(c);
    return col ? value(*col) : volume_id_;
  }
  // The integer value of column k of the table (after volume_id).
  std::int64_t value(int k) const { return value(t_.columns[static_cast<std::size_t>(k)]); }
  std::int64_t value(const PackedColumn& c) const {
    const PackedColumn* col = &c;
    switch (col->field) {
      case Field::kKey:
        return block_ * t_.per_block + index_;
      case Field::kInt:
      case Field::kOptInt:
        return static_cast<std::int32_t>(load_be32(rec_ + col->offset));
      case Field::kOne:
        return 1;
      case Field::kLoopKind:
      case Field::kDouble:
        break;
    }
    return 0;
  }
  double d(int c) const override {
    const PackedColumn* col = column(c);
    if (col && col->field == Field::kDouble) {
      return std::bit_cast<double>(load_be64(rec_ + col->offset));
    }
    return static_cast<double>(i(c));
  }
  std::string s(int c) const override {
    const PackedColumn* col = column(c);
    if (col && col->field == Field::kLoopKind) {
      return load_be32(rec_ + t_.ord_offset) == 0 ? "outer" : "inner";
    }
    return std::to_string(i(c));
  }

 private:
  // nullptr for volume_id.
  const PackedColumn* column(int c) const {
    const int k = columns_[static_cast<std::size_t>(c)];
    return k < 0 ? nullptr : &t_.columns[static_cast<std::size_t>(k)];
  }
  const PackedTable& t_;
  const std::vector<int>& columns_;
  std::int64_t volume_id_ = 0, block_ = 0;
  int index_ = 0;
  const char* rec_ = nullptr;
};

// The view that unpacks a packed table, and the functions it decodes with.
std::vector<std::string> packed_ddl(const PackedTable& t) {
  const std::string rec = std::to_string(t.record);
  std::string view = std::string("CREATE VIEW ") + t.name + " AS\nSELECT b.volume_id";
  auto at = [&](int offset) { return "b.data, k * " + rec + " + " + std::to_string(offset); };
  for (const PackedColumn& c : t.columns) {
    std::string e;
    switch (c.field) {
      case Field::kKey:
        e = "b.block * " + std::to_string(t.per_block) + " + k";
        break;
      case Field::kInt:
        e = "cellforge_i4(" + at(c.offset) + ")";
        break;
      case Field::kOptInt:
        e = "NULLIF(cellforge_i4(" + at(c.offset) + "), -1)";
        break;
      case Field::kDouble:
        e = "cellforge_f8(" + at(c.offset) + ")";
        break;
      case Field::kOne:
        e = "1";
        break;
      case Field::kLoopKind:
        e = "CASE cellforge_i4(" + at(t.ord_offset) + ") WHEN 0 THEN 'outer' ELSE 'inner' END";
        break;
    }
    view += ",\n  " + e + " AS " + c.name;
  }
  const std::string select = view.substr(view.find("SELECT"));
  view += std::string("\nFROM ") + t.blocks +
          " b CROSS JOIN LATERAL generate_series(0, length(b.data) / " + rec + " - 1) AS k";
  std::vector<std::string> range;
  if (t.columns.front().field == Field::kKey) {
    // <kind>_range(volume_id, first, last): the rows of keys first ... last of one
    // volume, read from the blocks that hold them (an indexed scan; the view
    // itself would unpack every block of the volume to find them). SQL, so the
    // planner inlines it into a query.
    const std::string per = std::to_string(t.per_block);
    const std::string name = std::string(t.blocks, std::strlen(t.blocks) - 7) + "_range";
    range.push_back("CREATE OR REPLACE FUNCTION " + name +
                    "(bigint, integer, integer) RETURNS SETOF " + t.name +
                    "\nLANGUAGE sql STABLE PARALLEL SAFE AS $$\n" + select + "\nFROM " + t.blocks +
                    " b CROSS JOIN LATERAL generate_series(greatest($2 - b.block * " + per +
                    ", 0), least($3 - b.block * " + per + ", length(b.data) / " + rec +
                    " - 1)) AS k\nWHERE b.volume_id = $1 AND b.block BETWEEN $2 / " + per +
                    " AND $3 / " + per + " $$");
  }
  std::vector<std::string> out = {
      std::string("CREATE TABLE ") + t.blocks +
          " (\n  volume_id BIGINT NOT NULL,\n  block INTEGER NOT NULL,\n  data BYTEA NOT NULL,\n"
          "  PRIMARY KEY (volume_id, block))",
      // Blocks stay in their heap row, uncompressed (a page holds one).
      std::string("ALTER TABLE ") + t.blocks + " ALTER COLUMN data SET STORAGE PLAIN",
      view,
  };
  for (std::string& r : range) out.push_back(std::move(r));
  return out;
}

// The decoding functions of the views: big-endian int4 and float8 at a byte
// offset of a bytea. PostgreSQL has no cast from 8 bytes to float8, so the
// double is rebuilt from its bits exactly: sign * significand * 2^exponent, each
// factor and the product exact (-0, subnormals and infinities included; NaN is
// PostgreSQL's one NaN).
const std::vector<std::string>& packed_functions() {
  static const std::vector<std::string> f = {
      R"(CREATE OR REPLACE FUNCTION cellforge_i4(b bytea, o integer) RETURNS integer
LANGUAGE sql IMMUTABLE STRICT PARALLEL SAFE AS
$$ SELECT (get_byte(b, o) << 24) | (get_byte(b, o + 1) << 16) | (get_byte(b, o + 2) << 8)
          | get_byte(b, o + 3) $$)",
      // One SQL expression, not STRICT (a CASE is not strict), so that the
      // planner inlines it: twice as fast as the same in PL/pgSQL.
      R"(CREATE OR REPLACE FUNCTION cellforge_f8(b bytea, o integer) RETURNS double precision
LANGUAGE sql IMMUTABLE PARALLEL SAFE AS $$
SELECT CASE WHEN (((get_byte(b, o) & 127) << 4) | (get_byte(b, o + 1) >> 4)) = 2047 THEN
  CASE WHEN (('x' || encode(substring(b FROM o + 2 FOR 7), 'hex'))::bit(56)::bigint
             & 4503599627370495) <> 0 THEN 'NaN'::float8
       WHEN get_byte(b, o) >= 128 THEN '-Infinity'::float8 ELSE 'Infinity'::float8 END
ELSE (CASE WHEN get_byte(b, o) >= 128 THEN -1.0::float8 ELSE 1.0::float8 END)
  * ((('x' || encode(substring(b FROM o + 2 FOR 7), 'hex'))::bit(56)::bigint & 4503599627370495)
     | (CASE WHEN (((get_byte(b, o) & 127) << 4) | (get_byte(b, o + 1) >> 4)) = 0 THEN 0
             ELSE 4503599627370496 END))::float8
  * (2.0::float8 ^ (greatest(((get_byte(b, o) & 127) << 4) | (get_byte(b, o + 1) >> 4), 1) - 1075))
END $$)",
  };
  return f;
}

std::string param_text(const Value& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&v)) {
    char tmp[32];
    std::snprintf(tmp, sizeof tmp, "%.17g", *d);
    return tmp;
  }
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  return {};  // NULL: sent as a null pointer
}

class PgConnection final : public Connection {
 public:
  ~PgConnection() override {
    if (conn_ != nullptr) pq().PQfinish(conn_);
  }

  Status open(const std::string& url) {
    url_ = url;
    if (std::string why; load_libpq(why) == nullptr) return db_error("postgresql: " + why);
    conn_ = pq().PQconnectdb(url.c_str());
    if (!conn_ || pq().PQstatus(conn_) != CONNECTION_OK) return fail("cannot connect");
    pq().PQsetNoticeProcessor(
        conn_, [](void*, const char*) {}, nullptr);
    if (pq().PQsetClientEncoding(conn_, "UTF8") != 0) return fail("client encoding");
    // The cube type and its operators live where the extension was created.
    if (Status s = exec("SELECT set_config('search_path', current_setting('search_path') || "
                        "', public', false)",
                        {});
        !s) {
      return s;
    }
    return exec("SET extra_float_digits = 1", {});  // shortest exact text for doubles
  }

  std::string backend() const override { return "postgresql"; }
  Result<std::unique_ptr<Connection>> open_another() const override {
    return open_postgresql(url_);
  }
  std::string serial_primary_key() const override {
    return "BIGINT GENERATED BY DEFAULT AS IDENTITY PRIMARY KEY";
  }

  Status exec(const std::string& sql, const std::vector<Value>& params) override {
    ResultGuard r{run(sql, params)};
    return check(r.r, sql);
  }

  Status select(const std::string& sql, const std::vector<Value>& params,
                const RowFn& fn) override {
    ResultGuard r{run(sql, params)};
    if (Status s = check(r.r, sql); !s) return s;
    for (int k = 0, n = pq().PQntuples(r.r); k < n; ++k) fn(PgRow(r.r, k));
    return Status::Ok();
  }

  Status begin_write(const std::string& lock_name) override {
    if (Status s = begin("BEGIN"); !s) return s;
    Status s = exec("SELECT pg_advisory_xact_lock(hashtext($1))", {lock_name});
    if (!s) rollback();
    return s;
  }
  Status begin_read() override {
    if (Status s = begin("BEGIN ISOLATION LEVEL REPEATABLE READ READ ONLY"); !s) return s;
    read_only_ = true;
    return Status::Ok();
  }
  Status commit() override {
    in_transaction_ = read_only_ = false;
    return exec("COMMIT", {});
  }
  void rollback() override {
    in_transaction_ = read_only_ = false;
    pq().PQclear(pq().PQexec(conn_, "ROLLBACK"));
  }

  Status bulk_insert(const std::string& table, int, std::size_t rows, const FillFn& fill,
                     const std::function<void(std::uint64_t)>& progress) override {
    if (rows == 0) return Status::Ok();
    if (const PackedTable* t = find_packed(table)) return insert_blocks(*t, rows, fill, progress);
    auto widths = column_widths(table);
    if (!widths) return widths.error();
    {
      ResultGuard r{pq().PQexec(conn_, ("COPY " + table + " FROM STDIN (FORMAT binary)").c_str())};
      if (pq().PQresultStatus(r.r) != PGRES_COPY_IN) return fail("COPY " + table);
    }
    BinaryCopyWriter w(widths.value());
    constexpr std::size_t kChunk = 1 << 20;
    for (std::size_t k = 0; k < rows; ++k) {
      w.start_row();
      fill(k, w);
      if (k + 1 == rows) put_be(w.buf, 0xFFFF, 2);  // the trailer
      if (w.buf.size() >= kChunk || k + 1 == rows) {
        if (pq().PQputCopyData(conn_, w.buf.data(), static_cast<int>(w.buf.size())) != 1) {
          return fail("COPY " + table);
        }
        w.buf.clear();
        if (progress) progress(k + 1);
      }
    }
    if (pq().PQputCopyEnd(conn_, nullptr) != 1) return fail("COPY " + table);
    return copy_result("COPY " + table);
  }

  Status bulk_select(const std::string& sql, const std::vector<std::int64_t>& params,
                     const RowFn& fn) override {
    std::string text = sql;
    for (std::size_t k = params.size(); k > 0; --k) {  // $10 before $1
      const std::string marker = "$" + std::to_string(k);
      for (std::size_t at; (at = text.find(marker)) != std::string::npos;) {
        text.replace(at, marker.size(), std::to_string(params[k - 1]));
      }
    }
    return copy_out(text, [&](const BinaryRow& row) { fn(row); });
  }

  std::vector<std::string> table_ddl(const std::string& table,
                                     const std::string& create_table) const override {
    const PackedTable* t = find_packed(table);
    if (!t) return {create_table};
    std::vector<std::string> ddl = packed_functions();
    for (std::string& d : packed_ddl(*t)) ddl.push_back(std::move(d));
    return ddl;
  }
  std::string stored_in(const std::string& table) const override {
    const PackedTable* t = find_packed(table);
    return t ? t->blocks : table;
  }

  // A packed table is read by its blocks (all of the volume's, or those that can
  // hold the keys), unpacked here; rows come in key order whatever `order_by` says.
  Status read_volume_rows(const std::string& table, const std::string& columns,
                          const std::string& order_by, std::int64_t id,
                          const std::string& key_column, const std::vector<std::uint32_t>* keys,
                          const RowFn& fn) override {
    const PackedTable* t = find_packed(table);
    if (!t) {
      return Connection::read_volume_rows(table, columns, order_by, id, key_column, keys, fn);
    }
    auto index_of = [&](const std::string& name) {
      for (std::size_t k = 0; k < t->columns.size(); ++k) {
        if (name == t->columns[k].name) return static_cast<int>(k);
      }
      return name == "volume_id" ? -1 : -2;
    };
    std::vector<int> wanted;
    for (std::size_t at = 0; at <= columns.size();) {
      std::size_t end = columns.find(',', at);
      if (end == std::string::npos) end = columns.size();
      std::string name = columns.substr(at, end - at);
      name.erase(0, name.find_first_not_of(' '));
      name.erase(name.find_last_not_of(' ') + 1);
      const int k = index_of(name);
      if (k == -2) return db_error("postgresql: no column " + name + " in " + table);
      wanted.push_back(k);
      at = end + 1;
    }
    const int key = keys ? index_of(key_column) : -1;
    if (keys && key < 0) return db_error("postgresql: no column " + key_column + " in " + table);
    const bool dense = keys && t->columns[static_cast<std::size_t>(key)].field == Field::kKey;
    std::string sql = std::string("SELECT block, data FROM ") + t->blocks +
                      " WHERE volume_id = " + std::to_string(id);
    if (dense) {  // only the blocks that hold the keys
      std::string blocks;
      std::int64_t last = -1;
      for (std::uint32_t k : *keys) {
        const std::int64_t b = k / static_cast<std::uint32_t>(t->per_block);
        if (b == last) continue;
        blocks += (blocks.empty() ? "" : ",") + std::to_string(b);
        last = b;
      }
      if (blocks.empty()) return Status::Ok();
      sql += " AND block = ANY('{" + blocks + "}'::integer[])";
    }
    sql += " ORDER BY block";
    PackedRow row(*t, wanted);
    bool ok = true;
    Status s = copy_out(sql, [&](const BinaryRow& r) {
      const std::int32_t bytes = r.length(1);
      if (r.length(0) != 4 || bytes < 0 || bytes % t->record != 0) {
        ok = false;
        return;
      }
      const std::int64_t block = static_cast<std::int32_t>(load_be32(r.bytes(0)));
      const char* data = r.bytes(1);
      for (int n = bytes / t->record, k = 0; k < n; ++k) {
        row.at(id, block, k, data + static_cast<std::size_t>(k) * t->record);
        if (keys && !std::binary_search(keys->begin(), keys->end(),
                                        static_cast<std::uint32_t>(row.value(key)))) {
          continue;
        }
        fn(row);
      }
    });
    if (s && !ok) s = db_error(std::string("postgresql: a malformed block in ") + t->blocks);
    return s;
  }

  // The rows of `rows_table` (a table in the row layout of `table`, as schema 2
  // stored it) as blocks of `table`: INSERT ... SELECT, packed by the server
  // (int4send, float8send), for a schema migration.
  std::vector<std::string> pack_rows(const std::string& table,
                                     const std::string& rows_table) const override {
    const PackedTable* t = find_packed(table);
    if (!t) return {};
    std::string record, order;
    for (const PackedColumn& c : t->columns) {
      const std::string name = c.name;
      if (c.field == Field::kKey) order = name;
      if (c.field == Field::kInt)
        record += (record.empty() ? "" : " || ") + ("int4send(" + name + ")");
      if (c.field == Field::kOptInt) {
        record += (record.empty() ? "" : " || ") + ("int4send(COALESCE(" + name + ", -1))");
      }
      if (c.field == Field::kDouble)
        record += (record.empty() ? "" : " || ") + ("float8send(" + name + ")");
    }
    if (order.empty()) order = "loop_key, ord";  // loop_edges: uses in loop order
    const std::string per = std::to_string(t->per_block);
    return {std::string("INSERT INTO ") + t->blocks + " (volume_id, block, data)\n" +
            "SELECT volume_id, (n / " + per + ")::integer, string_agg(r, ''::bytea ORDER BY n)\n" +
            "FROM (SELECT volume_id, " + record +
            " AS r, row_number() OVER (PARTITION BY volume_id ORDER BY " + order +
            ") - 1 AS n FROM " + rows_table + ") s\nGROUP BY volume_id, n / " + per};
  }

  Status copy_out(const std::string& text, const std::function<void(const BinaryRow&)>& fn) {
    {
      ResultGuard r{pq().PQexec(conn_, ("COPY (" + text + ") TO STDOUT (FORMAT binary)").c_str())};
      if (pq().PQresultStatus(r.r) != PGRES_COPY_OUT) return result_error(r.r, "COPY out");
    }
    BinaryRow row;
    bool header = true, ok = true;
    for (;;) {
      char* buf = nullptr;
      const int n = pq().PQgetCopyData(conn_, &buf, 0);
      if (n < 0) break;  // -1: done; -2: error (reported by the result below)
      const char* p = buf;
      std::size_t len = static_cast<std::size_t>(n);
      if (header) {
        ok = ok && len >= kCopyHeader && std::memcmp(p, kCopySignature, 11) == 0;
        const std::size_t ext = ok ? get_be(p + 15, 4) : 0;
        ok = ok && len >= kCopyHeader + ext;
        if (ok) p += kCopyHeader + ext, len -= kCopyHeader + ext;
        header = false;
      }
      const bool trailer = len == 2 && get_be(p, 2) == 0xFFFF;
      if (ok && len > 0 && !trailer) {
        ok = row.parse(p, len);
        if (ok) fn(row);
      }
      pq().PQfreemem(buf);
    }
    Status s = copy_result("COPY out");
    if (s && !ok) s = db_error("postgresql: COPY out: malformed binary row");
    return s;
  }

  Status untrusted_select(const std::string& sql, const std::vector<Value>& params,
                          const RowFn& fn) override {
    // PQexecParams runs one statement only, and a read transaction is READ ONLY.
    if (!in_transaction_ || !read_only_) return db_error("a condition runs only in a read");
    return select(sql, params, fn);
  }

  std::string clustered() const override { return ""; }
  std::string double_type() const override { return "DOUBLE PRECISION"; }
  std::vector<std::string> reader_schema() const override {
    // Without the right to create roles the reader is not made; user SQL then
    // fails with a message naming the role, and everything else works.
    return {R"(DO $$ BEGIN
  IF NOT EXISTS (SELECT FROM pg_roles WHERE rolname = 'cellforge_reader') THEN
    CREATE ROLE cellforge_reader LOGIN NOSUPERUSER NOCREATEDB NOCREATEROLE NOINHERIT;
  END IF;
  EXECUTE format('GRANT USAGE ON SCHEMA %I TO cellforge_reader', current_schema());
  EXECUTE format('GRANT SELECT ON ALL TABLES IN SCHEMA %I TO cellforge_reader', current_schema());
EXCEPTION WHEN insufficient_privilege THEN NULL;
END $$)"};
  }
  std::vector<std::string> spatial_schema() const override {
    auto table = [](const std::string& name, const std::string& extra) {
      return "CREATE TABLE " + name +
             " (\n  id BIGINT PRIMARY KEY,\n"
             "  min_x DOUBLE PRECISION NOT NULL, max_x DOUBLE PRECISION NOT NULL,\n"
             "  min_y DOUBLE PRECISION NOT NULL, max_y DOUBLE PRECISION NOT NULL,\n"
             "  min_z DOUBLE PRECISION NOT NULL, max_z DOUBLE PRECISION NOT NULL,\n" +
             extra +
             "  box cube GENERATED ALWAYS AS (cube(ARRAY[min_x, min_y, min_z], "
             "ARRAY[max_x, max_y, max_z])) STORED)";
    };
    return {
        "CREATE EXTENSION IF NOT EXISTS cube SCHEMA public",
        table("face_tiles",
              "  volume_id BIGINT NOT NULL, first_face INTEGER NOT NULL, "
              "last_face INTEGER NOT NULL,\n"),
        "CREATE INDEX face_tiles_box ON face_tiles USING gist (box)",
        table("volume_boxes", ""),
        "CREATE INDEX volume_boxes_box ON volume_boxes USING gist (box)",
    };
  }
  std::string overlaps(const std::string& alias, int p) const override {
    auto corner = [p](int first) {
      std::string out = "ARRAY[";
      for (int k = 0; k < 3; ++k) out += (k ? ", $" : "$") + std::to_string(p + first + k) + "::float8";
      return out + "]";
    };
    return alias + ".box && cube(" + corner(0) + ", " + corner(3) + ")";
  }
  Status before_key_set_reads() override { return exec("SET LOCAL enable_nestloop = off", {}); }
  std::string tiles_then_faces() const override {
    // face_range reads only the blocks of each tile's faces.
    return "face_tiles t CROSS JOIN LATERAL face_range(t.volume_id, t.first_face, t.last_face) f";
  }
  std::string key_set_query(int param) const override {
    return "SELECT unnest($" + std::to_string(param) + "::bigint[])";
  }
  Value key_set(const std::vector<std::uint32_t>& keys) const override {
    std::string s = "{";
    for (std::size_t k = 0; k < keys.size(); ++k) {
      if (k) s += ',';
      s += std::to_string(keys[k]);
    }
    return s + "}";
  }

  // User SQL runs on a connection of its own, logged in as the role
  // cellforge_reader (created with the schema, allowed to SELECT the model tables
  // and views and nothing else), so that nothing in the query — not SET ROLE, not
  // set_config — can take the rights of the store's role. The text is wrapped as
  // a subquery, so only a query parses (no COPY, SET or other utility command),
  // inside a READ ONLY transaction with a statement timeout, rolled back after.
  Result<bool> read_only_query(const std::string& sql, const QueryOptions& options,
                               const QueryCallbacks& callbacks) override {
    if (!reader_ || pq().PQstatus(reader_->conn_) != CONNECTION_OK) {
      auto reader = open_reader();
      if (!reader) return reader.error();
      reader_ = std::move(reader.value());
    }
    return reader_->run_user_query(sql, options, callbacks);
  }

 private:
  static constexpr const char* kReader = "cellforge_reader";

  // This connection's parameters with the user replaced by the reader role.
  Result<std::unique_ptr<PgConnection>> open_reader() const {
    char* error = nullptr;
    PQconninfoOption* options = pq().PQconninfoParse(url_.c_str(), &error);
    if (!options) {
      std::string m = error ? error : "cannot parse the connection string";
      pq().PQfreemem(error);
      return db_error("postgresql: " + m);
    }
    std::string conninfo;
    for (PQconninfoOption* o = options; o->keyword; ++o) {
      const bool user = std::strcmp(o->keyword, "user") == 0;
      if (!o->val && !user) continue;
      std::string value = user ? kReader : o->val, quoted = "'";
      for (char c : value) {
        if (c == '\\' || c == '\'') quoted += '\\';
        quoted += c;
      }
      conninfo += std::string(conninfo.empty() ? "" : " ") + o->keyword + "=" + quoted + "'";
    }
    pq().PQconninfoFree(options);
    auto c = std::make_unique<PgConnection>();
    if (Status s = c->open(conninfo); !s) {
      return db_error("user SQL runs as the role " + std::string(kReader) +
                      ", which cannot connect (docs/database.md, \"User SQL\"): " +
                      s.error().message);
    }
    return c;
  }

  // Single-row mode: each row is its own PGresult, handed over and freed before
  // the next is read, so nothing accumulates. A stop asked by the caller cancels
  // the query on the server.
  Result<bool> run_user_query(std::string sql, const QueryOptions& options,
                              const QueryCallbacks& callbacks) {
    while (!sql.empty() && (std::isspace(static_cast<unsigned char>(sql.back())) || sql.back() == ';')) {
      sql.pop_back();
    }
    if (Status s = begin("BEGIN READ ONLY"); !s) return s.error();
    const long ms = std::max(1L, static_cast<long>(options.timeout * 1000));
    Status s = exec("SET LOCAL statement_timeout = " + std::to_string(ms), {});
    if (s) s = exec("SET LOCAL bytea_output = 'hex'", {});  // blobs as \x.. on both backends
    if (!s) {
      rollback();
      return s.error();
    }
    const std::string wrapped =
        "SELECT * FROM (\n" + sql + "\n) AS cellforge_user_query" +
        (options.max_rows ? " LIMIT " + std::to_string(options.max_rows + 1) : std::string());
    if (pq().PQsendQueryParams(conn_, wrapped.c_str(), 0, nullptr, nullptr, nullptr, nullptr, 0) != 1 ||
        pq().PQsetSingleRowMode(conn_) != 1) {
      Status e = fail("query");
      drain();
      rollback();
      return e.error();
    }
    std::optional<Status> error;
    bool truncated = false, stopped = false, started = false;
    std::size_t rows = 0;
    std::vector<ValueKind> kinds;
    QueryRow row;
    while (PGresult* r = pq().PQgetResult(conn_)) {
      ResultGuard guard{r};
      const ExecStatusType st = pq().PQresultStatus(r);
      if (error || stopped || truncated) continue;  // the rest of a stopped query
      if (st != PGRES_SINGLE_TUPLE && st != PGRES_TUPLES_OK) {
        const char* state = pq().PQresultErrorField(r, PG_DIAG_SQLSTATE);
        error = state && std::strcmp(state, "57014") == 0 && !stopped
                    ? db_error("postgresql: the query ran past its time limit of " +
                               std::to_string(options.timeout) + " s and was cancelled")
                    : result_error(r, "query");
        continue;
      }
      const int n = pq().PQnfields(r);
      if (!started) {
        started = true;
        std::vector<std::string> columns;
        for (int c = 0; c < n; ++c) columns.emplace_back(pq().PQfname(r, c));
        // The kind of each column from its type (pg_type's OIDs): int2, int4,
        // int8, oid; float4, float8, numeric; bytea.
        for (int c = 0; c < n; ++c) {
          const Oid type = pq().PQftype(r, c);
          kinds.push_back(type == 20 || type == 21 || type == 23 || type == 26 ? ValueKind::kInteger
                          : type == 700 || type == 701 || type == 1700         ? ValueKind::kReal
                          : type == 17                                         ? ValueKind::kBlob
                                                                               : ValueKind::kText);
        }
        if (callbacks.columns) callbacks.columns(columns);
      }
      for (int k = 0, count = pq().PQntuples(r); k < count && !stopped && !truncated; ++k) {
        if (options.max_rows && rows == options.max_rows) {
          truncated = true;
          break;
        }
        ++rows;
        row.values.clear();
        row.kinds = kinds;
        for (int c = 0; c < n; ++c) {
          if (pq().PQgetisnull(r, k, c)) {
            row.values.emplace_back();
          } else {
            row.values.emplace_back(
                std::string(pq().PQgetvalue(r, k, c), static_cast<std::size_t>(pq().PQgetlength(r, k, c))));
          }
        }
        if (callbacks.row && !callbacks.row(row)) {
          stopped = true;
          cancel();
        }
      }
    }
    rollback();
    if (error) return error->error();
    return truncated;
  }

  // Asks the server to stop the query running on this connection.
  void cancel() {
    if (PGcancel* c = pq().PQgetCancel(conn_)) {
      char message[256];
      pq().PQcancel(c, message, sizeof message);
      pq().PQfreeCancel(c);
    }
  }

  void drain() {
    while (PGresult* r = pq().PQgetResult(conn_)) pq().PQclear(r);
  }

  Status begin(const char* sql) {
    if (Status s = exec(sql, {}); !s) return s;
    in_transaction_ = true;
    return Status::Ok();
  }

  PGresult* run(const std::string& sql, const std::vector<Value>& params) {
    std::vector<std::string> text;
    std::vector<const char*> values;
    text.reserve(params.size());
    for (const Value& v : params) text.push_back(param_text(v));
    for (std::size_t k = 0; k < params.size(); ++k) {
      values.push_back(std::holds_alternative<std::monostate>(params[k]) ? nullptr
                                                                         : text[k].c_str());
    }
    return pq().PQexecParams(conn_, sql.c_str(), static_cast<int>(params.size()), nullptr, values.data(),
                        nullptr, nullptr, 0);
  }

  Status check(PGresult* r, const std::string& what) {
    const ExecStatusType st = pq().PQresultStatus(r);
    if (st == PGRES_COMMAND_OK || st == PGRES_TUPLES_OK) return Status::Ok();
    return result_error(r, what.substr(0, what.find('\n')));
  }

  Status result_error(PGresult* r, const std::string& what) {
    const char* msg = r ? pq().PQresultErrorMessage(r) : pq().PQerrorMessage(conn_);
    std::string m = msg ? msg : "";
    while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
    return db_error("postgresql: " + what + ": " + m);
  }

  Status fail(const std::string& what) {
    std::string m = conn_ ? pq().PQerrorMessage(conn_) : "out of memory";
    while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
    return db_error("postgresql: " + what + ": " + m);
  }

  // The rows of a packed table as its blocks, by COPY (FORMAT binary): each block
  // a row (volume_id int8, block int4, data bytea) of `<name>_blocks`.
  Status insert_blocks(const PackedTable& t, std::size_t rows, const FillFn& fill,
                       const std::function<void(std::uint64_t)>& progress) {
    const std::string what = std::string("COPY ") + t.blocks;
    {
      ResultGuard r{pq().PQexec(conn_, (what + " FROM STDIN (FORMAT binary)").c_str())};
      if (pq().PQresultStatus(r.r) != PGRES_COPY_IN) return fail(what);
    }
    std::string buf(kCopySignature, 11);
    put_be(buf, 0, 4);
    put_be(buf, 0, 4);
    PackedWriter w(t);
    const auto per = static_cast<std::size_t>(t.per_block);
    w.data.reserve(per * static_cast<std::size_t>(t.record));
    constexpr std::size_t kChunk = 1 << 20;
    for (std::size_t k = 0; k < rows; ++k) {
      w.start_row();
      fill(k, w);
      if (w.wrong) {
        pq().PQputCopyEnd(conn_, "a value of the wrong kind");
        (void)copy_result(what);
        return db_error("postgresql: " + what + ": a value of the wrong kind for its column");
      }
      if ((k + 1) % per != 0 && k + 1 != rows) continue;
      put_be(buf, 3, 2);
      put_be(buf, 8, 4);
      append_be64(buf, static_cast<std::uint64_t>(w.volume_id));
      put_be(buf, 4, 4);
      append_be32(buf, static_cast<std::uint32_t>(k / per));
      append_be32(buf, static_cast<std::uint32_t>(w.data.size()));
      buf += w.data;
      w.data.clear();
      if (k + 1 == rows) put_be(buf, 0xFFFF, 2);  // the trailer
      if (buf.size() >= kChunk || k + 1 == rows) {
        if (pq().PQputCopyData(conn_, buf.data(), static_cast<int>(buf.size())) != 1) return fail(what);
        buf.clear();
        if (progress) progress(k + 1);
      }
    }
    if (pq().PQputCopyEnd(conn_, nullptr) != 1) return fail(what);
    return copy_result(what);
  }

  // Bytes per value of each column of `table` as COPY (FORMAT binary) wants them
  // (0 for text), in column order, generated columns left out.
  Result<std::vector<int>> column_widths(const std::string& table) {
    if (const auto it = widths_.find(table); it != widths_.end()) return it->second;
    std::vector<int> widths;
    Status s = select(
        "SELECT a.atttypid::int FROM pg_attribute a WHERE a.attrelid = $1::regclass "
        "AND a.attnum > 0 AND NOT a.attisdropped AND a.attgenerated = '' ORDER BY a.attnum",
        {table}, [&](const Row& r) {
          const std::int64_t type = r.i(0);
          widths.push_back(type == 21 ? 2 : type == 23 ? 4 : type == 20 || type == 701 ? 8 : 0);
        });
    if (!s) return s.error();
    return widths_[table] = widths;
  }

  Status copy_result(const std::string& what) {
    Status s = Status::Ok();
    while (PGresult* r = pq().PQgetResult(conn_)) {
      if (s && pq().PQresultStatus(r) != PGRES_COMMAND_OK) s = result_error(r, what);
      pq().PQclear(r);
    }
    return s;
  }

  std::string url_;
  PGconn* conn_ = nullptr;
  bool in_transaction_ = false, read_only_ = false;
  std::map<std::string, std::vector<int>> widths_;
  std::unique_ptr<PgConnection> reader_;  // for user SQL (read_only_query)
};

}  // namespace

Result<std::unique_ptr<Connection>> open_postgresql(const std::string& url) {
  auto c = std::make_unique<PgConnection>();
  if (Status s = c->open(url); !s) return s.error();
  return std::unique_ptr<Connection>(std::move(c));
}

}  // namespace cellforge::store
