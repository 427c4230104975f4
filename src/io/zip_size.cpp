// How much a ZIP archive (a 3MF package) declares it unpacks to, read from its
// central directory before the archive is handed to lib3mf: a 2 MB package of
// well-compressed XML can unpack to gigabytes, and lib3mf builds all of it in memory.
// The sizes are the ones the archive declares (ZIP64 sizes included); the limit is
// on those.
#include <cstring>

#include "io/formats.h"
#include "io/text.h"

namespace cellforge::io {

namespace {

std::uint64_t le(const std::uint8_t* p, int n) {
  std::uint64_t v = 0;
  for (int k = n - 1; k >= 0; --k) v = (v << 8) | p[k];
  return v;
}

constexpr std::uint32_t kEnd = 0x06054b50;  // end of central directory
constexpr std::uint32_t kEnd64Locator = 0x07064b50;
constexpr std::uint32_t kEnd64 = 0x06064b50;
constexpr std::uint32_t kCentral = 0x02014b50;  // central directory file header

}  // namespace

Status check_zip_size(std::string_view format, std::span<const std::uint8_t> bytes,
                      std::uint64_t max_unpacked) {
  if (max_unpacked == 0 || bytes.size() < 22) return Status::Ok();
  const std::uint8_t* b = bytes.data();
  const std::size_t n = bytes.size();
  // The end record is in the last 22 + 65535 bytes (its comment is at most 64 KiB).
  std::size_t end = n - 22;
  const std::size_t lowest = n > 22 + 65535 ? n - 22 - 65535 : 0;
  while (le(b + end, 4) != kEnd) {
    if (end == lowest) return Status::Ok();
    --end;
  }
  std::uint64_t entries = le(b + end + 10, 2);
  std::uint64_t directory = le(b + end + 16, 4);
  if ((entries == 0xFFFF || directory == 0xFFFFFFFF) && end >= 20 &&
      le(b + end - 20, 4) == kEnd64Locator) {
    const std::uint64_t at = le(b + end - 20 + 8, 8);
    if (at > n || n - at < 56 || le(b + at, 4) != kEnd64) return Status::Ok();
    entries = le(b + at + 32, 8);
    directory = le(b + at + 48, 8);
  }
  std::uint64_t total = 0;
  std::uint64_t at = directory;
  for (std::uint64_t e = 0; e < entries; ++e) {
    if (at > n || n - at < 46 || le(b + at, 4) != kCentral) return Status::Ok();
    std::uint64_t size = le(b + at + 24, 4);
    const std::uint64_t name = le(b + at + 28, 2), extra = le(b + at + 30, 2),
                        comment = le(b + at + 32, 2);
    if (n - at - 46 < name + extra + comment) return Status::Ok();
    if (size == 0xFFFFFFFF) {
      // The ZIP64 extra field (id 1) holds the unpacked size first.
      for (std::uint64_t x = at + 46 + name; x + 4 <= at + 46 + name + extra;) {
        const std::uint64_t id = le(b + x, 2), len = le(b + x + 2, 2);
        if (id == 1 && len >= 8 && x + 4 + 8 <= n) {
          size = le(b + x + 4, 8);
          break;
        }
        x += 4 + len;
      }
    }
    total = size > UINT64_MAX - total ? UINT64_MAX : total + size;
    if (total > max_unpacked) {
      return Error{ErrorCode::kParse,
                   std::string(format) + ": the archive unpacks to " +
                       (e + 1 == entries ? std::to_string(total) + " bytes"
                                         : "more than " + std::to_string(total) + " bytes") +
                       ", more than the limit of " + std::to_string(max_unpacked) +
                       " bytes (the option max_3mf_bytes=N raises it, 0 lifts it)"};
    }
    at += 46 + name + extra + comment;
  }
  return Status::Ok();
}

}  // namespace cellforge::io
