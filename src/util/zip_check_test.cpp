#include "util/zip_check.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <string>
#include <utility>
#include <vector>

namespace vaegail {
namespace {

std::string le(std::uint64_t value, int width) {
  std::string s;
  for (int i = 0; i < width; ++i) s += static_cast<char>(value >> (8 * i) & 0xFF);
  return s;
}

// A zip of stored entries laid out as LibTorch's writer lays it out (a zip64 end record too).
std::string stored_zip(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string zip, directory;
  for (const auto& [name, data] : entries) {
    const auto crc = ::crc32(0, reinterpret_cast<const Bytef*>(data.data()), static_cast<uInt>(data.size()));
    const std::string sizes = le(crc, 4) + le(data.size(), 4) + le(data.size(), 4);
    directory += le(0x02014b50, 4) + le(20, 2) + le(20, 2) + le(0, 2) + le(0, 2) + le(0, 4) + sizes +
                 le(name.size(), 2) + le(0, 2) + le(0, 2) + le(0, 2) + le(0, 2) + le(0, 4) + le(zip.size(), 4) + name;
    zip += le(0x04034b50, 4) + le(20, 2) + le(0, 2) + le(0, 2) + le(0, 4) + sizes + le(name.size(), 2) + le(0, 2) +
           name + data;
  }
  const std::uint64_t offset = zip.size(), n = entries.size();
  zip += directory;
  const std::uint64_t end64 = zip.size();
  zip += le(0x06064b50, 4) + le(44, 8) + le(45, 2) + le(45, 2) + le(0, 4) + le(0, 4) + le(n, 8) + le(n, 8) +
         le(directory.size(), 8) + le(offset, 8);
  zip += le(0x07064b50, 4) + le(0, 4) + le(end64, 8) + le(1, 4);
  zip += le(0x06054b50, 4) + le(0, 2) + le(0, 2) + le(0xFFFF, 2) + le(0xFFFF, 2) + le(0xFFFFFFFF, 4) +
         le(0xFFFFFFFF, 4) + le(0, 2);
  return zip;
}

const std::vector<std::pair<std::string, std::string>> kEntries = {{"archive/data.pkl", "pickled"},
                                                                   {"archive/data/0", std::string(1000, 'w')}};

TEST(ZipCheck, AWholeArchivePasses) {
  const std::string zip = stored_zip(kEntries);
  EXPECT_TRUE(looks_like_zip(zip));
  EXPECT_EQ(zip_damage(zip), "");
}

TEST(ZipCheck, AFlippedByteInAnEntryIsNamed) {
  std::string zip = stored_zip(kEntries);
  zip[zip.find("wwww") + 500] ^= 0x10;
  EXPECT_EQ(zip_damage(zip), "entry archive/data/0 fails its CRC-32");
}

TEST(ZipCheck, ATruncatedArchiveHasNoDirectory) {
  const std::string zip = stored_zip(kEntries);
  EXPECT_EQ(zip_damage(zip.substr(0, zip.size() / 2)), "truncated: no zip directory at the end");
  EXPECT_FALSE(looks_like_zip("checkpoint 1"));
}

TEST(ZipCheck, ADamagedDirectoryIsReportedNotFollowed) {
  std::string zip = stored_zip(kEntries);
  const size_t central = zip.find(le(0x02014b50, 4));
  zip.replace(central + 42, 4, le(0x7FFFFFFF, 4));  // the first entry's data far past the end
  EXPECT_EQ(zip_damage(zip), "entry archive/data.pkl: local header damaged");
}

TEST(ZipCheck, EntriesReadBackByNameAndDamageThrows) {
  const auto entries = zip_entries(stored_zip(kEntries));
  ASSERT_EQ(entries.size(), 2u);
  EXPECT_EQ(entries.at("archive/data.pkl"), "pickled");
  EXPECT_EQ(entries.at("archive/data/0"), std::string(1000, 'w'));
  std::string zip = stored_zip(kEntries);
  zip[zip.find("wwww") + 500] ^= 0x10;
  EXPECT_THROW(zip_entries(zip), std::runtime_error);
}

}  // namespace
}  // namespace vaegail
