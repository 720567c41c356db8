// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/io/model_files.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <utility>

#include "dform/core/atomic_file.h"
#include "dform/core/file_hash.h"
#include "dform/core/input_file.h"
#include "io_util.h"
#include "obj_format.h"

namespace dform {
namespace {

using io_detail::exactDecimal;

std::string joinPath(const std::string& dir, const char* name) {
  return (std::filesystem::path(dir) / name).string();
}

// The groups that name what an `l` polyline is. A file from before free boundaries and creases has
// one ungrouped `l`: the seam.
constexpr const char* kSeamGroup = "seam";
constexpr const char* kBoundaryGroup = "boundary";
constexpr const char* kCreaseGroup = "crease";

std::string polylineText(const std::vector<int>& indices) {
  std::string text = "l";
  for (int i : indices) text += " " + std::to_string(i + 1);
  return text + "\n";
}

/// One piece's mesh with its seam, free boundaries and creases, as OBJ text. Coordinates are
/// written with the shortest decimal form that reads back to the same double, so a round trip is
/// exact. Closed loops (seam, boundaries) do not repeat their first index.
std::string objText(const Piece& piece, const Eigen::MatrixXd& V, const std::string& layout) {
  assert(V.cols() == 2 || V.cols() == 3);
  std::string text = "# dform piece " + piece.name + ", " + layout +
                     " (mm): vertices, faces, then polylines grouped as seam, free boundary "
                     "loops and creases\n";
  text.reserve(text.size() + std::size_t(V.rows()) * 60 + std::size_t(piece.F.rows()) * 24);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    text += "v " + exactDecimal(V(i, 0)) + " " + exactDecimal(V(i, 1)) + " " +
            (V.cols() == 3 ? exactDecimal(V(i, 2)) : std::string("0")) + "\n";
  }
  for (Eigen::Index f = 0; f < piece.F.rows(); ++f)
    text += "f " + std::to_string(piece.F(f, 0) + 1) + " " + std::to_string(piece.F(f, 1) + 1) +
            " " + std::to_string(piece.F(f, 2) + 1) + "\n";
  text += std::string("g ") + kSeamGroup + "\n" + polylineText(piece.seam);
  for (const auto& [group, lines] : {std::pair{kBoundaryGroup, &piece.freeBoundaries},
                                     std::pair{kCreaseGroup, &piece.creases}}) {
    if (!lines->empty()) text += std::string("g ") + group + "\n";
    for (const std::vector<int>& line : *lines) text += polylineText(line);
  }
  return text;
}

/// The polylines and the triangles of one OBJ file, checked for shape.
struct PieceFile {
  std::string path;
  std::string sha256;  // of the bytes parsed
  io_detail::ObjData obj;
  Faces F;
  std::vector<int> seam;
  std::vector<std::vector<int>> freeBoundaries;
  std::vector<std::vector<int>> creases;
};

Result<PieceFile> readPieceFile(const std::string& path) {
  auto fail = [&](const std::string& what) {
    return Status{ErrorCode::InputInvalid, path + ": " + what};
  };
  const Result<std::string> text = readInputFile(path);
  if (!text.isOk()) return text.status();
  Result<io_detail::ObjData> parsed = io_detail::parseObj(path, text.value());
  if (!parsed.isOk()) return parsed.status();
  PieceFile file{path, sha256Hex(text.value()), std::move(parsed).value(), {}, {}, {}, {}};
  const io_detail::ObjData& obj = file.obj;
  for (std::size_t i = 0; i < obj.vertices.size(); ++i)
    if (!obj.vertices[i].allFinite())
      return fail("vertex " + std::to_string(i + 1) +
                  " has a coordinate that is not a finite number");
  if (obj.faces.empty()) return fail("has no faces");
  std::vector<std::vector<int>> seams;
  for (const io_detail::ObjElement& line : obj.lines) {
    std::vector<int> indices = line.indices;
    const bool closed = line.group != kCreaseGroup;
    // Loops may repeat their first index at the end; tolerate it.
    if (closed && indices.size() > 1 && indices.front() == indices.back()) indices.pop_back();
    if (line.group.empty() || line.group == kSeamGroup)
      seams.push_back(std::move(indices));
    else if (line.group == kBoundaryGroup)
      file.freeBoundaries.push_back(std::move(indices));
    else if (line.group == kCreaseGroup)
      file.creases.push_back(std::move(indices));
    else
      return fail("line " + std::to_string(line.lineNumber) + ": a polyline in group '" +
                  line.group + "'; expected group seam, boundary or crease");
  }
  if (seams.size() != 1)
    return fail("has " + std::to_string(seams.size()) +
                " seam polylines ('l' elements); expected one");
  file.seam = std::move(seams.front());
  if (file.seam.size() < 3) return fail("the seam has fewer than 3 vertices");
  for (std::size_t k = 0; k < file.freeBoundaries.size(); ++k)
    if (file.freeBoundaries[k].size() < 3)
      return fail("free boundary " + std::to_string(k + 1) + " has fewer than 3 vertices");
  file.F.resize(Eigen::Index(obj.faces.size()), 3);
  for (std::size_t f = 0; f < obj.faces.size(); ++f) {
    if (obj.faces[f].indices.size() != 3)
      return fail("line " + std::to_string(obj.faces[f].lineNumber) + ": face has " +
                  std::to_string(obj.faces[f].indices.size()) + " vertices; expected a triangle");
    for (int k = 0; k < 3; ++k) file.F(Eigen::Index(f), k) = obj.faces[f].indices[std::size_t(k)];
  }
  return file;
}

/// Checks that each free boundary is a boundary loop of the mesh with the piece on its left, and
/// that each crease runs along interior mesh edges from boundary to boundary.
Status checkLoopsAndCreases(const PieceFile& file) {
  auto fail = [&](const std::string& what) {
    return Status{ErrorCode::InputInvalid, file.path + ": " + what};
  };
  if (file.freeBoundaries.empty() && file.creases.empty()) return Status::ok();
  // (u, v) for each face that runs from u to v, as u * 2^32 + v, sorted.
  const auto key = [](int u, int v) {
    return (std::uint64_t(std::uint32_t(u)) << 32) | std::uint32_t(v);
  };
  std::vector<std::uint64_t> halfEdges;
  halfEdges.reserve(std::size_t(3 * file.F.rows()));
  for (Eigen::Index f = 0; f < file.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) halfEdges.push_back(key(file.F(f, k), file.F(f, (k + 1) % 3)));
  std::sort(halfEdges.begin(), halfEdges.end());
  auto has = [&](int u, int v) {
    return std::binary_search(halfEdges.begin(), halfEdges.end(), key(u, v));
  };
  auto pair = [](int u, int v) { return std::to_string(u + 1) + " and " + std::to_string(v + 1); };
  for (std::size_t k = 0; k < file.freeBoundaries.size(); ++k) {
    const std::vector<int>& loop = file.freeBoundaries[k];
    const std::string name = "free boundary " + std::to_string(k + 1);
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const int u = loop[i], v = loop[(i + 1) % loop.size()];
      if (!has(u, v) && !has(v, u))
        return fail(name + " is not along mesh edges: vertices " + pair(u, v) + " share no edge");
      if (has(u, v) && has(v, u))
        return fail(name + " is not a boundary: the edge between vertices " + pair(u, v) +
                    " has triangles on both sides");
      if (!has(u, v))
        return fail(name + " runs the wrong way: the piece must lie on its left (vertices " +
                    pair(u, v) + ")");
    }
  }
  std::vector<bool> onBoundary(file.obj.vertices.size(), false);
  for (const std::uint64_t e : halfEdges) {
    const int u = int(e >> 32), v = int(e & 0xFFFFFFFFu);
    if (!has(v, u)) onBoundary[std::size_t(u)] = onBoundary[std::size_t(v)] = true;
  }
  for (std::size_t k = 0; k < file.creases.size(); ++k) {
    const std::vector<int>& line = file.creases[k];
    const std::string name = "crease " + std::to_string(k + 1);
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      const int u = line[i], v = line[i + 1];
      if (!has(u, v) && !has(v, u))
        return fail(name + " is not along mesh edges: vertices " + pair(u, v) + " share no edge");
      if (!has(u, v) || !has(v, u))
        return fail(name + " runs along the boundary between vertices " + pair(u, v));
    }
    for (int end : {line.front(), line.back()})
      if (!onBoundary[std::size_t(end)])
        return fail(name + " ends at vertex " + std::to_string(end + 1) +
                    ", which is not on the boundary (a crease runs from boundary to boundary)");
  }
  return Status::ok();
}

