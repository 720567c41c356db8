// SPDX-License-Identifier: GPL-3.0-or-later
#include "dform/model/terms.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cassert>

#include "dform/core/interrupt.h"

namespace dform {

namespace {

using Triplet = Eigen::Triplet<double>;
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

std::unique_ptr<ResidualTerm> linearTerm(int rows, int cols, const std::vector<Triplet>& entries,
                                         Eigen::VectorXd b) {
  RowSparse M(rows, cols);
  M.setFromTriplets(entries.begin(), entries.end());
  return std::make_unique<LinearResidual>(std::move(M), std::move(b));
}

// Vertices on an edge that only one triangle uses.
std::vector<bool> boundaryMask(int n, const Faces& F) {
  std::vector<bool> onBoundary(n, false);
  std::vector<std::pair<int, int>> directed;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = F(f, k), j = F(f, (k + 1) % 3);
      directed.emplace_back(std::min(i, j), std::max(i, j));
    }
  std::sort(directed.begin(), directed.end());
  for (std::size_t k = 0; k < directed.size();) {
    std::size_t next = k;
    while (next < directed.size() && directed[next] == directed[k]) ++next;
    if (next - k == 1) onBoundary[directed[k].first] = onBoundary[directed[k].second] = true;
    k = next;
  }
  return onBoundary;
}

// Residuals |x_i - x_j|^2 - |u_i - u_j|^2 for a list of vertex-index pairs in the layout.
class IsometryResidual : public ResidualTerm {
 public:
  IsometryResidual(std::vector<std::array<int, 2>> xOffsets,
                   std::vector<std::array<int, 2>> uOffsets)
      : x_(std::move(xOffsets)), u_(std::move(uOffsets)) {}

  int numResiduals() const override { return int(x_.size()); }

  JacobianPattern pattern() const override {
    JacobianPattern p;
    for (std::size_t e = 0; e < x_.size(); ++e) {
      for (int c = 0; c < 3; ++c) p.cols.push_back(x_[e][0] + c);
      for (int c = 0; c < 3; ++c) p.cols.push_back(x_[e][1] + c);
      for (int c = 0; c < 2; ++c) p.cols.push_back(u_[e][0] + c);
      for (int c = 0; c < 2; ++c) p.cols.push_back(u_[e][1] + c);
      p.rowStart.push_back(int(p.cols.size()));
    }
    return p;
  }

  // The residual is a quadratic form in x, so along v it curves by 2 (|dv_x|^2 - |dv_u|^2).
  void secondDirectionalDerivative(const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                   double* rvv) const override {
    for (std::size_t e = 0; e < x_.size(); ++e)
      rvv[e] = 2.0 * ((v.segment<3>(x_[e][0]) - v.segment<3>(x_[e][1])).squaredNorm() -
                      (v.segment<2>(u_[e][0]) - v.segment<2>(u_[e][1])).squaredNorm());
  }

  void evaluate(const Eigen::VectorXd& x, double* r, double* J) const override {
    for (std::size_t e = 0; e < x_.size(); ++e) {
      const Eigen::Vector3d d = x.segment<3>(x_[e][0]) - x.segment<3>(x_[e][1]);
      const Eigen::Vector2d q = x.segment<2>(u_[e][0]) - x.segment<2>(u_[e][1]);
      r[e] = d.squaredNorm() - q.squaredNorm();
      if (!J) continue;
      double* row = J + 10 * e;
      for (int c = 0; c < 3; ++c) {
        row[c] = 2.0 * d[c];
        row[3 + c] = -2.0 * d[c];
      }
      for (int c = 0; c < 2; ++c) {
        row[6 + c] = -2.0 * q[c];
        row[8 + c] = 2.0 * q[c];
      }
    }
  }

 private:
  std::vector<std::array<int, 2>> x_, u_;
};

void addLaplacianRows(const CotangentWeights& w, const std::vector<bool>& onBoundary,
                      const std::vector<int>& offsets, int dim, int& row,
                      std::vector<Triplet>& entries) {
  for (std::size_t i = 0; i < w.neighbours.size(); ++i) {
    if (i % 4096 == 0) throwIfInterrupted("the solve");
    if (onBoundary[i]) continue;
    for (int c = 0; c < dim; ++c) {
      double diagonal = 0.0;
      for (const auto& [j, weight] : w.neighbours[i]) {
        entries.emplace_back(row, offsets[j] + c, weight);
        diagonal -= weight;
      }
      entries.emplace_back(row, offsets[i] + c, diagonal);
      ++row;
    }
  }
}

}  // namespace

