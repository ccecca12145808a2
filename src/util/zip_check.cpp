#include "util/zip_check.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>

namespace vaegail {

namespace {

// Zip's little-endian fields, bounds-checked: a damaged directory must not read past the end.
class Bytes {
 public:
  explicit Bytes(const std::string& bytes) : bytes_(bytes) {}
  bool has(std::uint64_t offset, std::uint64_t size) const {
    return offset <= bytes_.size() && size <= bytes_.size() - offset;
  }
  std::uint64_t le(std::uint64_t offset, int width) const {
    std::uint64_t value = 0;
    for (int i = width - 1; i >= 0; --i) value = value << 8 | static_cast<unsigned char>(bytes_[offset + i]);
    return value;
  }
  bool signature(std::uint64_t offset, std::uint32_t magic) const { return has(offset, 4) && le(offset, 4) == magic; }
  const char* at(std::uint64_t offset) const { return bytes_.data() + offset; }
  std::uint64_t size() const { return bytes_.size(); }

 private:
  const std::string& bytes_;
};

constexpr std::uint32_t kLocalHeader = 0x04034b50, kCentralHeader = 0x02014b50, kEnd = 0x06054b50,
                        kEnd64Locator = 0x07064b50, kEnd64 = 0x06064b50;
constexpr std::uint16_t kZip64Extra = 0x0001;
constexpr std::uint64_t kStored = 0, kDeflated = 8;

struct Directory {
  std::uint64_t entries = 0, offset = 0;
};

// The end-of-central-directory record, or its zip64 form when the archive has one.
bool find_directory(const Bytes& b, Directory& dir) {
  const std::uint64_t longest_comment = 0xFFFF, record = 22;
  if (b.size() < record) return false;
  std::uint64_t end = b.size() - record;
  const std::uint64_t lowest = end > longest_comment ? end - longest_comment : 0;
  while (!b.signature(end, kEnd)) {
    if (end == lowest) return false;
    --end;
  }
  dir = {b.le(end + 10, 2), b.le(end + 16, 4)};
  if (end >= 20 && b.signature(end - 20, kEnd64Locator)) {
    const std::uint64_t end64 = b.le(end - 20 + 8, 8);
    if (!b.has(end64, 56) || !b.signature(end64, kEnd64)) return false;
    dir = {b.le(end64 + 32, 8), b.le(end64 + 48, 8)};
  }
  return true;
}

// Replaces the 32-bit sizes and offset that read 0xFFFFFFFF with their zip64 extra values.
bool read_zip64_extra(const Bytes& b, std::uint64_t extra, std::uint64_t length, std::uint64_t* fields[3]) {
  for (std::uint64_t p = extra; p + 4 <= extra + length;) {
    const std::uint64_t id = b.le(p, 2), size = b.le(p + 2, 2), end = p + 4 + size;
    if (end > extra + length) return false;
    if (id == kZip64Extra) {
      std::uint64_t q = p + 4;
      for (int i = 0; i < 3; ++i)
        if (*fields[i] == 0xFFFFFFFF) {
          if (q + 8 > end) return false;
          *fields[i] = b.le(q, 8);
          q += 8;
        }
    }
    p = end;
  }
  return true;
}

std::uint32_t crc_of_stored(const char* data, std::uint64_t size) {
  uLong crc = ::crc32(0, Z_NULL, 0);
  for (std::uint64_t done = 0; done < size;) {
    const uInt n = static_cast<uInt>(std::min<std::uint64_t>(size - done, 1u << 30));
    crc = ::crc32(crc, reinterpret_cast<const Bytef*>(data + done), n);
    done += n;
  }
  return static_cast<std::uint32_t>(crc);
}

// Inflates a raw deflate stream piece by piece (nothing sized by the directory is allocated),
// appending the bytes to `out` when it is given; false when the stream is malformed or does not
// inflate to `uncompressed` bytes.
bool crc_of_deflated(const char* data, std::uint64_t size, std::uint64_t uncompressed, std::uint32_t& crc,
                     std::string* out_bytes) {
  z_stream z{};
  if (inflateInit2(&z, -MAX_WBITS) != Z_OK) return false;
  std::array<Bytef, 1 << 16> piece;
  uLong running = ::crc32(0, Z_NULL, 0);
  std::uint64_t out = 0;
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data));
  z.avail_in = static_cast<uInt>(std::min<std::uint64_t>(size, 1u << 30));  // code entries are small
  int status = Z_OK;
  while (status == Z_OK) {
    z.next_out = piece.data();
    z.avail_out = piece.size();
    status = inflate(&z, Z_NO_FLUSH);
    const uInt produced = static_cast<uInt>(piece.size() - z.avail_out);
    running = ::crc32(running, piece.data(), produced);
    out += produced;
    if (out > uncompressed) break;  // more than the directory says: damaged
    if (out_bytes) out_bytes->append(reinterpret_cast<const char*>(piece.data()), produced);
    if (status == Z_OK && produced == 0) break;  // input used up before the stream's end
  }
  inflateEnd(&z);
  crc = static_cast<std::uint32_t>(running);
  return status == Z_STREAM_END && out == uncompressed;
}

}  // namespace

