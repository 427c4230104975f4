// ZIP archives for 3MF (zip.h).
#include "io/zip.h"

#include <zlib.h>

#include <algorithm>

#include "io/text.h"

namespace cellforge::io {

namespace {

void put16(std::string& out, std::uint32_t v) {
  out += static_cast<char>(v & 0xff);
  out += static_cast<char>((v >> 8) & 0xff);
}
void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xffff);
  put16(out, v >> 16);
}
std::uint32_t get16(std::span<const std::uint8_t> b, std::size_t at) {
  return b[at] | static_cast<std::uint32_t>(b[at + 1]) << 8;
}
std::uint32_t get32(std::span<const std::uint8_t> b, std::size_t at) {
  return get16(b, at) | get16(b, at + 2) << 16;
}
std::uint64_t get64(std::span<const std::uint8_t> b, std::size_t at) {
  return get32(b, at) | static_cast<std::uint64_t>(get32(b, at + 4)) << 32;
}

std::string deflate_raw(const std::string& data) {
  z_stream z{};
  deflateInit2(&z, Z_DEFAULT_COMPRESSION, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&z, static_cast<uLong>(data.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  z.avail_in = static_cast<uInt>(data.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

std::uint32_t crc_of(const void* data, std::size_t size) {
  return static_cast<std::uint32_t>(
      crc32(crc32(0, nullptr, 0), static_cast<const Bytef*>(data), static_cast<uInt>(size)));
}

Error zip_error(std::size_t offset, const std::string& message) {
  return byte_error("3mf", offset, message);
}

}  // namespace

std::string write_zip(const std::vector<ZipEntry>& entries) {
  std::string out, directory;
  for (const ZipEntry& e : entries) {
    const std::string packed = deflate_raw(e.data);
    const std::uint32_t crc = crc_of(e.data.data(), e.data.size());
    const auto offset = static_cast<std::uint32_t>(out.size());
    const auto header = [&](std::string& s, bool central) {
      put32(s, central ? 0x02014b50 : 0x04034b50);
      if (central) put16(s, 20);  // made by: version 2.0
      put16(s, 20);               // needed: version 2.0 (deflate)
      put16(s, 0);                // flags
      put16(s, 8);                // deflate
      put16(s, 0);                // time
      put16(s, 0x21);             // date: 1980-01-01
      put32(s, crc);
      put32(s, static_cast<std::uint32_t>(packed.size()));
      put32(s, static_cast<std::uint32_t>(e.data.size()));
      put16(s, static_cast<std::uint32_t>(e.name.size()));
      put16(s, 0);  // extra
      if (central) {
        put16(s, 0);  // comment
        put16(s, 0);  // disk
        put16(s, 0);  // internal attributes
        put32(s, 0);  // external attributes
        put32(s, offset);
      }
      s += e.name;
    };
    header(out, false);
    out += packed;
    header(directory, true);
  }
  const auto at = static_cast<std::uint32_t>(out.size());
  out += directory;
  put32(out, 0x06054b50);
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint32_t>(entries.size()));
  put16(out, static_cast<std::uint32_t>(entries.size()));
  put32(out, static_cast<std::uint32_t>(directory.size()));
  put32(out, at);
  put16(out, 0);
  return out;
}

Result<ZipReader> ZipReader::open(std::span<const std::uint8_t> bytes) {
  ZipReader z;
  z.bytes_ = bytes;
  // The end record: its signature within the last 22 + 65535 bytes (the comment).
  if (bytes.size() < 22) return zip_error(0, "too short for a ZIP archive");
  std::size_t end = bytes.size() - 22;
  const std::size_t stop = bytes.size() > 22 + 65535 ? bytes.size() - 22 - 65535 : 0;
  while (get32(bytes, end) != 0x06054b50) {
    if (end == stop) return zip_error(0, "no end of central directory record (not a ZIP archive)");
    --end;
  }
  std::uint64_t count = get16(bytes, end + 10), size = get32(bytes, end + 12);
  std::uint64_t at = get32(bytes, end + 16);
  std::uint64_t limit = end;  // where the central directory must end
  if (count == 0xffff || size == 0xffffffffu || at == 0xffffffffu) {
    // ZIP64: a locator right before the end record names the ZIP64 end record.
    if (end < 20 || get32(bytes, end - 20) != 0x07064b50)
      return zip_error(end, "a ZIP64 archive without its end record locator");
    const std::uint64_t record = get64(bytes, end - 12);
    if (record > end - 20 || end - 20 - record < 56 || get32(bytes, record) != 0x06064b50)
      return zip_error(end - 20, "the ZIP64 end record is damaged");
    count = get64(bytes, record + 32);
    size = get64(bytes, record + 40);
    at = get64(bytes, record + 48);
    limit = record;
  }
  if (at > limit || size > limit - at)
    return zip_error(end, "the central directory lies outside the archive");
  if (count > size / 46)
    return zip_error(end, "the central directory is too short for its entries");
  std::uint64_t p = at;
  for (std::uint64_t i = 0; i < count; ++i) {
    if (p + 46 > limit || get32(bytes, p) != 0x02014b50)
      return zip_error(p, "central directory entry " + std::to_string(i) + " is damaged");
    Entry e;
    e.method = static_cast<std::uint16_t>(get16(bytes, p + 10));
    e.crc = get32(bytes, p + 16);
    e.packed = get32(bytes, p + 20);
    e.size = get32(bytes, p + 24);
    const std::uint32_t name = get16(bytes, p + 28), extra = get16(bytes, p + 30),
                        comment = get16(bytes, p + 32);
    e.header = get32(bytes, p + 42);
    if (get16(bytes, p + 8) & 1) return zip_error(p, "encrypted entries are not supported");
    if (p + 46 + name + extra > limit)
      return zip_error(p, "central directory entry " + std::to_string(i) + " runs past it");
    e.name.assign(reinterpret_cast<const char*>(bytes.data() + p + 46), name);
    // ZIP64 extra field (id 1): 8-byte values for the fields saturated above, in order.
    for (std::uint64_t x = p + 46 + name; x + 4 <= p + 46 + name + extra;) {
      const std::uint32_t id = get16(bytes, x), len = get16(bytes, x + 2);
      if (x + 4 + len > p + 46 + name + extra) break;
      if (id == 1) {
        std::uint64_t f = x + 4;
        const auto take = [&](std::uint64_t& v) {
          if (v == 0xffffffffu && f + 8 <= x + 4 + len) v = get64(bytes, f), f += 8;
        };
        take(e.size);
        take(e.packed);
        take(e.header);
      }
      x += 4 + len;
    }
    z.entries_.push_back(std::move(e));
    p += 46 + name + extra + comment;
  }
  return z;
}

bool ZipReader::has(const std::string& name) const {
  return std::any_of(entries_.begin(), entries_.end(),
                     [&](const Entry& e) { return e.name == name; });
}

Result<std::string> ZipReader::read(const std::string& name, std::uint64_t limit) const {
  const auto it = std::find_if(entries_.begin(), entries_.end(),
                               [&](const Entry& e) { return e.name == name; });
  if (it == entries_.end()) return Error{ErrorCode::kParse, "3mf: the package has no part " + name};
  const Entry& e = *it;
  const std::uint64_t h = e.header;
  if (h > bytes_.size() || bytes_.size() - h < 30 || get32(bytes_, h) != 0x04034b50)
    return zip_error(h, "the local header of " + name + " is damaged");
  const std::uint64_t data = h + 30 + get16(bytes_, h + 26) + get16(bytes_, h + 28);
  if (data > bytes_.size() || e.packed > bytes_.size() - data)
    return zip_error(h, name + " runs past the end of the archive");
  if (e.size > limit)
    return zip_error(h, name + " would unpack to " + std::to_string(e.size) +
                            " bytes, more than the limit of " + std::to_string(limit));
  // Deflate expands at most 1032 to 1 (a run of 258 bytes per 2 bits): a larger size
  // is a lie, and would be allocated before the data could refute it.
  if (e.method == 8 && e.size > 1032 * e.packed + 1032)
    return zip_error(h, name + " declares " + std::to_string(e.size) + " bytes from " +
                            std::to_string(e.packed) + " deflated ones, more than deflate can make");
  std::string out(e.size, '\0');
  const std::uint8_t* in = bytes_.data() + data;
  if (e.method == 0) {
    if (e.packed != e.size) return zip_error(h, name + ": stored sizes disagree");
    std::copy(in, in + e.size, out.begin());
  } else if (e.method == 8) {
    z_stream z{};
    inflateInit2(&z, -15);
    z.next_in = const_cast<Bytef*>(in);
    z.avail_in = static_cast<uInt>(e.packed);
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = static_cast<uInt>(out.size());
    const int r = inflate(&z, Z_FINISH);
    const std::uint64_t got = z.total_out;
    inflateEnd(&z);
    if (r != Z_STREAM_END || got != e.size)
      return zip_error(data, name + ": the deflate stream is damaged or longer than its size");
  } else {
    return zip_error(h, name + ": compression method " + std::to_string(e.method) +
                            " is not supported (only stored and deflate)");
  }
  if (crc_of(out.data(), out.size()) != e.crc)
    return zip_error(data, name + ": CRC-32 mismatch (the entry is damaged)");
  return out;
}

}  // namespace cellforge::io