VariableLayout::VariableLayout(int verticesA, int verticesB, const std::vector<int>& seamA,
                               const std::vector<int>& seamB)
    : nA_(verticesA), nB_(verticesB), sharedWithA_(std::size_t(verticesB), -1) {
  assert(seamA.size() == seamB.size() && "seams must pair one to one");
  for (std::size_t k = 0; k < seamB.size(); ++k) sharedWithA_[std::size_t(seamB[k])] = seamA[k];
}

Eigen::VectorXd packVariables(const VariableLayout& layout, const Piece& a, const Piece& b) {
  // Unused slots (a shared seam's own 3D ones) are zero; B is written first so that A's 3D
  // positions stand where the two share.
  Eigen::VectorXd x = Eigen::VectorXd::Zero(layout.numVariables());
  const Piece* pieces[2] = {&a, &b};
  for (int p = 1; p >= 0; --p)
    for (int i = 0; i < layout.verticesOf(p); ++i) {
      x.segment<3>(layout.x(p, i)) = pieces[p]->shape.row(i).transpose();
      x.segment<2>(layout.u(p, i)) = pieces[p]->flat.row(i).transpose();
    }
  return x;
}

void unpackVariables(const VariableLayout& layout, const Eigen::VectorXd& x, Piece& a, Piece& b) {
  Piece* pieces[2] = {&a, &b};
  for (int p = 0; p < 2; ++p) {
    pieces[p]->shape.resize(layout.verticesOf(p), 3);
    pieces[p]->flat.resize(layout.verticesOf(p), 2);
    for (int i = 0; i < layout.verticesOf(p); ++i) {
      pieces[p]->shape.row(i) = x.segment<3>(layout.x(p, i)).transpose();
      pieces[p]->flat.row(i) = x.segment<2>(layout.u(p, i)).transpose();
    }
  }
}

Eigen::Matrix<int, Eigen::Dynamic, 2> meshEdges(const Faces& F) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * F.rows());
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int i = F(f, k), j = F(f, (k + 1) % 3);
      edges.emplace_back(std::min(i, j), std::max(i, j));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  Eigen::Matrix<int, Eigen::Dynamic, 2> E(edges.size(), 2);
  for (std::size_t e = 0; e < edges.size(); ++e) E.row(e) << edges[e].first, edges[e].second;
  return E;
}

EdgeLengthPairs meshEdgePairs(const VariableLayout& layout, const Faces& FA, const Faces& FB) {
  EdgeLengthPairs pairs;
  const Faces* faces[2] = {&FA, &FB};
  for (int p = 0; p < 2; ++p) {
    const auto E = meshEdges(*faces[p]);
    for (int e = 0; e < E.rows(); ++e) {
      pairs.x.push_back({layout.x(p, E(e, 0)), layout.x(p, E(e, 1))});
      pairs.u.push_back({layout.u(p, E(e, 0)), layout.u(p, E(e, 1))});
      pairs.weight.push_back(1.0);
    }
  }
  return pairs;
}

void weightByFlatLength(EdgeLengthPairs& edges, const Eigen::VectorXd& x, double isometryWeight) {
  for (std::size_t e = 0; e < edges.weight.size(); ++e) {
    const double flat2 = (x.segment<2>(edges.u[e][0]) - x.segment<2>(edges.u[e][1])).squaredNorm();
    edges.weight[e] = 8.0 * flat2 * isometryWeight;
  }
}

void scaleLengths(DForm& model, double factor) {
  for (Piece* p : {&model.a, &model.b}) {
    p->flat *= factor;
    p->shape *= factor;
  }
}

std::unique_ptr<ResidualTerm> makeIsometryTerm(const EdgeLengthPairs& edges) {
  return std::make_unique<IsometryResidual>(edges.x, edges.u);
}