Result<Piece> readPiece(const std::string& dir, const char* flatName, const char* shapeName,
                        const std::string& name, FileHashes* hashes) {
  const Result<PieceFile> flat = readPieceFile(joinPath(dir, flatName));
  if (!flat.isOk()) return flat.status();
  const Result<PieceFile> shape = readPieceFile(joinPath(dir, shapeName));
  if (!shape.isOk()) return shape.status();
  if (hashes) {
    (*hashes)[flatName] = flat.value().sha256;
    (*hashes)[shapeName] = shape.value().sha256;
  }
  const PieceFile& a = flat.value();
  const PieceFile& b = shape.value();
  auto mismatch = [&](const std::string& what) {
    return Status{ErrorCode::InputInvalid, b.path + ": " + what + " than " + a.path};
  };
  if (a.obj.vertices.size() != b.obj.vertices.size())
    return mismatch("has a different number of vertices");
  if (a.F != b.F) return mismatch("has different faces");
  if (a.seam != b.seam) return mismatch("has a different seam");
  if (a.freeBoundaries != b.freeBoundaries) return mismatch("has different free boundaries");
  if (a.creases != b.creases) return mismatch("has different creases");
  if (Status s = checkLoopsAndCreases(a); !s.isOk()) return s;

  Piece piece;
  piece.name = name;
  const Eigen::Index n = Eigen::Index(a.obj.vertices.size());
  piece.flat.resize(n, 2);
  piece.shape.resize(n, 3);
  double extent = 1.0;
  for (Eigen::Index i = 0; i < n; ++i)
    extent = std::max(extent, a.obj.vertices[std::size_t(i)].head<2>().cwiseAbs().maxCoeff());
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d& v = a.obj.vertices[std::size_t(i)];
    // The flat layout is written with z = 0; allow rounding from other tools, relative to size.
    if (std::abs(v.z()) > 1e-9 * extent)
      return Status{ErrorCode::InputInvalid, a.path + ": is not flat (vertex " +
                                                 std::to_string(i + 1) +
                                                 " has z = " + io_detail::fmt(v.z()) + ")"};
    piece.flat.row(i) = v.head<2>().transpose();
    piece.shape.row(i) = b.obj.vertices[std::size_t(i)].transpose();
  }
  piece.F = a.F;
  piece.seam = a.seam;
  piece.freeBoundaries = a.freeBoundaries;
  piece.creases = a.creases;
  return piece;
}

}  // namespace

