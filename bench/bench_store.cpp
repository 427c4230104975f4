// Save and load of a 10^6-face model in the model database, on SQLite and (when
// CELLFORGE_PG_URL or --pg names one) PostgreSQL: seconds and rows per second,
// and (save + load) / (STL write + read) from the same run; a partial load (the
// faces of one tenth of the sheet, by a condition on the face boxes), spatial
// queries (faces of the volume in a box, volumes in a box) and the bytes on disk
// per face, beside the sizes of the same model as binary STL, 3MF and JSON.
//
//   bench_store [--faces N] [--dir DIR] [--pg postgresql://...] [--sizes]
//
// --sizes also writes the model as 3MF and JSON and prints their sizes.
//
// The model is a triangulated sheet with irregular coordinates (2 n^2 faces).
// Rows are every row written to or read from the tables of docs/database.md. The
// same model written and read as binary STL is timed first, for comparison.
#include <libpq-fe.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cellforge/io/mesh_io.h"
#include "cellforge/store/store.h"
#include "cellforge/topo/builder.h"
#include "store/model_rows.h"

namespace {

using cellforge::Model;

Model sheet(int n) {
  cellforge::MeshInput in;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) in.positions.push_back({i * 0.1, j * 0.1, 1e-3 * ((i ^ j) & 7)});
  }
  auto at = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      in.faces.push_back({{{at(i, j), at(i + 1, j), at(i + 1, j + 1)}}});
      in.faces.push_back({{{at(i, j), at(i + 1, j + 1), at(i, j + 1)}}});
    }
  }
  Model m;
  auto r = cellforge::build_mesh(m, in);
  if (!r) {
    std::fprintf(stderr, "build_mesh: %s\n", r.error().message.c_str());
    std::exit(1);
  }
  return m;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Runs one statement on PostgreSQL (schema set-up); false on failure.
bool pg_exec(const std::string& url, const std::string& sql) {
  PGconn* c = PQconnectdb(url.c_str());
  bool ok = PQstatus(c) == CONNECTION_OK;
  if (ok) {
    PQsetNoticeProcessor(c, [](void*, const char*) {}, nullptr);
    PGresult* r = PQexec(c, sql.c_str());
    ok = PQresultStatus(r) == PGRES_COMMAND_OK;
    if (!ok) std::fprintf(stderr, "%s: %s", sql.c_str(), PQresultErrorMessage(r));
    PQclear(r);
  }
  PQfinish(c);
  return ok;
}

double stl_seconds = 0;  // binary STL write + read, measured first

// Bytes the stored model takes: SQLite's pages, PostgreSQL's relations
// (tables, indexes and TOAST) of the model tables.
std::int64_t stored_bytes(cellforge::Store& store) {
  const std::string sql =
      store.backend() == "sqlite"
          ? "SELECT page_count * page_size FROM pragma_page_count(), pragma_page_size()"
          : "SELECT SUM(pg_total_relation_size(c.oid))::bigint FROM pg_class c "
            "JOIN pg_namespace n ON n.oid = c.relnamespace "
            "WHERE n.nspname = current_schema() AND c.relkind IN ('r', 'v', 'm') "
            "AND c.relname <> 'objects' AND c.relname <> 'object_volumes'";
  auto r = store.query(sql);
  if (!r || r->rows.empty() || !r->rows[0][0]) return -1;
  return std::stoll(*r->rows[0][0]);
}

bool run(const std::string& db, const Model& m, std::uint64_t rows) {
  auto opened = cellforge::open_store(db);
  if (!opened) {
    std::fprintf(stderr, "open %s: %s\n", db.c_str(), opened.error().message.c_str());
    return false;
  }
  cellforge::Store& store = *opened.value();
  const std::string backend = store.backend();
  const char* name = backend.c_str();
  (void)store.remove("bench");
  auto t0 = std::chrono::steady_clock::now();
  auto put = store.put("bench", m);
  const double save = seconds_since(t0);
  if (!put) {
    std::fprintf(stderr, "save: %s\n", put.error().message.c_str());
    return false;
  }
  t0 = std::chrono::steady_clock::now();
  auto got = store.get("bench");
  const double load = seconds_since(t0);
  if (!got) {
    std::fprintf(stderr, "load: %s\n", got.error().message.c_str());
    return false;
  }
  // The sheet has no free slots, so the loaded ids are the saved ones.
  bool same = got->num_faces() == m.num_faces() && got->num_edges() == m.num_edges() &&
              got->num_vertices() == m.num_vertices();
  for (cellforge::VertexId v : m.vertices()) {
    same = same && got->position(v) == m.position(v);
  }
  std::printf("%-11s save  %8.2f s  %12.0f rows/s\n", name, save,
              static_cast<double>(rows) / save);
  std::printf("%-11s load  %8.2f s  %12.0f rows/s  (validated%s)\n", name, load,
              static_cast<double>(rows) / load, same ? ", identical" : ", DIFFERENT");
  std::printf("%-11s save + load = %.2f x (STL write + read)\n", name,
              (save + load) / stl_seconds);

  // A tenth of the sheet by its face boxes: x below a tenth of its width.
  const cellforge::Vec3 lo = put->bbox_min, hi = put->bbox_max;
  const double cut = lo.x + 0.1 * (hi.x - lo.x);
  t0 = std::chrono::steady_clock::now();
  auto part = store.get_faces_where("bench", "f.max_x <= " + std::to_string(cut));
  const double partial = seconds_since(t0);
  if (!part) {
    std::fprintf(stderr, "partial load: %s\n", part.error().message.c_str());
    return false;
  }
  std::printf("%-11s partial load %6.2f s  %zu faces (validated)\n", name, partial,
              part->num_faces());

  // Boxes of 1/100 of the sheet's width at random places.
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  const int queries = 200;
  std::size_t found = 0;
  t0 = std::chrono::steady_clock::now();
  for (int q = 0; q < queries; ++q) {
    const double x = lo.x + u(rng) * (hi.x - lo.x), y = lo.y + u(rng) * (hi.y - lo.y);
    const double w = 0.01 * (hi.x - lo.x);
    auto faces = store.faces_in_box("bench", {{x, y, lo.z}, {x + w, y + w, hi.z}});
    if (!faces) {
      std::fprintf(stderr, "faces_in_box: %s\n", faces.error().message.c_str());
      return false;
    }
    found += faces->size();
  }
  const double spatial = seconds_since(t0);
  std::printf("%-11s faces in box  %6.2f ms per query  (%zu faces on average)\n", name,
              1e3 * spatial / queries, found / queries);
  t0 = std::chrono::steady_clock::now();
  auto volumes = store.volumes_in_box({lo, lo});
  const double vq = seconds_since(t0);
  std::printf("%-11s volumes in box %5.2f ms  (%zu found)\n", name, 1e3 * vq,
              volumes ? volumes->size() : 0);
  const std::int64_t bytes = stored_bytes(store);
  std::printf("%-11s on disk %10.1f MB  %6.1f bytes per face\n", name, bytes / 1e6,
              static_cast<double>(bytes) / static_cast<double>(m.num_faces()));
  (void)store.remove("bench");
  return same;
}

