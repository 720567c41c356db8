// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/inverse/pre_dform.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_set>
#include <utility>

#include "dform/core/polyline.h"
#include "dform/meshing/convex_hull.h"
#include "dform/meshing/triangulate.h"
#include "unfold.h"

namespace dform {
namespace {

using Vec3 = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

Status invalid(std::string message) { return {ErrorCode::InputInvalid, std::move(message)}; }

// Curve points are numbered from 1 in messages, as the readers number file points.
std::string pointName(int i) { return std::to_string(i + 1); }

// "3-7, 12, 40-44": ascending indices as 1-based runs.
std::string describeRuns(const std::vector<int>& indices) {
  std::string out;
  for (std::size_t s = 0; s < indices.size();) {
    std::size_t e = s;
    while (e + 1 < indices.size() && indices[e + 1] == indices[e] + 1) ++e;
    if (!out.empty()) out += ", ";
    out += pointName(indices[s]);
    if (e > s) out += "-" + pointName(indices[e]);
    s = e + 1;
  }
  return out;
}

double orient(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (b - a).cross(c - a).dot(d - a);
}

// The convex hull's facets: hull faces in one plane (up to rounding) merged, since CGAL splits a
// facet into triangles arbitrarily and the split changes when the curve is rotated. A triangle on
// three curve points lies on the hull exactly when its corners share a facet. Its "curve
// orientation" is (i, k, j) for i < k < j: the order in which a disc bounded by the curve run
// forwards uses it. Facing out in that orientation, it can belong to the disc on the left of the
// curve seen from outside (disc A); facing in, to disc B. So every hull triangle has a side
// without tracing the curve on the hull.
class HullFacets {
 public:
  HullFacets(const Points3& C, const Faces& hullF) : C_(C), facetsOf_(std::size_t(C.rows())) {
    const Eigen::Index nH = hullF.rows();
    const double diagonal = (C.colwise().maxCoeff() - C.colwise().minCoeff()).norm();
    // Rounding-level coplanarity, as the hull's own flatness test (1e-9 of the size): real
    // neighbouring facets of a sampled smooth curve are bent far more.
    const double coplanar = 1e-9 * diagonal;
    std::map<std::pair<int, int>, std::vector<int>> facesOfEdge;
    std::vector<Vec3> faceNormal(static_cast<std::size_t>(nH), Vec3::Zero());
    for (Eigen::Index f = 0; f < nH; ++f) {
      const Vec3 a = C.row(hullF(f, 0)), b = C.row(hullF(f, 1)), c = C.row(hullF(f, 2));
      faceNormal[std::size_t(f)] = (b - a).cross(c - a).normalized();
      for (int e = 0; e < 3; ++e) {
        const int u = hullF(f, e), v = hullF(f, (e + 1) % 3);
        facesOfEdge[{std::min(u, v), std::max(u, v)}].push_back(int(f));
      }
    }
    std::vector<int> facetOfFace(static_cast<std::size_t>(nH), -1);
    for (Eigen::Index seed = 0; seed < nH; ++seed) {
      if (facetOfFace[std::size_t(seed)] >= 0) continue;
      const int facet = int(normal_.size());
      const Vec3 n = faceNormal[std::size_t(seed)];
      const double offset = n.dot(Vec3(C.row(hullF(seed, 0))));
      normal_.push_back(n);
      member_.emplace_back(std::size_t(C.rows()), 0);
      std::vector<int> stack{int(seed)};
      facetOfFace[std::size_t(seed)] = facet;
      while (!stack.empty()) {
        const int f = stack.back();
        stack.pop_back();
        for (int e = 0; e < 3; ++e) {
          const int u = hullF(f, e), v = hullF(f, (e + 1) % 3);
          member_.back()[std::size_t(u)] = 1;
          for (int g : facesOfEdge[{std::min(u, v), std::max(u, v)}]) {
            if (facetOfFace[std::size_t(g)] >= 0 || faceNormal[std::size_t(g)].dot(n) <= 0.0)
              continue;
            bool inPlane = true;
            for (int c = 0; c < 3; ++c)
              inPlane = inPlane && std::abs(n.dot(Vec3(C.row(hullF(g, c)))) - offset) <= coplanar;
            if (!inPlane) continue;
            facetOfFace[std::size_t(g)] = facet;
            stack.push_back(g);
          }
        }
      }
      for (Eigen::Index i = 0; i < C.rows(); ++i)
        if (member_.back()[std::size_t(i)]) facetsOf_[std::size_t(i)].push_back(facet);
    }
  }

