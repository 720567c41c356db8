// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: a small Wavefront OBJ reader for what dform exchanges (vertices, faces, polylines),
// shared by the seam-curve reader and the result-model reader.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "dform/core/status.h"

namespace dform::io_detail {

/// An `f` or `l` element: 0-based vertex indices, the line it was read from and the group it is
/// in (the first name of the last `g` statement before it; "" before any, or after a bare `g`).
struct ObjElement {
  std::vector<int> indices;
  int lineNumber = 0;
  std::string group;
};

struct ObjData {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<ObjElement> faces;
  std::vector<ObjElement> lines;
};

/// Parses `v`, `f`, `l` and `g` statements; other statements (vn, vt, o, usemtl, ...) are ignored.
/// Indices follow the OBJ spec: 1-based, negative ones count back from the last vertex defined
/// so far, `i/t/n` forms use the vertex index. A malformed statement or an index out of range is
/// InputUnreadable naming `path` and the line number. More than `maxVertices` vertices, or an
/// element with more than maxVertices + 1 indices (a closed polyline repeats its first), is
/// InputInvalid, reported at the line where the limit is passed.
Result<ObjData> parseObj(const std::string& path, const std::string& text,
                         std::size_t maxVertices = std::size_t(-1));

}  // namespace dform::io_detail
