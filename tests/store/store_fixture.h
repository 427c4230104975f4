// The backends the store tests run on, and helpers shared by them.
//
// Every test of a StoreTest suite runs on SQLite (a fresh file) and on PostgreSQL
// (a fresh schema in the database named by CELLFORGE_PG_URL; start one with
// scripts/pg_test_server.sh). Without CELLFORGE_PG_URL the PostgreSQL runs fail
// when CI is set and are skipped, loudly, otherwise.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "cellforge/store/store.h"
#include "cellforge/topo/model.h"

namespace cellforge::testing {

class StoreTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override;
  void TearDown() override;
  // A new connection to this test's database (for other threads or processes).
  std::unique_ptr<Store> open_again() const;

  std::string db_;  // what open_store was given
  std::unique_ptr<Store> store_;

 private:
  std::string file_, schema_;
};

// Fails the test unless `loaded` is `original` exactly: the same canonical dump,
// and, record by record after numbering the live entities densely, the same
// edge directions, loop starts, radial cycles and bit-identical coordinates.
void expect_same_model(const Model& original, const Model& loaded);

// A triangulated n x n grid sheet (2 n^2 faces) with irregular coordinates.
Model grid_sheet(int n, double z = 0);

std::string unique_suffix();

}  // namespace cellforge::testing

#define CELLFORGE_BACKENDS(suite) \
  INSTANTIATE_TEST_SUITE_P(Backends, suite, ::testing::Values("sqlite", "postgresql"))