// The same model as a binary STL file, written and read back (with welding and the
// topology built), for comparison in the same run.
void ok_stl(const std::string& dir, const Model& m) {
  const std::string file = dir + "/bench_store.stl";
  auto t0 = std::chrono::steady_clock::now();
  const cellforge::Status w = cellforge::io::write_file(m, file);
  const double write = seconds_since(t0);
  Model back;
  t0 = std::chrono::steady_clock::now();
  auto r = cellforge::io::read_file(back, file);
  const double read = seconds_since(t0);
  const auto stl_bytes = w ? std::filesystem::file_size(file) : 0;
  std::filesystem::remove(file);
  if (!w || !r) {
    std::printf("binary STL  failed: %s\n",
                !w ? w.error().message.c_str() : r.error().message.c_str());
    return;
  }
  stl_seconds = write + read;
  std::printf("binary STL  write %8.2f s  %12.0f faces/s\n", write,
              static_cast<double>(m.num_faces()) / write);
  std::printf("binary STL  read  %8.2f s  %12.0f faces/s  (welded, topology built)\n", read,
              static_cast<double>(m.num_faces()) / read);
  std::printf("binary STL  on disk %10.1f MB  %6.1f bytes per face\n", stl_bytes / 1e6,
              static_cast<double>(stl_bytes) / static_cast<double>(m.num_faces()));
}

// The sizes of the same model as 3MF and native JSON.
void file_sizes(const std::string& dir, const Model& m) {
  for (const char* ext : {".3mf", ".json"}) {
    const std::string file = dir + "/bench_store" + ext;
    if (cellforge::io::write_file(m, file)) {
      const auto bytes = std::filesystem::file_size(file);
      std::printf("%-11s on disk %10.1f MB  %6.1f bytes per face\n", ext + 1, bytes / 1e6,
                  static_cast<double>(bytes) / static_cast<double>(m.num_faces()));
    }
    std::filesystem::remove(file);
  }
}

}  // namespace

int main(int argc, char** argv) {
  long faces = 1000000;
  std::string dir = std::filesystem::temp_directory_path().string();
  const char* env = std::getenv("CELLFORGE_PG_URL");
  std::string pg = env ? env : "";
  bool sizes = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--sizes") {
      sizes = true;
    } else if (i + 1 < argc && a == "--faces") {
      faces = std::atol(argv[++i]);
    } else if (i + 1 < argc && a == "--dir") {
      dir = argv[++i];
    } else if (i + 1 < argc && a == "--pg") {
      pg = argv[++i];
    }
  }
  int n = 1;
  while (2L * n * n < faces) ++n;
  const Model m = sheet(n);
  const std::uint64_t rows = cellforge::store::to_rows(m).row_count() + 1;
  std::printf("model: %zu faces, %zu edges, %zu vertices, %zu edge uses; %llu rows\n",
              m.num_faces(), m.num_edges(), m.num_vertices(), m.num_edge_uses(),
              static_cast<unsigned long long>(rows));
  ok_stl(dir, m);
  if (sizes) file_sizes(dir, m);
  const std::string file = dir + "/bench_store.db";
  for (const char* ext : {"", "-wal", "-shm"}) std::filesystem::remove(file + ext);
  bool ok = run(file, m, rows);
  for (const char* ext : {"", "-wal", "-shm"}) std::filesystem::remove(file + ext);
  if (pg.empty()) {
    std::printf("postgresql  skipped (set CELLFORGE_PG_URL or pass --pg)\n");
  } else {
    // A schema of its own, so that the sizes are of this model alone.
    const std::string schema = "cellforge_bench_" + std::to_string(getpid());
    if (!pg_exec(pg, "CREATE SCHEMA " + schema)) return 1;
    const std::string url =
        pg + (pg.find('?') == std::string::npos ? "?" : "&") + "options=-csearch_path%3D" + schema;
    ok = run(url, m, rows) && ok;
    ok = pg_exec(pg, "DROP SCHEMA " + schema + " CASCADE") && ok;
  }
  return ok ? 0 : 1;
}
