// SPDX-License-Identifier: GPL-3.0-or-later
#include "models.h"

#include <Eigen/Geometry>
#include <cassert>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include "dform/meshing/triangulate.h"

namespace dform::test {

namespace {

// Rows of `vertices`, merged when they agree to 1e-9 mm.
struct VertexPool {
  std::map<std::tuple<long long, long long, long long>, int> index;
  std::vector<Eigen::Vector3d> points;
  int add(const Eigen::Vector3d& p) {
    const auto key = std::make_tuple(std::llround(p.x() * 1e9), std::llround(p.y() * 1e9),
                                     std::llround(p.z() * 1e9));
    const auto [it, inserted] = index.emplace(key, int(points.size()));
    if (inserted) points.push_back(p);
    return it->second;
  }
  Points3 matrix() const {
    Points3 V(Eigen::Index(points.size()), 3);
    for (size_t i = 0; i < points.size(); ++i) V.row(Eigen::Index(i)) = points[i];
    return V;
  }
};

// Splits the triangles (p, q, r) into k*k triangles of the same orientation.
void subdivide(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r, int k,
               VertexPool& pool, std::vector<Eigen::Vector3i>& faces) {
  auto at = [&](int i, int j) {
    return pool.add(p + (q - p) * double(i) / k + (r - p) * double(j) / k);
  };
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      faces.emplace_back(at(i, j), at(i + 1, j), at(i, j + 1));
      if (i + j + 1 < k) faces.emplace_back(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
    }
}

Faces toFaces(const std::vector<Eigen::Vector3i>& faces) {
  Faces F(Eigen::Index(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) F.row(Eigen::Index(f)) = faces[f].transpose();
  return F;
}

int nearestRow(const Points3& V, const Eigen::RowVector3d& p) {
  Eigen::Index best;
  (V.rowwise() - p).rowwise().squaredNorm().minCoeff(&best);
  return int(best);
}

}  // namespace

Piece developPiece(const Points3& shape, const Faces& F, const std::string& name, int start) {
  Piece piece;
  piece.name = name;
  piece.shape = shape;
  piece.F = F;
  piece.flat = Points2::Zero(shape.rows(), 2);
  std::vector<bool> placed(size_t(shape.rows()), false);
  auto dist = [&](int i, int j) { return (shape.row(i) - shape.row(j)).norm(); };
  // Puts w on the left of u -> v at its 3D distances from u and v.
  auto place = [&](int u, int v, int w) {
    const Eigen::Vector2d pu = piece.flat.row(u), pv = piece.flat.row(v);
    const double duv = (pv - pu).norm(), duw = dist(u, w), dvw = dist(v, w);
    const Eigen::Vector2d e = (pv - pu) / duv, left(-e.y(), e.x());
    const double x = (duw * duw - dvw * dvw + duv * duv) / (2 * duv);
    piece.flat.row(w) =
        (pu + x * e + std::sqrt(std::max(0.0, duw * duw - x * x)) * left).transpose();
    placed[w] = true;
  };
  placed[F(0, 0)] = placed[F(0, 1)] = true;
  piece.flat.row(F(0, 1)) << dist(F(0, 0), F(0, 1)), 0.0;
  for (bool progress = true; progress;) {
    progress = false;
    for (int f = 0; f < F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        const int u = F(f, k), v = F(f, (k + 1) % 3), w = F(f, (k + 2) % 3);
        if (placed[u] && placed[v] && !placed[w]) place(u, v, w), progress = true;
      }
  }
  // Boundary loop: half-edges whose twin is missing, followed in face orientation.
  std::map<std::pair<int, int>, int> halfEdges;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) halfEdges[{F(f, k), F(f, (k + 1) % 3)}] = f;
  std::map<int, int> next;
  for (const auto& [edge, f] : halfEdges)
    if (!halfEdges.count({edge.second, edge.first})) next[edge.first] = edge.second;
  assert(next.count(start) && "the seam starts on the boundary");
  for (int v = start;;) {
    piece.seam.push_back(v);
    v = next.at(v);
    if (v == start) break;
  }
  return piece;
}

Piece mirroredCopy(const Piece& a, const std::string& name) {
  Piece b = a;
  b.name = name;
  b.flat.col(1) *= -1.0;
  b.F.col(1).swap(b.F.col(2));
  return b;
}

DForm tetraDForm(int k, double size, double h) {
  const Eigen::Vector3d A = size * Eigen::Vector3d(-1, 0, -h), B = size * Eigen::Vector3d(0, -1, h);
  const Eigen::Vector3d C = size * Eigen::Vector3d(1, 0, -h), D = size * Eigen::Vector3d(0, 1, h);
  auto piece = [&](const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                   const Eigen::Vector3d& p3, const std::string& name) {
    VertexPool pool;
    std::vector<Eigen::Vector3i> faces;
    subdivide(p0, p1, p2, k, pool, faces);  // both faces outward-facing, hinge p0-p2
    subdivide(p0, p2, p3, k, pool, faces);
    const Points3 V = pool.matrix();
    return developPiece(V, toFaces(faces), name, nearestRow(V, A.transpose()));
  };
  DForm model;
  model.a = piece(A, D, C, B, "A");
  model.b = piece(B, C, D, A, "B");
  model.b.seam.clear();
  for (int v : model.a.seam)
    model.b.seam.push_back(nearestRow(model.b.shape, model.a.shape.row(v)));
  return model;
}

DForm ribbonDForm(const Ribbon& r) {
  const int m = r.segments;
  Points3 V(2 * (m + 1), 3);
  for (int i = 0; i <= m; ++i) {
    const double t = 2 * M_PI * r.turns * i / m;
    V.row(i) << r.outerR * std::cos(t), r.outerR * std::sin(t), r.outerRise * t;
    V.row(m + 1 + i) << r.innerR * std::cos(t), r.innerR * std::sin(t),
        r.innerLift + r.innerRise * t;
  }
  std::vector<Eigen::Vector3i> fa, fb;
  for (int i = 0; i < m; ++i) {
    const int o0 = i, o1 = i + 1, n0 = m + 1 + i, n1 = m + 2 + i;
    fa.emplace_back(o0, o1, n1), fa.emplace_back(o0, n1, n0);
    fb.emplace_back(o1, o0, n0), fb.emplace_back(o1, n0, n1);  // the other diagonal, facing away
  }
  DForm model;
  model.a = developPiece(V, toFaces(fa), "A", 0);
  model.b = developPiece(V, toFaces(fb), "B", 0);
  model.b.seam = model.a.seam;
  return model;
}

DForm flatDoubleDisc(int rings, int sectors, double r) {
  Points2 P(1 + rings * sectors, 2);
  P.row(0) << 0, 0;
  auto id = [&](int ring, int s) { return 1 + (ring - 1) * sectors + (s % sectors); };
  for (int ring = 1; ring <= rings; ++ring)
    for (int s = 0; s < sectors; ++s) {
      const double t = 2 * M_PI * s / sectors, rho = r * ring / rings;
      P.row(id(ring, s)) << rho * std::cos(t), rho * std::sin(t);
    }
  std::vector<Eigen::Vector3i> faces;
  for (int s = 0; s < sectors; ++s) faces.emplace_back(0, id(1, s), id(1, s + 1));
  for (int ring = 1; ring < rings; ++ring)
    for (int s = 0; s < sectors; ++s) {
      faces.emplace_back(id(ring, s), id(ring + 1, s), id(ring + 1, s + 1));
      faces.emplace_back(id(ring, s), id(ring + 1, s + 1), id(ring, s + 1));
    }
  DForm model;
  model.a.name = "A";
  model.a.flat = P;
  model.a.shape = Points3::Zero(P.rows(), 3);
  model.a.shape.leftCols<2>() = P;
  model.a.F = toFaces(faces);
  for (int s = 0; s < sectors; ++s) model.a.seam.push_back(id(rings, s));
  model.b = mirroredCopy(model.a, "B");
  return model;
}

DForm rolledCylinder(int columns, int rows, double r, double height) {
  const double sweep = 1.5 * M_PI, chord = 2 * r * std::sin(sweep / columns / 2);
  Points2 P((columns + 1) * (rows + 1), 2);
  Points3 V(P.rows(), 3);
  auto id = [&](int j, int i) { return j * (rows + 1) + i; };
  for (int j = 0; j <= columns; ++j)
    for (int i = 0; i <= rows; ++i) {
      const double t = sweep * j / columns, z = height * i / rows;
      P.row(id(j, i)) << chord * j, z;
      V.row(id(j, i)) << r * std::cos(t), r * std::sin(t), z;
    }
  std::vector<Eigen::Vector3i> faces;
  for (int j = 0; j < columns; ++j)
    for (int i = 0; i < rows; ++i) {
      faces.emplace_back(id(j, i), id(j + 1, i), id(j + 1, i + 1));
      faces.emplace_back(id(j, i), id(j + 1, i + 1), id(j, i + 1));
    }
  DForm model;
  model.a = developPiece(V, toFaces(faces), "A", id(0, 0));
  model.a.flat = P;  // the rectangle itself: the development up to a rigid motion
  model.b = mirroredCopy(model.a, "B");
  return model;
}

std::vector<int> verticesOnSegment(const Piece& piece, const Eigen::Vector3d& p,
                                   const Eigen::Vector3d& q) {
  std::vector<std::pair<double, int>> along;
  const Eigen::Vector3d d = (q - p).normalized();
  for (int v = 0; v < piece.shape.rows(); ++v) {
    const Eigen::Vector3d x = piece.shape.row(v).transpose() - p;
    const double t = x.dot(d);
    if ((x - t * d).norm() < 1e-9 && t > -1e-9 && t < (q - p).norm() + 1e-9)
      along.emplace_back(t, v);
  }
  std::sort(along.begin(), along.end());
  std::vector<int> line;
  for (const auto& [t, v] : along) line.push_back(v);
  return line;
}

DForm creasedTetraDForm(int k, double size, double h) {
  DForm model = tetraDForm(k, size, h);
  const Eigen::Vector3d A = size * Eigen::Vector3d(-1, 0, -h), B = size * Eigen::Vector3d(0, -1, h);
  const Eigen::Vector3d C = size * Eigen::Vector3d(1, 0, -h), D = size * Eigen::Vector3d(0, 1, h);
  model.a.creases = {verticesOnSegment(model.a, A, C)};
  model.b.creases = {verticesOnSegment(model.b, B, D)};
  return model;
}

namespace {

Points2 regularPolygon(int sides, double radius, bool clockwise) {
  Points2 P(sides, 2);
  for (int i = 0; i < sides; ++i) {
    const double t = (clockwise ? -2 : 2) * M_PI * i / sides;
    P.row(i) << radius * std::cos(t), radius * std::sin(t);
  }
  return P;
}

}  // namespace

DForm annulusDForm(double R, double r, int sides, double edge, double slopeDeg) {
  TriangulateOptions options;
  options.targetEdgeLength = edge;
  const Result<FlatMesh> mesh =
      triangulateDomain(regularPolygon(sides, R, false), {regularPolygon(sides, r, true)}, options);
  assert(mesh.isOk() && "the annulus meshes");
  const FlatMesh& m = mesh.value();
  const double slope = slopeDeg * M_PI / 180.0;
  DForm model;
  Piece& a = model.a;
  a.name = "A";
  a.flat = m.V;
  a.F = m.F;
  a.shape.resize(m.V.rows(), 3);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const double rho = m.V.row(v).norm(), t = std::atan2(m.V(v, 1), m.V(v, 0));
    const double radius = r + (rho - r) * std::cos(slope);
    a.shape.row(v) << radius * std::cos(t), radius * std::sin(t), (rho - r) * std::sin(slope);
  }
  a.freeBoundaries = {m.boundary};
  for (int i = 0; i < sides; ++i) a.seam.push_back(sides + i);  // the hole, after the outline
  Piece& b = model.b;
  b = mirroredCopy(a, "B");
  b.shape.col(2) *= -1.0;
  b.freeBoundaries = {std::vector<int>(m.boundary.rbegin(), m.boundary.rend())};
  return model;
}