  /// +1 when triangle (i, k, j) (i < k < j) lies on a hull facet facing out in curve
  /// orientation, -1 facing in, 0 when it is not on the hull.
  int side(int i, int k, int j) const {
    for (int facet : facetsOf_[std::size_t(i)]) {
      const std::vector<char>& in = member_[std::size_t(facet)];
      if (!in[std::size_t(k)] || !in[std::size_t(j)]) continue;
      const Vec3 a = C_.row(i);
      const double facing =
          (Vec3(C_.row(k)) - a).cross(Vec3(C_.row(j)) - a).dot(normal_[std::size_t(facet)]);
      return facing > 0.0 ? 1 : facing < 0.0 ? -1 : 0;
    }
    return 0;
  }

  int facetCount() const { return int(normal_.size()); }

 private:
  const Points3& C_;
  std::vector<std::vector<int>> facetsOf_;  // per curve point: the facets it is a corner of
  std::vector<std::vector<char>> member_;   // per facet, per curve point: is it a corner
  std::vector<Vec3> normal_;                // per facet: outward unit normal
};

// One number per triangle on curve points i < k < j.
long long triangleKey(int n, int i, int k, int j) {
  return (static_cast<long long>(i) * n + k) * n + j;
}

struct DiscCosts {
  const Points3* C = nullptr;
  const HullFacets* hull = nullptr;
  double areaScale = 1.0;  // the hull's surface area: filled area is measured in it
  double foldWeight = 1.0;
  double degeneratePenalty =
      1.0;  // dwarfs every other cost: a degenerate triangle is a last resort
  const std::unordered_set<long long>* banned = nullptr;  // triangles found crossing: as degenerate
};

// Rounding-level collinearity: a triangle whose height is below this fraction of its longest
// edge has no usable normal (a few hundred ulps of the coordinates, far below any real sliver).
constexpr double kDegenerateHeight = 1e-9;

bool degenerate(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return (b - a).cross(c - a).norm() <= kDegenerateHeight * longest * longest;
}

// One disc as a minimum-weight triangulation of the polygon C (interval dynamic programming, as
// in hole filling). Triangle (i, k, j), i < k < j, is free when it is a hull face of this side;
// any other costs its area over the hull's area. Every interior edge with a filled triangle on
// it costs foldWeight * ((1 - n1.n2) / 2)^2: 0 for a flat continuation, foldWeight for a fold
// straight back. The fold is measured against the best triangle found for the sub-polygon, the
// usual O(n^3) approximation. Chords in `forbidden` (n x n, i < j) may not be used.
struct DiscSolution {
  double cost = kInf;
  std::vector<std::array<int, 3>> triangles;  // (i, k, j), i < k < j
};

DiscSolution solveDisc(const DiscCosts& costs, int side, const std::vector<char>& forbidden) {
  const Points3& C = *costs.C;
  const int n = int(C.rows());
  std::vector<double> W(std::size_t(n) * std::size_t(n), 0.0);
  std::vector<int> apex(std::size_t(n) * std::size_t(n), -1);
  std::vector<Vec3> normal(std::size_t(n) * std::size_t(n), Vec3::Zero());
  std::vector<char> free(std::size_t(n) * std::size_t(n), 0);
  auto at = [n](int i, int j) { return std::size_t(i) * std::size_t(n) + std::size_t(j); };
  auto fold = [&](const Vec3& n1, bool free1, int i, int j) {
    if (j - i < 2) return 0.0;  // a curve edge: its other side belongs to the other disc
    if (free1 && free[at(i, j)]) return 0.0;
    const double bend = 0.5 * (1.0 - n1.dot(normal[at(i, j)]));
    return costs.foldWeight * bend * bend;
  };
  for (int length = 2; length < n; ++length) {
    for (int i = 0; i + length < n; ++i) {
      const int j = i + length;
      const std::size_t ij = at(i, j);
      W[ij] = kInf;
      if (forbidden[ij]) continue;
      const Vec3 a = C.row(i), c = C.row(j);
      for (int k = i + 1; k < j; ++k) {
        const double sub = W[at(i, k)] + W[at(k, j)];
        if (!(sub < W[ij])) continue;
        const Vec3 b = C.row(k);
        const Vec3 cross = (b - a).cross(c - a);
        // A hull sliver (exactly convex, geometrically flat) is degenerate like any other.
        const bool flat = degenerate(a, b, c);
        const bool isFree = !flat && costs.hull->side(i, k, j) == side;
        const double area = 0.5 * cross.norm();
        const Vec3 unit = flat ? Vec3::Zero() : Vec3(cross / (2.0 * area));
        double total = sub;
        if (!isFree) total += area / costs.areaScale + (flat ? costs.degeneratePenalty : 0.0);
        if (!costs.banned->empty() && costs.banned->count(triangleKey(n, i, k, j)))
          total += costs.degeneratePenalty;
        total += fold(unit, isFree, i, k) + fold(unit, isFree, k, j);
        if (total < W[ij]) {
          W[ij] = total;
          apex[ij] = k;
          normal[ij] = unit;
          free[ij] = isFree;
        }
      }
    }
  }
  DiscSolution out;
  out.cost = W[at(0, n - 1)];
  if (!(out.cost < kInf)) return out;
  std::vector<std::pair<int, int>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const int k = apex[at(i, j)];
    out.triangles.push_back({i, k, j});
    stack.emplace_back(i, k);
    stack.emplace_back(k, j);
  }
  return out;
}

std::vector<char> chordsOf(const DiscSolution& disc, int n) {
  std::vector<char> chords(std::size_t(n) * std::size_t(n), 0);
  for (const auto& t : disc.triangles) {
    const std::array<std::pair<int, int>, 3> edges{{{t[0], t[1]}, {t[1], t[2]}, {t[0], t[2]}}};
    for (const auto& [u, v] : edges)
      if (v - u >= 2 && !(u == 0 && v == n - 1))
        chords[std::size_t(u) * std::size_t(n) + std::size_t(v)] = 1;
  }
  return chords;
}

// Whether segment pq crosses triangle abc at a point strictly inside both; touching (within
// `tol`, a volume) does not count.
bool segmentCrossesTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                            const Vec3& c, double tol) {
  const double sp = orient(a, b, c, p), sq = orient(a, b, c, q);
  if (!((sp > tol && sq < -tol) || (sp < -tol && sq > tol))) return false;
  const double t1 = orient(p, q, a, b), t2 = orient(p, q, b, c), t3 = orient(p, q, c, a);
  return (t1 > tol && t2 > tol && t3 > tol) || (t1 < -tol && t2 < -tol && t3 < -tol);
}

