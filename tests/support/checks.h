// Shared assertions for topology tests.
#pragma once

#include <gtest/gtest.h>

#include "cellforge/topo/dump.h"
#include "cellforge/topo/validate.h"

#define EXPECT_VALID(model)                                                     \
  do {                                                                          \
    const auto violations_ = ::cellforge::validate(model);                      \
    EXPECT_TRUE(violations_.empty())                                            \
        << ::cellforge::to_string(violations_) << ::cellforge::raw_dump(model); \
  } while (0)

#define ASSERT_OK(expr)                         \
  do {                                          \
    const auto& r_ = (expr);                    \
    ASSERT_TRUE(r_.ok()) << r_.error().message; \
  } while (0)