DForm demiDForm(double R, double r, int sides, double edge, double height, double slopeDeg) {
  TriangulateOptions options;
  options.targetEdgeLength = edge;
  const Result<FlatMesh> disc = triangulateDomain(regularPolygon(sides, r, false), {}, options);
  const Result<FlatMesh> ring =
      triangulateDomain(regularPolygon(sides, R, false), {regularPolygon(sides, r, true)}, options);
  assert(disc.isOk() && ring.isOk() && "the disc and the annulus mesh");
  DForm model;
  Piece& a = model.a;
  a.name = "A";
  a.flat = disc.value().V;
  a.F = disc.value().F;
  a.shape.resize(a.flat.rows(), 3);
  for (Eigen::Index v = 0; v < a.flat.rows(); ++v) {
    const double rho = a.flat.row(v).norm() / r;
    a.shape.row(v) << a.flat(v, 0), a.flat(v, 1), height * (1 - rho * rho);
  }
  a.seam = disc.value().boundary;
  Piece& b = model.b;
  b.name = "B";
  b.flat = ring.value().V;
  b.F = ring.value().F;
  b.shape.resize(b.flat.rows(), 3);
  const double slope = slopeDeg * M_PI / 180.0;
  for (Eigen::Index v = 0; v < b.flat.rows(); ++v) {
    const double rho = b.flat.row(v).norm(), t = std::atan2(b.flat(v, 1), b.flat(v, 0));
    const double radius = r + (rho - r) * std::cos(slope);
    b.shape.row(v) << radius * std::cos(t), radius * std::sin(t), -(rho - r) * std::sin(slope);
  }
  // The hole was given clockwise: hole vertex j sits at angle -2 pi j / sides, A's seam vertex i
  // at 2 pi i / sides.
  for (int i = 0; i < sides; ++i) b.seam.push_back(sides + (sides - i) % sides);
  b.freeBoundaries = {ring.value().boundary};
  return model;
}

