// SPDX-License-Identifier: GPL-3.0-or-later
// The injectivity safeguard of the forward solve: a step is refused when it turns a flat triangle
// over or folds two 3D neighbours onto each other, so that no fold is left to luck (a rounding
// difference, a long Levenberg-Marquardt step).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "dform/core/types.h"
#include "dform/model/terms.h"
#include "dform/solver/solver.h"

namespace dform {

/// The fold test of validate's figures, on the solver's unknowns: a flat triangle is turned over
/// when its signed area is <= 0 (the pieces' faces run counter-clockwise), and two 3D triangles
/// sharing an edge that is not a crease are folded when their normals point apart (negative dot
/// product, a dihedral turn beyond 90 degrees). Creases may fold sharply, as drawn.
class FoldGuard {
 public:
  /// The guard of pieces `a` and `b` (their faces, seams and creases) whose unknowns `layout`
  /// places in the solver's vector.
  FoldGuard(const VariableLayout& layout, const Piece& a, const Piece& b);

  /// Flat triangles turned over plus 3D neighbour pairs folded, at x.
  int count(const Eigen::VectorXd& x) const;
  /// Whether moving from `from` to `to` turns over a flat triangle or folds a pair that stood
  /// upright at `from` (what was folded may stay so or unfold; slivers are let be, see the .cpp).
  bool addsFold(const Eigen::VectorXd& from, const Eigen::VectorXd& to) const;

 private:
  struct Orientations {
    std::vector<double>
        value;  ///< per flat triangle twice its signed area, per pair the normals' dot
    std::vector<bool> clear;  ///< whether it stands upright and is no sliver (see the .cpp)
  };
  Orientations orientations(const Eigen::VectorXd& x) const;

  struct Face {
    std::array<int, 3> x, u;  ///< offsets of the corners' 3D and flat positions
  };
  std::vector<Face> faces_;
  std::vector<std::array<int, 2>> neighbours_;  ///< faces sharing an edge that is not a crease
};

/// Sets the solver's acceptStep to refuse a step that adds a fold by `guard`'s test. `guard` must
/// outlive the solves.
void refuseNewFolds(const FoldGuard& guard, SolverOptions& solver);

}  // namespace dform