Status writeObj(const std::string& path, const Piece& piece, PieceForm form, std::string* sha256) {
  assert(piece.flat.rows() == piece.shape.rows() && "flat and 3D vertex counts differ");
  const std::string text = form == PieceForm::Flat ? objText(piece, piece.flat, "flat layout")
                                                   : objText(piece, piece.shape, "3D shape");
  if (sha256) *sha256 = sha256Hex(text);
  return writeFileAtomically(path, text);
}

Status writeModel(const std::string& dir, const DForm& model, FileHashes* hashes) {
  struct Output {
    const char* name;
    const Piece& piece;
    PieceForm form;
  };
  const Output outputs[] = {{ModelFileNames::aFlat, model.a, PieceForm::Flat},
                            {ModelFileNames::a3d, model.a, PieceForm::Shape3D},
                            {ModelFileNames::bFlat, model.b, PieceForm::Flat},
                            {ModelFileNames::b3d, model.b, PieceForm::Shape3D}};
  for (const Output& out : outputs) {
    std::string sha256;
    const Status written = writeObj(joinPath(dir, out.name), out.piece, out.form, &sha256);
    if (hashes) (*hashes)[out.name] = sha256;
    if (!written.isOk()) return written;
  }
  return Status::ok();
}

Status writeTargetCurve(const std::string& dir, const Curve3& curve, FileHashes* hashes) {
  std::string text = "# dform target seam curve (mm), closed polyline\n";
  for (Eigen::Index i = 0; i < curve.points.rows(); ++i)
    text += "v " + exactDecimal(curve.points(i, 0)) + " " + exactDecimal(curve.points(i, 1)) + " " +
            exactDecimal(curve.points(i, 2)) + "\n";
  text += "l";
  for (Eigen::Index i = 0; i < curve.points.rows(); ++i) text += " " + std::to_string(i + 1);
  text += " 1\n";
  if (hashes) (*hashes)[ModelFileNames::targetCurve] = sha256Hex(text);
  return writeFileAtomically(joinPath(dir, ModelFileNames::targetCurve), text);
}

Result<DForm> readModel(const std::string& dir, FileHashes* hashes) {
  Result<Piece> a = readPiece(dir, ModelFileNames::aFlat, ModelFileNames::a3d, "A", hashes);
  if (!a.isOk()) return a.status();
  Result<Piece> b = readPiece(dir, ModelFileNames::bFlat, ModelFileNames::b3d, "B", hashes);
  if (!b.isOk()) return b.status();
  if (a.value().seam.size() != b.value().seam.size())
    return Status{ErrorCode::InputInvalid, joinPath(dir, ModelFileNames::bFlat) + ": seam has " +
                                               std::to_string(b.value().seam.size()) +
                                               " vertices but piece A's has " +
                                               std::to_string(a.value().seam.size())};
  return DForm{std::move(a).value(), std::move(b).value()};
}

}  // namespace dform