Piece foldedSquare(int k, double size, const std::vector<GridCrease>& creases,
                   const std::string& name) {
  Piece piece;
  piece.name = name;
  auto id = [&](int i, int j) { return j * (k + 1) + i; };
  piece.flat.resize((k + 1) * (k + 1), 2);
  for (int j = 0; j <= k; ++j)
    for (int i = 0; i <= k; ++i) piece.flat.row(id(i, j)) << size * i / k, size * j / k;
  std::vector<Eigen::Vector3i> faces;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) {
      faces.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      faces.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  piece.F = toFaces(faces);
  piece.shape = Points3::Zero(piece.flat.rows(), 3);
  piece.shape.leftCols<2>() = piece.flat;
  for (int i = 0; i < k; ++i) piece.seam.push_back(id(i, 0));
  for (int j = 0; j < k; ++j) piece.seam.push_back(id(k, j));
  for (int i = k; i > 0; --i) piece.seam.push_back(id(i, k));
  for (int j = k; j > 0; --j) piece.seam.push_back(id(0, j));
  for (const GridCrease& c : creases) {
    const int steps = std::max(std::abs(c.i1 - c.i0), std::abs(c.j1 - c.j0));
    std::vector<int> line;
    for (int s = 0; s <= steps; ++s)
      line.push_back(id(c.i0 + (c.i1 - c.i0) / steps * s, c.j0 + (c.j1 - c.j0) / steps * s));
    piece.creases.push_back(line);
  }
  // The last crease first: each turn carries the creases right of it along.
  for (size_t c = creases.size(); c-- > 0;) {
    const std::vector<int>& line = piece.creases[c];
    const Eigen::Vector2d p0 = piece.flat.row(line.front()),
                          d = piece.flat.row(line.back()) - p0.transpose();
    const Eigen::Vector3d origin = piece.shape.row(line.front());
    const Eigen::Vector3d axis = (piece.shape.row(line.back()).transpose() - origin).normalized();
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(creases[c].angleDeg * M_PI / 180.0, axis).toRotationMatrix();
    for (Eigen::Index v = 0; v < piece.flat.rows(); ++v) {
      const Eigen::Vector2d q = piece.flat.row(v).transpose() - p0;
      if (d.x() * q.y() - d.y() * q.x() < -1e-9 * size * size)  // strictly right of the crease
        piece.shape.row(v) =
            (origin + turn * (piece.shape.row(v).transpose() - origin)).transpose();
    }
  }
  return piece;
}

}  // namespace dform::test