// The pairs of triangles of F (on the rows of V) that cross each other: a shared edge with both
// triangles folded flat onto the same side, or a crossing away from shared corners. O(#F^2) with
// a bounding-box test, about 1 ms for #F = 200.
std::vector<std::pair<int, int>> findCrossingTriangles(const Points3& V, const Faces& F) {
  std::vector<std::pair<int, int>> out;
  const Eigen::Index nF = F.rows();
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  // Orientation volumes of real crossings are ~(edge length)^2 * diagonal; rounding noise is
  // ~1e-16 diagonal^3. 1e-13 diagonal^3 ignores touching yet keeps crossings of edges 1e-5 long.
  const double tol = 1e-13 * diagonal * diagonal * diagonal;
  std::vector<Eigen::AlignedBox3d> box(static_cast<std::size_t>(nF), Eigen::AlignedBox3d());
  for (Eigen::Index f = 0; f < nF; ++f)
    for (int c = 0; c < 3; ++c) box[std::size_t(f)].extend(Vec3(V.row(F(f, c))));
  for (Eigen::Index f = 0; f < nF; ++f) {
    for (Eigen::Index g = f + 1; g < nF; ++g) {
      if (!box[std::size_t(f)].intersects(box[std::size_t(g)])) continue;
      std::array<int, 3> tf{F(f, 0), F(f, 1), F(f, 2)}, tg{F(g, 0), F(g, 1), F(g, 2)};
      std::array<int, 3> of{};  // shared corners
      int shared = 0, restF = 0, restG = 0;
      std::array<int, 3> otherF{}, otherG{};
      for (int x : tf) {
        if (std::find(tg.begin(), tg.end(), x) != tg.end())
          of[std::size_t(shared++)] = x;
        else
          otherF[std::size_t(restF++)] = x;
      }
      for (int x : tg)
        if (std::find(tf.begin(), tf.end(), x) == tf.end()) otherG[std::size_t(restG++)] = x;
      auto P = [&](int i) { return Vec3(V.row(i)); };
      bool crossing = false;
      if (shared == 2) {
        const Vec3 u = P(of[0]), v = P(of[1]), a = P(otherF[0]), b = P(otherG[0]);
        const Vec3 na = (v - u).cross(a - u), nb = (v - u).cross(b - u);
        crossing =
            std::abs(orient(u, v, a, b)) <= 1e-12 * na.norm() * (b - u).norm() && na.dot(nb) > 0.0;
      } else if (shared == 1) {
        const Vec3 v = P(of[0]);
        crossing =
            segmentCrossesTriangle(P(otherF[0]), P(otherF[1]), v, P(otherG[0]), P(otherG[1]),
                                   tol) ||
            segmentCrossesTriangle(P(otherG[0]), P(otherG[1]), v, P(otherF[0]), P(otherF[1]), tol);
      } else if (shared == 0) {
        for (int e = 0; e < 3 && !crossing; ++e) {
          crossing = segmentCrossesTriangle(P(tf[std::size_t(e)]), P(tf[std::size_t((e + 1) % 3)]),
                                            P(tg[0]), P(tg[1]), P(tg[2]), tol) ||
                     segmentCrossesTriangle(P(tg[std::size_t(e)]), P(tg[std::size_t((e + 1) % 3)]),
                                            P(tf[0]), P(tf[1]), P(tf[2]), tol);
        }
      }
      if (crossing) out.emplace_back(int(f), int(g));
    }
  }
  return out;
}

