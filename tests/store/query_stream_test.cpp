// User queries stream (issue 18): Store::query_each hands each row over as it is
// read. The property tested is one a buffered answer cannot have: the rows a
// query produced before it failed reach the caller before the error does (a
// buffered read gets the error alone). Stopping from the callback ends the
// query, and the row limit still applies.
#include <gtest/gtest.h>

#include "store/store_fixture.h"
#include "support/checks.h"

namespace cellforge::testing {
namespace {

using QueryStream = StoreTest;

// Rows 1 to 5, then an error at row 6 (SQLite: abs of the smallest integer
// overflows; PostgreSQL: division by zero), of a query that would go on to 10.
std::string fails_at_row_six(const std::string& backend) {
  return backend == "sqlite"
             ? "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE i < 10) "
               "SELECT CASE WHEN i <= 5 THEN i ELSE abs(-9223372036854775802 - i) END AS i FROM n"
             : "SELECT CASE WHEN i <= 5 THEN i ELSE 1 / (i - i) END AS i "
               "FROM generate_series(1, 10) AS i";
}

// A query of `n` rows 1 ... n.
std::string counting(const std::string& backend, long n) {
  return backend == "sqlite"
             ? "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n WHERE i < " +
                   std::to_string(n) + ") SELECT i FROM n"
             : "SELECT i FROM generate_series(1, " + std::to_string(n) + ") AS i";
}

TEST_P(QueryStream, RowsBeforeAnErrorArriveFirst) {
  std::vector<std::string> columns, got;
  QueryCallbacks cb;
  cb.columns = [&](const std::vector<std::string>& c) { columns = c; };
  cb.row = [&](const QueryRow& r) {
    got.push_back(r.values.at(0).value_or("NULL"));
    EXPECT_EQ(r.kinds.at(0), ValueKind::kInteger);
    return true;
  };
  auto r = store_->query_each(fails_at_row_six(GetParam()), {}, cb);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(columns, std::vector<std::string>{"i"});
  EXPECT_EQ(got, (std::vector<std::string>{"1", "2", "3", "4", "5"}));
  // The buffered call of the same query gives the error and no rows.
  EXPECT_FALSE(store_->query(fails_at_row_six(GetParam())).ok());
}

TEST_P(QueryStream, StoppingEndsTheQuery) {
  // A million rows, of which the caller takes three: the query stops there and
  // the connection serves the next query.
  int calls = 0;
  QueryCallbacks cb;
  cb.row = [&](const QueryRow&) { return ++calls < 3; };
  auto r = store_->query_each(counting(GetParam(), 1000000), {}, cb);
  ASSERT_OK(r);
  EXPECT_FALSE(r.value());
  EXPECT_EQ(calls, 3);
  auto next = store_->query(counting(GetParam(), 2));
  ASSERT_OK(next);
  EXPECT_EQ(next->rows.size(), 2u);
}

TEST_P(QueryStream, TheRowLimitStillApplies) {
  QueryOptions o;
  o.max_rows = 4;
  std::vector<std::string> got;
  QueryCallbacks cb;
  cb.row = [&](const QueryRow& r) {
    got.push_back(*r.values.at(0));
    return true;
  };
  auto r = store_->query_each(counting(GetParam(), 10), o, cb);
  ASSERT_OK(r);
  EXPECT_TRUE(r.value());  // rows were left out
  EXPECT_EQ(got, (std::vector<std::string>{"1", "2", "3", "4"}));
  got.clear();
  o.max_rows = 10;
  r = store_->query_each(counting(GetParam(), 10), o, cb);
  ASSERT_OK(r);
  EXPECT_FALSE(r.value());  // exactly the limit: nothing left out
  EXPECT_EQ(got.size(), 10u);
}

CELLFORGE_BACKENDS(QueryStream);

}  // namespace
}  // namespace cellforge::testing
