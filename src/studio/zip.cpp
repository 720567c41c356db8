// SPDX-License-Identifier: GPL-3.0-or-later
#include "zip.h"

#include <array>
#include <cstdint>

namespace dform::studio {

unsigned long crc32(const std::string& data) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (unsigned char byte : data) c = table[(c ^ byte) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

namespace {

void put16(std::string& out, std::uint32_t v) {
  out += char(v & 0xFF);
  out += char((v >> 8) & 0xFF);
}
void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xFFFF);
  put16(out, v >> 16);
}

// The fields a local header and a central directory entry share: version needed (2.0), flags
// (bit 11: names are UTF-8), method 0 (stored), a fixed DOS time (1980-01-01 00:00, so that an
// archive's bytes depend on its files only), CRC, sizes, name length.
void commonFields(std::string& out, std::uint32_t crc, std::uint32_t size, std::size_t nameLength) {
  put16(out, 20);
  put16(out, 1u << 11);
  put16(out, 0);
  put16(out, 0);
  put16(out, (0 << 9) | (1 << 5) | 1);
  put32(out, crc);
  put32(out, size);
  put32(out, size);
  put16(out, std::uint32_t(nameLength));
}

}  // namespace

std::string storedZip(const std::vector<std::pair<std::string, std::string>>& files) {
  std::string out, directory;
  for (const auto& [name, content] : files) {
    const std::uint32_t crc = std::uint32_t(crc32(content));
    const std::uint32_t offset = std::uint32_t(out.size());
    put32(out, 0x04034b50);
    commonFields(out, crc, std::uint32_t(content.size()), name.size());
    put16(out, 0);  // extra field length
    out += name;
    out += content;

    put32(directory, 0x02014b50);
    put16(directory, 0x0314);  // made by: Unix, 2.0
    commonFields(directory, crc, std::uint32_t(content.size()), name.size());
    put16(directory, 0);               // extra field
    put16(directory, 0);               // comment
    put16(directory, 0);               // disk
    put16(directory, 0);               // internal attributes
    put32(directory, 0100644u << 16);  // external: a regular file, rw-r--r--
    put32(directory, offset);
    directory += name;
  }
  const std::uint32_t directoryOffset = std::uint32_t(out.size());
  out += directory;
  put32(out, 0x06054b50);
  put16(out, 0);
  put16(out, 0);
  put16(out, std::uint32_t(files.size()));
  put16(out, std::uint32_t(files.size()));
  put32(out, std::uint32_t(directory.size()));
  put32(out, directoryOffset);
  put16(out, 0);
  return out;
}

}  // namespace dform::studio
