// SPDX-License-Identifier: GPL-3.0-or-later
// The studio's request guard (docs/studio.md, "Security"): a request is served only when it is
// addressed to the loopback host the studio listens on (no DNS rebinding), comes from no other
// origin (no cross-site requests) and carries the run's token.
#pragma once

#include <string>
#include <vector>

namespace dform::studio {

/// What the guard sees of a request: its headers and its token query parameter.
struct RequestFacts {
  std::string host;         ///< the Host header
  std::string origin;       ///< the Origin header ("" when absent)
  std::string fetchSite;    ///< the Sec-Fetch-Site header ("" when absent)
  std::string queryToken;   ///< ?token=
  std::string headerToken;  ///< X-Dform-Token
  std::string cookie;       ///< the Cookie header
};

/// Why a request is refused ("" when it may be served).
std::string refusal(const RequestFacts& request, int port, const std::string& token);

/// The name of the cookie that carries the token for the studio on `port`.
std::string tokenCookieName(int port);

/// A random token: 32 hexadecimal digits from the system's random device.
std::string randomToken();

/// A file name as the studio saves an upload under: its last path component with every
/// character but letters, digits, '.', '-' and '_' replaced by '-', at most 80 characters, with
/// one of `extensions` (else `fallback`).
std::string safeFileName(const std::string& name, const std::vector<std::string>& extensions,
                         const std::string& fallback);

}  // namespace dform::studio