std::unique_ptr<ResidualTerm> makeFlatAnchorTerm(const VariableLayout& layout,
                                                 const std::vector<int>& verticesA,
                                                 const Points2& targetsA,
                                                 const std::vector<int>& verticesB,
                                                 const Points2& targetsB) {
  std::vector<Triplet> entries;
  std::vector<double> b;
  int row = 0;
  const std::vector<int>* vertices[2] = {&verticesA, &verticesB};
  const Points2* targets[2] = {&targetsA, &targetsB};
  for (int p = 0; p < 2; ++p)
    for (std::size_t k = 0; k < vertices[p]->size(); ++k)
      for (int c = 0; c < 2; ++c, ++row) {
        entries.emplace_back(row, layout.u(p, (*vertices[p])[k]) + c, 1.0);
        b.push_back((*targets[p])(k, c));
      }
  return linearTerm(row, layout.numVariables(), entries,
                    Eigen::Map<Eigen::VectorXd>(b.data(), Eigen::Index(b.size())));
}

CotangentWeights cotangentWeights(const Points2& V, const Faces& F) {
  CotangentWeights w;
  w.neighbours.resize(V.rows());
  auto add = [&](int i, int j, double value) {
    for (auto& [k, weight] : w.neighbours[i])
      if (k == j) {
        weight += value;
        return;
      }
    w.neighbours[i].emplace_back(j, value);
  };
  for (int f = 0; f < F.rows(); ++f) {
    if (f % 4096 == 0) throwIfInterrupted("the solve");
    for (int k = 0; k < 3; ++k) {
      // The angle at corner k is opposite edge (k+1, k+2).
      const int i = F(f, k), j = F(f, (k + 1) % 3), l = F(f, (k + 2) % 3);
      const Eigen::Vector2d a = V.row(j) - V.row(i), b = V.row(l) - V.row(i);
      const double cross = std::abs(a.x() * b.y() - a.y() * b.x());
      const double cot = cross > 0 ? a.dot(b) / cross : 0.0;
      add(j, l, 0.5 * cot);
      add(l, j, 0.5 * cot);
    }
  }
  return w;
}

std::unique_ptr<ResidualTerm> makeSmoothnessTerm(const VariableLayout& layout, const Piece& a,
                                                 const Piece& b, bool threeD) {
  std::vector<Triplet> entries;
  int row = 0;
  const Piece* pieces[2] = {&a, &b};
  for (int p = 0; p < 2; ++p) {
    const CotangentWeights w = cotangentWeights(pieces[p]->flat, pieces[p]->F);
    std::vector<int> offsets(layout.verticesOf(p));
    for (int i = 0; i < layout.verticesOf(p); ++i)
      offsets[i] = threeD ? layout.x(p, i) : layout.u(p, i);
    // Creases are left out like the boundary: the sheet may fold there.
    std::vector<bool> skip = boundaryMask(layout.verticesOf(p), pieces[p]->F);
    for (const std::vector<int>& crease : pieces[p]->creases)
      for (int v : crease) skip[v] = true;
    addLaplacianRows(w, skip, offsets, threeD ? 3 : 2, row, entries);
  }
  return linearTerm(row, layout.numVariables(), entries, Eigen::VectorXd::Zero(row));
}

std::unique_ptr<ResidualTerm> makeSeamSmoothnessTerm(const VariableLayout& layout,
                                                     const std::vector<int>& seamA,
                                                     const std::vector<int>& seamB) {
  std::vector<Triplet> entries;
  int row = 0;
  const std::vector<int>* seams[2] = {&seamA, &seamB};
  for (int p = 0; p < 2; ++p) {
    const auto& s = *seams[p];
    const int n = int(s.size());
    for (int k = 0; k < n; ++k)
      for (int c = 0; c < 3; ++c, ++row) {
        entries.emplace_back(row, layout.x(p, s[(k + n - 1) % n]) + c, 1.0);
        entries.emplace_back(row, layout.x(p, s[(k + 1) % n]) + c, 1.0);
        entries.emplace_back(row, layout.x(p, s[k]) + c, -2.0);
      }
  }
  return linearTerm(row, layout.numVariables(), entries, Eigen::VectorXd::Zero(row));
}

}  // namespace dform
