// Helpers for the io/ tests: fixture files, round trips through bytes.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "cellforge/io/mesh_io.h"

namespace cellforge::testing {

inline std::string data_path(const std::string& name) {
  return std::string(CELLFORGE_TEST_DATA) + "/" + name;
}

inline std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// Reads a fixture file into a fresh model (the test fails on an error).
inline Model read_fixture(const std::string& name, const io::ReadOptions& options = {}) {
  Model m;
  auto r = io::read_file(m, data_path(name), options);
  EXPECT_TRUE(r.ok()) << name << ": " << (r.ok() ? "" : r.error().message);
  return m;
}

// Writes m in `format` and reads the bytes back into a fresh model.
inline Model round_trip(const Model& m, io::Format format, const io::WriteOptions& w = {},
                        const io::ReadOptions& r = {}) {
  auto bytes = io::write_model(m, format, w);
  EXPECT_TRUE(bytes.ok()) << (bytes.ok() ? "" : bytes.error().message);
  Model back;
  if (!bytes.ok()) return back;
  auto read = io::read_model(back, bytes_of(*bytes), format, r);
  EXPECT_TRUE(read.ok()) << (read.ok() ? "" : read.error().message);
  return back;
}

// The error message of reading a fixture that must fail.
inline std::string read_error(const std::string& name) {
  Model m;
  auto r = io::read_file(m, data_path(name));
  EXPECT_FALSE(r.ok()) << name << " was read without error";
  EXPECT_TRUE(m.empty()) << name << " left entities in the model";
  return r.ok() ? std::string() : r.error().message;
}

}  // namespace cellforge::testing
