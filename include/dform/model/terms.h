// SPDX-License-Identifier: GPL-3.0-or-later
// The D-Form objective's terms (paper Eq. 1-6) over the unknowns of two pieces. Used by forward
// and inverse modelling alike.
#pragma once

#include <memory>
#include <vector>

#include "dform/core/types.h"
#include "dform/model/local_global.h"
#include "dform/solver/problem.h"

namespace dform {

/// Unknowns of a two-piece D-Form: per vertex [x y z u v] (3D position, flat position); piece A's
/// vertices first, then piece B's. With a shared seam, B's seam vertex seamB[k] has no 3D position
/// of its own: it is A's seamA[k], so the seam is closed exactly, by construction (the limit of the
/// paper's alignment term, Eq. 2, as its weight grows; section 6.6). Its own three slots stay in
/// the vector, unused, so that every vertex keeps the [x y z u v] stride.
class VariableLayout {
 public:
  static constexpr int kPerVertex = 5;  ///< unknowns per vertex: x y z u v
  /// Pieces of `verticesA` and `verticesB` vertices, each with a 3D position of its own.
  VariableLayout(int verticesA, int verticesB) : nA_(verticesA), nB_(verticesB) {}
  /// The same with a shared seam: B's vertex seamB[k] takes the 3D position of A's seamA[k].
  VariableLayout(int verticesA, int verticesB, const std::vector<int>& seamA,
                 const std::vector<int>& seamB);
  /// The length of the unknown vector.
  int numVariables() const { return kPerVertex * (nA_ + nB_); }
  /// Vertex i of `piece` (0 for A, 1 for B) numbered across both pieces, A's first.
  int vertex(int piece, int i) const { return piece == 0 ? i : nA_ + i; }
  int x(int piece, int i) const {  ///< 3D, 3 values
    return piece == 1 && !sharedWithA_.empty() && sharedWithA_[i] >= 0
               ? x(0, sharedWithA_[i])
               : kPerVertex * vertex(piece, i);
  }
  int u(int piece, int i) const { return kPerVertex * vertex(piece, i) + 3; }  ///< flat, 2 values
  /// The number of vertices of `piece` (0 for A, 1 for B).
  int verticesOf(int piece) const { return piece == 0 ? nA_ : nB_; }
  /// Whether B's seam vertices share A's 3D positions (the seam closed by construction).
  bool sharesSeam() const { return !sharedWithA_.empty(); }

 private:
  int nA_, nB_;
  std::vector<int> sharedWithA_;  ///< per B vertex: the A vertex whose 3D position it has, or -1
};

/// Packs both pieces' shape and flat positions into the unknown vector (and back). A shared seam
/// takes A's 3D positions.
Eigen::VectorXd packVariables(const VariableLayout& layout, const Piece& a, const Piece& b);
void unpackVariables(const VariableLayout& layout, const Eigen::VectorXd& x, Piece& a, Piece& b);

/// Undirected edges of a triangle mesh, each once, as #E by 2 (smaller index first).
Eigen::Matrix<int, Eigen::Dynamic, 2> meshEdges(const Faces& F);

/// Every edge of both pieces as a pair of 3D and flat offsets (weights 1).
EdgeLengthPairs meshEdgePairs(const VariableLayout& layout, const Faces& FA, const Faces& FB);

/// Weights for the local-global form of the isometry term: near an isometry
/// w (|x|^2 - |u|^2)^2 ~ 4 l^2 w (|x| - |u|)^2, and the projective form counts (|x| - |u|)^2 / 2,
/// so edge e gets 8 l_e^2 w_iso with l_e its flat length in x.
void weightByFlatLength(EdgeLengthPairs& edges, const Eigen::VectorXd& x, double isometryWeight);

/// Multiplies every length of the model (flat and 3D) by `factor`: to and from the solver's unit.
void scaleLengths(DForm& model, double factor);

/// Isometry (Eq. 1): per edge ij, |x_i - x_j|^2 - |u_i - u_j|^2 (the pairs' weights are ignored).
std::unique_ptr<ResidualTerm> makeIsometryTerm(const EdgeLengthPairs& edges);

/// Boundary fix (Eq. 3): u(piece, i) - target.row(k) for i = vertices[k].
std::unique_ptr<ResidualTerm> makeFlatAnchorTerm(const VariableLayout& layout,
                                                 const std::vector<int>& verticesA,
                                                 const Points2& targetsA,
                                                 const std::vector<int>& verticesB,
                                                 const Points2& targetsB);

/// Cotangent weights of a flat mesh: for each vertex, its neighbours and (cot a + cot b) / 2.
struct CotangentWeights {
  std::vector<std::vector<std::pair<int, double>>> neighbours;  ///< per vertex
};
CotangentWeights cotangentWeights(const Points2& V, const Faces& F);

/// Surface smoothness (Eq. 4): sum_j w_ij (p_j - p_i) at each interior vertex i of both pieces,
/// on the 3D positions (`threeD`) or the flat ones, with the weights of the flat rest meshes.
/// Boundary and crease vertices are left out: a piece's boundary is a seam or a free edge, and a
/// crease a fold, not a smooth region.
std::unique_ptr<ResidualTerm> makeSmoothnessTerm(const VariableLayout& layout, const Piece& a,
                                                 const Piece& b, bool threeD);

/// Seam smoothness (Eq. 5): x(s[i-1]) + x(s[i+1]) - 2 x(s[i]) along each piece's seam in 3D.
std::unique_ptr<ResidualTerm> makeSeamSmoothnessTerm(const VariableLayout& layout,
                                                     const std::vector<int>& seamA,
                                                     const std::vector<int>& seamB);

/// What every term of an objective is built from (forward and inverse alike), in the solver's
/// unit: the tables of model/term_table.h make each term from these alone.
struct TermInputs {
  const VariableLayout& layout;  ///< where each vertex's unknowns lie
  const Piece& a;                ///< flat rest mesh, seam and creases of piece A
  const Piece& b;                ///< the same of piece B
  const EdgeLengthPairs& edges;  ///< every edge of both pieces (the isometry term)
  /// Drawn vertices of each piece that the boundary-fix term holds at their flat positions
  /// (forward modelling; none in inverse modelling, whose flat boundaries are free).
  std::vector<int> anchoredA;
  std::vector<int> anchoredB;  ///< the same of piece B
};

}  // namespace dform
