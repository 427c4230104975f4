// Save and load of a 10^6-face model in the model database, on SQLite and (when
// CELLFORGE_PG_URL or --pg names one) PostgreSQL: seconds and rows per second.
//
//   bench_store [--faces N] [--dir DIR] [--pg postgresql://...]
//
// The model is a triangulated sheet with irregular coordinates (2 n^2 faces).
// Rows are every row written to or read from the tables of docs/database.md. The
// same model written and read as binary STL is timed first, for comparison.
#include <chrono>
#include <cstdio>
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

bool run(const std::string& db, const Model& m, std::uint64_t rows) {
  auto opened = cellforge::open_store(db);
  if (!opened) {
    std::fprintf(stderr, "open %s: %s\n", db.c_str(), opened.error().message.c_str());
    return false;
  }
  cellforge::Store& store = *opened.value();
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
  std::printf("%-11s save  %8.2f s  %12.0f rows/s\n", store.backend().c_str(), save,
              static_cast<double>(rows) / save);
  std::printf("%-11s load  %8.2f s  %12.0f rows/s  (validated%s)\n", store.backend().c_str(), load,
              static_cast<double>(rows) / load, same ? ", identical" : ", DIFFERENT");
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
  std::filesystem::remove(file);
  if (!w || !r) {
    std::printf("binary STL  failed: %s\n",
                !w ? w.error().message.c_str() : r.error().message.c_str());
    return;
  }
  std::printf("binary STL  write %8.2f s  %12.0f faces/s\n", write,
              static_cast<double>(m.num_faces()) / write);
  std::printf("binary STL  read  %8.2f s  %12.0f faces/s  (welded, topology built)\n", read,
              static_cast<double>(m.num_faces()) / read);
}

}  // namespace

int main(int argc, char** argv) {
  long faces = 1000000;
  std::string dir = std::filesystem::temp_directory_path().string();
  const char* env = std::getenv("CELLFORGE_PG_URL");
  std::string pg = env ? env : "";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--faces")
      faces = std::atol(argv[i + 1]);
    else if (a == "--dir")
      dir = argv[i + 1];
    else if (a == "--pg")
      pg = argv[i + 1];
  }
  int n = 1;
  while (2L * n * n < faces) ++n;
  const Model m = sheet(n);
  const std::uint64_t rows = cellforge::store::to_rows(m).row_count() + 1;
  std::printf("model: %zu faces, %zu edges, %zu vertices, %zu edge uses; %llu rows\n",
              m.num_faces(), m.num_edges(), m.num_vertices(), m.num_edge_uses(),
              static_cast<unsigned long long>(rows));
  ok_stl(dir, m);
  const std::string file = dir + "/bench_store.db";
  for (const char* ext : {"", "-wal", "-shm"}) std::filesystem::remove(file + ext);
  bool ok = run(file, m, rows);
  for (const char* ext : {"", "-wal", "-shm"}) std::filesystem::remove(file + ext);
  if (pg.empty()) {
    std::printf("postgresql  skipped (set CELLFORGE_PG_URL or pass --pg)\n");
  } else {
    ok = run(pg, m, rows) && ok;
  }
  return ok ? 0 : 1;
}
