// SPDX-License-Identifier: GPL-3.0-or-later
// dform studio: a local web application to design a D-Form live (docs/studio.md). An HTTP server
// bound to the loopback interface serves one page (templates/studio/) and a JSON API over the
// pipeline's in-memory entry points; every request must carry the run's random token and a
// loopback Host (and Origin, when the browser sends one).
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "dform/core/status.h"

namespace dform {

/// How the studio serves: its port, the design it starts from, its limits and its token.
struct StudioOptions {
  int port = 0;         ///< TCP port on 127.0.0.1 (and ::1); 0: any free one
  std::string pieceA;   ///< piece A's outline file the first design starts from (empty: built-in)
  std::string pieceB;   ///< piece B's outline file (empty: the built-in ellipses)
  std::string jobFile;  ///< a forward job file to start from instead (its outlines and settings)
  std::size_t maxUploadBytes = std::size_t(8)
                               << 20;  ///< largest request body (an outline, a curve)
  int maxSessions = 32;  ///< browser tabs served at once; the least recently used is dropped
  std::string token;     ///< the run's token; empty: 32 random hexadecimal digits
};

/// A running studio. Requests are served on a pool of threads until stop() (or destruction).
class Studio {
 public:
  /// Reads the starting design (Usage, InputUnreadable or InputInvalid naming the file), binds
  /// the port (OutputFailed when it is taken) and starts serving.
  static Result<std::unique_ptr<Studio>> start(const StudioOptions& options);
  ~Studio();
  Studio(const Studio&) = delete;
  Studio& operator=(const Studio&) = delete;

  int port() const;                  ///< the port it listens on
  const std::string& token() const;  ///< the run's token every request must carry
  /// The page's address with the token: http://127.0.0.1:PORT/?token=TOKEN
  std::string url() const;
  /// Stops serving: open event streams end, running solves are cancelled, threads joined.
  void stop();

  struct Impl;

 private:
  explicit Studio(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace dform
