#include "store/store_fixture.h"

#include <libpq-fe.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "cellforge/topo/builder.h"
#include "cellforge/topo/dump.h"
#include "store/model_rows.h"

namespace cellforge::testing {

std::string unique_suffix() {
  static std::atomic<int> counter{0};
  return std::to_string(getpid()) + "_" + std::to_string(counter++);
}

namespace {

bool run_pg(const std::string& url, const std::string& sql) {
  PGconn* c = PQconnectdb(url.c_str());
  bool ok = PQstatus(c) == CONNECTION_OK;
  if (ok) {
    PGresult* r = PQexec(c, sql.c_str());
    ok = PQresultStatus(r) == PGRES_COMMAND_OK;
    if (!ok) ADD_FAILURE() << sql << ": " << PQresultErrorMessage(r);
    PQclear(r);
  } else {
    ADD_FAILURE() << "cannot connect to " << url << ": " << PQerrorMessage(c);
  }
  PQfinish(c);
  return ok;
}

}  // namespace

void StoreTest::SetUp() {
  if (GetParam() == "sqlite") {
    file_ =
        (std::filesystem::temp_directory_path() / ("cellforge_store_" + unique_suffix() + ".db"))
            .string();
    db_ = file_;
  } else {
    const char* url = std::getenv("CELLFORGE_PG_URL");
    if (!url || !*url) {
      if (std::getenv("CI")) {
        FAIL() << "CELLFORGE_PG_URL is not set but CI is: the PostgreSQL tests must run "
                  "(eval \"$(scripts/pg_test_server.sh start)\")";
      }
      GTEST_SKIP() << "\n*** PostgreSQL tests SKIPPED: CELLFORGE_PG_URL is not set.\n"
                      "*** Start a server with: eval \"$(scripts/pg_test_server.sh start)\"\n";
    }
    schema_ = "cellforge_test_" + unique_suffix();
    ASSERT_TRUE(run_pg(url, "CREATE SCHEMA " + schema_));
    db_ = std::string(url) + (std::strchr(url, '?') ? "&" : "?") + "options=-csearch_path%3D" +
          schema_;
  }
  auto s = open_store(db_);
  ASSERT_TRUE(s.ok()) << s.error().message;
  store_ = std::move(s.value());
  ASSERT_EQ(store_->backend(), GetParam());
}

void StoreTest::TearDown() {
  store_.reset();
  if (!file_.empty()) {
    for (const char* ext : {"", "-wal", "-shm"}) std::filesystem::remove(file_ + ext);
  }
  if (!schema_.empty())
    run_pg(std::getenv("CELLFORGE_PG_URL"), "DROP SCHEMA " + schema_ + " CASCADE");
}

std::unique_ptr<Store> StoreTest::open_again() const {
  auto s = open_store(db_);
  EXPECT_TRUE(s.ok()) << s.error().message;
  return s ? std::move(s.value()) : nullptr;
}

void expect_same_model(const Model& original, const Model& loaded) {
  EXPECT_EQ(canonical_dump(original), canonical_dump(loaded));
  // Record by record: the original renumbered densely (what the store keeps)
  // against the loaded model, whose ids are dense.
  auto dense = store::to_model(store::to_rows(original));
  ASSERT_TRUE(dense.ok()) << dense.error().message;
  EXPECT_EQ(raw_dump(dense.value()), raw_dump(loaded));
  const auto a = store::to_rows(original), b = store::to_rows(loaded);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) {
    EXPECT_EQ(0, std::memcmp(&a.vertices[i].p, &b.vertices[i].p, sizeof(Vec3))) << "vertex " << i;
  }
  ASSERT_EQ(a.uses.size(), b.uses.size());
  for (std::size_t i = 0; i < a.uses.size(); ++i) {
    EXPECT_EQ(a.uses[i].edge, b.uses[i].edge) << "use " << i;
    EXPECT_EQ(a.uses[i].reversed, b.uses[i].reversed) << "use " << i;
    EXPECT_EQ(a.uses[i].radial_ord, b.uses[i].radial_ord) << "use " << i;
  }
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].start, b.edges[i].start) << "edge " << i;
    EXPECT_EQ(a.edges[i].end, b.edges[i].end) << "edge " << i;
  }
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t i = 0; i < a.groups.size(); ++i) EXPECT_EQ(a.groups[i].name, b.groups[i].name);
  ASSERT_EQ(a.parameters.size(), b.parameters.size());
  for (std::size_t i = 0; i < a.parameters.size(); ++i) {
    EXPECT_EQ(a.parameters[i].name, b.parameters[i].name);
    EXPECT_EQ(a.parameters[i].value, b.parameters[i].value);
  }
  ASSERT_EQ(a.surfaces.size(), b.surfaces.size());
  for (std::size_t i = 0; i < a.surfaces.size(); ++i) EXPECT_EQ(a.surfaces[i], b.surfaces[i]);
}

Model grid_sheet(int n, double z) {
  MeshInput in;
  auto coord = [](int i) { return i * 0.1 + 1e-7 * ((i * 7919) % 13); };  // not round in binary
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i)
      in.positions.push_back({coord(i), coord(j), z + 1e-3 * ((i ^ j) & 3)});
  }
  auto at = [n](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      in.faces.push_back({{{at(i, j), at(i + 1, j), at(i + 1, j + 1)}}});
      in.faces.push_back({{{at(i, j), at(i + 1, j + 1), at(i, j + 1)}}});
    }
  }
  in.group_name = "grid";
  Model m;
  auto r = build_mesh(m, in);
  EXPECT_TRUE(r.ok()) << r.error().message;
  return m;
}

}  // namespace cellforge::testing
