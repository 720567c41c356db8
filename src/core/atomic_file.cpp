#include "dform/core/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace dform {

Status writeFileAtomically(const std::string& path, const std::string& content) {
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) {
      return {ErrorCode::OutputFailed, path + ": cannot write (" + std::strerror(errno) + ")"};
    }
    out.write(content.data(), std::streamsize(content.size()));
    out.flush();
    if (!out) {
      std::remove(temporary.c_str());
      return {ErrorCode::OutputFailed, path + ": write failed (disk full?)"};
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temporary.c_str());
    return {ErrorCode::OutputFailed, path + ": cannot rename into place (" + reason + ")"};
  }
  return Status::ok();
}

}  // namespace dform