std::string triangleName(const Faces& F, int f) {
  std::array<int, 3> t{F(f, 0), F(f, 1), F(f, 2)};
  std::sort(t.begin(), t.end());
  return pointName(t[0]) + ", " + pointName(t[1]) + ", " + pointName(t[2]);
}

Status prefixed(const Status& status, const std::string& source) {
  if (status.isOk() || source.empty()) return status;
  return {status.code(), source + ": " + status.message()};
}

}  // namespace

Result<PreDForm> buildPreDForm(const Points3& C, const InverseInitOptions& options) {
  const int n = int(C.rows());
  if (n < 4)
    return invalid("the curve needs at least 4 points to enclose a volume; it has " +
                   std::to_string(n));
  if (!C.allFinite()) return invalid("the curve has a non-finite coordinate");
  const double diagonal = (C.colwise().maxCoeff() - C.colwise().minCoeff()).norm();
  // Points closer than the hull's flatness tolerance (1e-9 of the size) are the same point.
  const double samePoint = 1e-9 * diagonal;
  for (int i = 0; i < n; ++i)
    if ((C.row((i + 1) % n) - C.row(i)).norm() <= samePoint)
      return invalid("the curve has a zero-length edge between points " + pointName(i) + " and " +
                     pointName((i + 1) % n));
  for (int i = 0; i < n; ++i)
    for (int j = i + 2; j < n; ++j)
      if (!(i == 0 && j == n - 1) && (C.row(j) - C.row(i)).norm() <= samePoint)
        return invalid("the curve touches itself: points " + pointName(i) + " and " + pointName(j) +
                       " coincide");

  Result<ConvexHull3> hullResult = convexHull3(C);
  if (!hullResult.isOk()) return hullResult.status();
  const ConvexHull3& hull = hullResult.value();

  PreDForm pre;
  for (int i = 0; i < n; ++i)
    if (!hull.onHull[std::size_t(i)]) pre.insideVertices.push_back(i);
  pre.onHull = pre.insideVertices.empty();

  const HullFacets facets(C, hull.F);
  DiscCosts costs;
  costs.C = &C;
  costs.hull = &facets;
  costs.areaScale = 0.0;
  for (Eigen::Index f = 0; f < hull.F.rows(); ++f) {
    const Vec3 a = C.row(hull.F(f, 0)), b = C.row(hull.F(f, 1)), c = C.row(hull.F(f, 2));
    costs.areaScale += 0.5 * (b - a).cross(c - a).norm();
  }
  costs.foldWeight = std::max(0.0, options.foldWeight);
  // Filled area totals at most a few hull areas and each of the 2n - 6 chords folds at most
  // foldWeight: one degenerate triangle must outweigh any combination of them.
  costs.degeneratePenalty = 1e3 * (1.0 + costs.foldWeight) * n;

  // Whether a triangle of the pre-D-Form (as oriented there) is a hull triangle facing out.
  auto onHullSurface = [&facets](const Eigen::RowVector3i& row) {
    std::array<int, 3> t{row(0), row(1), row(2)};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    const int side = facets.side(t[0], std::min(t[1], t[2]), std::max(t[1], t[2]));
    return side != 0 && (side == 1) == (t[1] < t[2]);
  };
  auto sortedKey = [n](const Eigen::RowVector3i& row) {
    std::array<int, 3> t{row(0), row(1), row(2)};
    std::sort(t.begin(), t.end());
    return triangleKey(n, t[0], t[1], t[2]);
  };
  auto toFaces = [](const DiscSolution& disc, bool forwards) {
    Faces F(Eigen::Index(disc.triangles.size()), 3);
    for (std::size_t t = 0; t < disc.triangles.size(); ++t) {
      const auto& [i, k, j] = disc.triangles[t];
      F.row(Eigen::Index(t)) = forwards ? Eigen::RowVector3i(i, k, j) : Eigen::RowVector3i(i, j, k);
    }
    return F;
  };

  // Filled triangles found crossing another triangle are banned (cost as degenerate) and both
  // discs solved again, a few rounds at most: the two discs are solved one after the other, so
  // one's filling can pierce the other's.
  std::unordered_set<long long> banned;
  costs.banned = &banned;
  const int repairRounds = 8;
  const std::vector<char> none(std::size_t(n) * std::size_t(n), 0);
  Faces all;
  std::vector<std::pair<int, int>> crossings;
  for (int round = 0;; ++round) {
    // The second disc may not reuse a chord of the first (the surface would pinch along it).
    // Both orders are solved and the cheaper pair kept, so neither side is favoured.
    DiscSolution bestA, bestB;
    double bestCost = kInf;
    for (int first : {1, -1}) {
      if (bestCost == 0.0) break;  // the hull itself: nothing can be cheaper
      const DiscSolution one = solveDisc(costs, first, none);
      if (!(one.cost < kInf)) continue;
      const DiscSolution two = solveDisc(costs, -first, chordsOf(one, n));
      if (!(one.cost + two.cost < bestCost)) continue;
      bestCost = one.cost + two.cost;
      bestA = first == 1 ? one : two;
      bestB = first == 1 ? two : one;
    }
    if (!(bestCost < kInf))
      return invalid(
          "the curve cannot be split into two discs: no two triangulations of it share only the "
          "curve");

    // Disc A's triangles run the curve forwards, disc B's backwards. If that closed surface is
    // inside out (possible only far from the hull), the sides swap.
    pre.discA = toFaces(bestA, true);
    pre.discB = toFaces(bestB, false);
    double volume = 0.0;
    const Vec3 centre = C.colwise().mean();
    for (const Faces* F : {&pre.discA, &pre.discB})
      for (Eigen::Index f = 0; f < F->rows(); ++f)
        volume += orient(centre, C.row((*F)(f, 0)), C.row((*F)(f, 1)), C.row((*F)(f, 2))) / 6.0;
    if (volume < 0.0) {
      pre.discA = toFaces(bestB, true);
      pre.discB = toFaces(bestA, false);
    }
    all.resize(pre.discA.rows() + pre.discB.rows(), 3);
    all << pre.discA, pre.discB;
    if (options.allowSelfIntersection) break;
    crossings = findCrossingTriangles(C, all);
    if (crossings.empty() || round == repairRounds) break;
    const std::size_t before = banned.size();
    for (const auto& [f, g] : crossings)
      for (int t : {f, g})
        if (!onHullSurface(all.row(t))) banned.insert(sortedKey(all.row(t)));
    if (banned.size() == before) break;
  }

  for (Eigen::Index f = 0; f < all.rows(); ++f)
    ++(onHullSurface(all.row(f)) ? pre.hullTriangles : pre.filledTriangles);
  // Two discs of hull triangles with no interior vertex cover the whole hull.
  pre.isHull = pre.onHull && pre.filledTriangles == 0;

  for (Eigen::Index f = 0; f < all.rows(); ++f)
    if (degenerate(C.row(all(f, 0)), C.row(all(f, 1)), C.row(all(f, 2))))
      return invalid(
          "the curve cannot be split into two discs without a degenerate triangle: "
          "curve points " +
          triangleName(all, int(f)) + " are collinear");
  if (!crossings.empty())
    return invalid(
        "the curve cannot be split into two discs: the pre-D-Form built on it crosses "
        "itself (triangles on curve points " +
        triangleName(all, crossings[0].first) + " and " + triangleName(all, crossings[0].second) +
        "); the curve may be knotted or wind around itself");

  const std::string faces = std::to_string(all.rows()) + " triangles";
  if (pre.isHull)
    pre.summary =
        "on-hull curve: the pre-D-Form is its convex hull cut along the curve (" + faces + ")";
  else if (pre.onHull)
    pre.summary = "on-hull curve, but not every curve edge is a hull edge: " +
                  std::to_string(pre.hullTriangles) + " hull triangles kept, " +
                  std::to_string(pre.filledTriangles) + " filled (" + faces + ")";
  else
    pre.summary = "non-on-hull curve: " + std::to_string(pre.insideVertices.size()) + " of " +
                  std::to_string(n) + " points lie inside the convex hull (curve points " +
                  describeRuns(pre.insideVertices) + "); " + std::to_string(pre.hullTriangles) +
                  " hull triangles kept, " + std::to_string(pre.filledTriangles) + " filled";
  return pre;
}

