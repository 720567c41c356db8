// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/core/file_hash.h"

#include <openssl/evp.h>

#include <array>
#include <cassert>
#include <cstdio>
#include <memory>

namespace dform {

std::string sha256Hex(std::string_view bytes) {
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(),
                                                                    EVP_MD_CTX_free);
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest;
  unsigned int size = 0;
  const bool hashed = ctx && EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) == 1 &&
                      EVP_DigestUpdate(ctx.get(), bytes.data(), bytes.size()) == 1 &&
                      EVP_DigestFinal_ex(ctx.get(), digest.data(), &size) == 1;
  assert(hashed && "OpenSSL's SHA-256 is always available");
  (void)hashed;
  std::string hex;
  for (unsigned int i = 0; i < size; ++i) {
    char byte[3];
    std::snprintf(byte, sizeof byte, "%02x", digest[i]);
    hex += byte;
  }
  return hex;
}

}  // namespace dform
