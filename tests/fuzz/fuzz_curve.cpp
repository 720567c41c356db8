// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzzes the seam-curve reader (OBJ or JSON, by DFORM_FUZZ_SOURCE's extension), both as the file
// says and forced closed (`--closed`). A curve it accepts must be what the inverse run relies on.
#include "dform/io/curve_reader.h"
#include "fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  using namespace dform;
  const std::string text = fuzz::text(data, size);
  for (const bool forceClosed : {false, true}) {
    CurveReadOptions options;
    options.forceClosed = forceClosed;
    const Result<Curve3> curve = parseCurve(text, DFORM_FUZZ_SOURCE, options);
    fuzz::checkStatus(curve.status(), DFORM_FUZZ_SOURCE);
    if (!curve.isOk()) continue;
    const Points3& P = curve.value().points;
    fuzz::require(P.rows() >= 5, "an accepted curve has fewer than 5 points");
    fuzz::require(P.allFinite() && P.cwiseAbs().maxCoeff() <= options.maxCoordinate,
                  "an accepted curve has a bad coordinate");
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      fuzz::require(P.row(i) != P.row((i + 1) % P.rows()), "an accepted curve repeats a point");
  }
  return 0;
}
