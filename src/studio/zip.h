// SPDX-License-Identifier: GPL-3.0-or-later
// A zip archive of stored (uncompressed) files, for the studio's downloads. Debian 12 offers
// libzip, but the studio only bundles a result folder's few files for the browser: the format's
// stored subset (local headers, central directory, CRC-32) is a few dozen lines and needs no
// compression, while PDFs, GLBs and PNGs barely compress anyway (docs/studio.md, "Downloads").
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace dform::studio {

/// The bytes of a zip archive holding `files` (name, content) in that order, stored. Names must
/// be relative, '/'-separated and under 64 KiB; every file under 4 GiB (no ZIP64).
std::string storedZip(const std::vector<std::pair<std::string, std::string>>& files);

/// CRC-32 (ISO-HDLC, as zip and PNG use it) of `data`.
unsigned long crc32(const std::string& data);

}  // namespace dform::studio