Result<InverseInit> initialiseInverse(const Points3& C, const InverseInitOptions& options) {
  Result<PreDForm> preResult = buildPreDForm(C, options);
  if (!preResult.isOk()) return preResult.status();
  InverseInit init;
  init.pre = std::move(preResult).value();
  const int n = int(C.rows());
  init.preDFormF.resize(init.pre.discA.rows() + init.pre.discB.rows(), 3);
  init.preDFormF << init.pre.discA, init.pre.discB;

  const double meanEdge = closedLength(C) / n;
  TriangulateOptions meshing;
  meshing.targetEdgeLength = std::max(options.edgeLengthFactor, 0.0) * meanEdge;
  meshing.minAngleDegrees = options.minAngleDegrees;

  for (const bool isA : {true, false}) {
    const std::string name = isA ? "A" : "B";
    const Faces& disc = isA ? init.pre.discA : init.pre.discB;
    Result<Points2> unfolded = unfoldDisc(C, disc);
    if (!unfolded.isOk())  // buildPreDForm makes discs without interior vertices
      return Status(ErrorCode::Internal, "piece " + name + ": " + unfolded.status().message());
    const Points2& flat = unfolded.value();
    if (Status sheet = checkSheet(flat, name); !sheet.isOk()) return sheet;

    // Counter-clockwise outline: A runs the curve forwards, B backwards (0, n-1, ..., 1).
    std::vector<int> order(static_cast<std::size_t>(n), 0);
    for (int j = 0; j < n; ++j) order[std::size_t(j)] = isA ? j : (n - j) % n;
    Points2 outline(n, 2);
    for (int j = 0; j < n; ++j) outline.row(j) = flat.row(order[std::size_t(j)]);
    if (!(signedArea(outline) > 0.0))
      return Status(ErrorCode::Internal, "piece " + name + " unfolds clockwise");

    FlatMesh& preFlat = isA ? init.preFlatA : init.preFlatB;
    preFlat.V = flat;
    preFlat.F = disc;
    preFlat.boundary = order;

    Result<FlatMesh> mesh = triangulateDomain(outline, {}, meshing);
    if (!mesh.isOk())
      return Status(mesh.status().code(),
                    "piece " + name + " cannot be meshed: " + mesh.status().message());
    Piece& piece = isA ? init.model.a : init.model.b;
    piece.name = name;
    piece.flat = mesh.value().V;
    piece.F = mesh.value().F;
    piece.shape = mapBarycentric(flat, C, disc, piece.flat);
    // Mesh vertex j < n is outline point j, i.e. curve point order[j].
    piece.seam.assign(std::size_t(n), 0);
    for (int j = 0; j < n; ++j) piece.seam[std::size_t(order[std::size_t(j)])] = j;
  }
  return init;
}

Result<InverseInit> initialiseInverse(const Curve3& curve, const InverseInitOptions& options) {
  Result<InverseInit> init = initialiseInverse(curve.points, options);
  if (!init.isOk()) return prefixed(init.status(), curve.source);
  return init;
}

}  // namespace dform
