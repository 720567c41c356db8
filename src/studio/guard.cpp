// SPDX-License-Identifier: GPL-3.0-or-later
#include "guard.h"

#include <cctype>
#include <random>

namespace dform::studio {

namespace {

// Equal strings, compared in a time that does not depend on where they differ.
bool sameSecret(const std::string& a, const std::string& b) {
  if (a.size() != b.size() || a.empty()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

std::string cookieValue(const std::string& cookies, const std::string& name) {
  std::size_t at = 0;
  while (at < cookies.size()) {
    std::size_t end = cookies.find(';', at);
    if (end == std::string::npos) end = cookies.size();
    std::string pair = cookies.substr(at, end - at);
    const std::size_t first = pair.find_first_not_of(' ');
    pair = first == std::string::npos ? "" : pair.substr(first);
    if (pair.compare(0, name.size() + 1, name + "=") == 0) return pair.substr(name.size() + 1);
    at = end + 1;
  }
  return "";
}

}  // namespace

std::string tokenCookieName(int port) { return "dform_studio_" + std::to_string(port); }

std::string refusal(const RequestFacts& r, int port, const std::string& token) {
  const std::string p = std::to_string(port);
  const std::string hosts[] = {"127.0.0.1:" + p, "localhost:" + p, "[::1]:" + p};
  bool hostOk = false, originOk = r.origin.empty();
  for (const std::string& h : hosts) {
    hostOk = hostOk || r.host == h;
    originOk = originOk || r.origin == "http://" + h;
  }
  if (!hostOk) return "the Host header must name the studio's loopback address";
  if (!originOk || r.fetchSite == "cross-site") return "requests from another origin are refused";
  if (!sameSecret(r.queryToken, token) && !sameSecret(r.headerToken, token) &&
      !sameSecret(cookieValue(r.cookie, tokenCookieName(port)), token))
    return "the studio's token is missing or wrong (open the address dform studio printed)";
  return "";
}

std::string randomToken() {
  std::random_device device;  // /dev/urandom on Linux
  static const char hex[] = "0123456789abcdef";
  std::string token;
  for (int i = 0; i < 8; ++i) {
    const unsigned int word = device();
    for (int k = 0; k < 4; ++k) token += hex[(word >> (4 * k)) & 15];
  }
  return token;
}

std::string safeFileName(const std::string& name, const std::vector<std::string>& extensions,
                         const std::string& fallback) {
  std::string base =
      name.substr(name.find_last_of("/\\") == std::string::npos ? 0 : name.find_last_of("/\\") + 1);
  for (char& c : base)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '-';
  if (base.size() > 80) base = base.substr(base.size() - 80);
  while (!base.empty() && base[0] == '.') base.erase(0, 1);  // no hidden files, no ".."
  for (const std::string& ext : extensions)
    if (base.size() > ext.size() && base.compare(base.size() - ext.size(), ext.size(), ext) == 0 &&
        base != "job.json")
      return base;
  return fallback;
}

}  // namespace dform::studio
