// SPDX-License-Identifier: GPL-3.0-or-later
// The Gram matrix M^T M of a sparse matrix, assembled so that a stop can be asked for meanwhile:
// on a fine mesh one product takes seconds.
#pragma once

#include <Eigen/SparseCore>

namespace dform {

/// M^T M, equal bit for bit to Eigen's `M.transpose() * M` (each entry is the same sum in the same
/// order: the product is taken a block of columns at a time). Throws Interrupted (core/interrupt.h)
/// between blocks when a stop has been requested.
Eigen::SparseMatrix<double> gramMatrix(const Eigen::SparseMatrix<double>& M);

}  // namespace dform
