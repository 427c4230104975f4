// The ZIP container of 3MF packages (PKWARE APPNOTE 6.3: local headers, central
// directory, end record, and the ZIP64 records lib3mf writes; methods 0 stored and 8
// deflate through zlib). No encryption, no multi-disk archives.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "cellforge/result.h"

namespace cellforge::io {

struct ZipEntry {
  std::string name;
  std::string data;
};

// A package of deflated entries.
std::string write_zip(const std::vector<ZipEntry>& entries);

// The entries of an archive, by the central directory. Errors name the byte offset.
class ZipReader {
 public:
  static Result<ZipReader> open(std::span<const std::uint8_t> bytes);
  bool has(const std::string& name) const;
  // The bytes of one entry, checked against its CRC-32; an entry that would unpack
  // to more than `limit` bytes is refused before it is unpacked.
  Result<std::string> read(const std::string& name, std::uint64_t limit) const;

 private:
  struct Entry {
    std::string name;
    std::uint16_t method = 0;
    std::uint32_t crc = 0;
    std::uint64_t packed = 0, size = 0, header = 0;
  };
  std::span<const std::uint8_t> bytes_;
  std::vector<Entry> entries_;
};

}  // namespace cellforge::io