bool looks_like_zip(const std::string& bytes) { return Bytes(bytes).signature(0, kLocalHeader); }

namespace {

// Checks every entry; fills `entries` (when given) with each entry's bytes, inflated.
std::string walk_entries(const std::string& bytes, std::map<std::string, std::string>* entries) {
  const Bytes b(bytes);
  Directory dir;
  if (!find_directory(b, dir)) return "truncated: no zip directory at the end";
  std::uint64_t p = dir.offset;
  for (std::uint64_t e = 0; e < dir.entries; ++e) {
    if (!b.has(p, 46) || !b.signature(p, kCentralHeader)) return "central directory damaged";
    const std::uint64_t name_length = b.le(p + 28, 2), extra_length = b.le(p + 30, 2), comment_length = b.le(p + 32, 2);
    if (!b.has(p + 46, name_length + extra_length + comment_length)) return "central directory damaged";
    const std::string name(b.at(p + 46), name_length);
    std::uint64_t size = b.le(p + 20, 4), uncompressed = b.le(p + 24, 4), local = b.le(p + 42, 4);
    std::uint64_t* fields[3] = {&uncompressed, &size, &local};
    if (!read_zip64_extra(b, p + 46 + name_length, extra_length, fields))
      return "entry " + name + ": zip64 fields damaged";
    const std::uint64_t method = b.le(p + 10, 2);
    if (method != kStored && method != kDeflated) return "entry " + name + ": unknown compression";
    if (!b.has(local, 30) || !b.signature(local, kLocalHeader)) return "entry " + name + ": local header damaged";
    const std::uint64_t data = local + 30 + b.le(local + 26, 2) + b.le(local + 28, 2);
    if (!b.has(data, size)) return "entry " + name + " runs past the end of the file: truncated";
    std::uint32_t crc = 0;
    std::string* content = entries ? &(*entries)[name] : nullptr;
    if (method == kStored) {
      crc = crc_of_stored(b.at(data), size);
      if (content) content->assign(b.at(data), size);
    } else if (!crc_of_deflated(b.at(data), size, uncompressed, crc, content)) {
      return "entry " + name + ": compressed data damaged";
    }
    if (crc != b.le(p + 16, 4)) return "entry " + name + " fails its CRC-32";
    p += 46 + name_length + extra_length + comment_length;
  }
  return "";
}

}  // namespace

std::string zip_damage(const std::string& bytes) { return walk_entries(bytes, nullptr); }

std::map<std::string, std::string> zip_entries(const std::string& bytes) {
  std::map<std::string, std::string> entries;
  const std::string damage = walk_entries(bytes, &entries);
  if (!damage.empty()) throw std::runtime_error(damage);
  return entries;
}

}  // namespace vaegail
