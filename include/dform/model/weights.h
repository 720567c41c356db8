// SPDX-License-Identifier: GPL-3.0-or-later
// The weights of the two D-Form objectives, one member per term: each has its row in the
// objective's table (model/term_table.h), which names it for job files, --weight and report.json.
#pragma once

namespace dform {

/// Term weights of the forward objective (paper Table 1's defaults). Each has its row in
/// forwardTerms (model/term_table.h): its name, its term and how the solve uses it.
struct ForwardWeights {
  double isometry = 1.0;  ///< w_iso, Eq. 1
  double alignment =
      1.0;  ///< w_align, Eq. 2: any positive weight closes the seam exactly (see VariableLayout)
  double boundaryFix = 1.0;  ///< w_fix, Eq. 3
  double smooth3d = 0.01;    ///< w_3D, Eq. 4 on the 3D meshes
  double smooth2d = 1.0;     ///< w_2D, Eq. 4 on the flat meshes
  double seam = 0.01;        ///< w_seam, Eq. 5
};

/// Term weights of the inverse objective (paper Table 1's defaults for inverse modelling). Each has
/// its row in inverseTerms (model/term_table.h): its name, its term and how the solve uses it.
struct InverseWeights {
  double isometry = 1.0;  ///< w_iso, Eq. 1
  double closeness =
      1.0;  ///< w_close, Eq. 6: any positive weight holds the seam on the curve exactly
  double smooth3d = 0.001;  ///< w_3D, Eq. 4 on the 3D meshes
  double smooth2d = 1.0;    ///< w_2D, Eq. 4 on the flat meshes
};

}  // namespace dform
