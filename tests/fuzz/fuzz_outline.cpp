// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzzes the flat-outline reader (SVG or JSON, by DFORM_FUZZ_SOURCE's extension) from parsing to
// shape assembly. A shape it accepts must be what the pipeline relies on.
#include <cmath>

#include "dform/core/polyline.h"
#include "dform/io/outline_reader.h"
#include "fuzz_check.h"

namespace {

using namespace dform;

void checkOutline(const Outline2& outline) {
  const Points2& P = outline.points;
  fuzz::require(P.rows() >= 3, "an accepted outline has fewer than 3 points");
  fuzz::require(P.allFinite() && P.cwiseAbs().maxCoeff() <= OutlineReadOptions().maxCoordinate,
                "an accepted outline has a bad coordinate");
  fuzz::require(signedArea(P) > 0.0, "an accepted outline is not counter-clockwise");
  fuzz::require(!findSelfIntersection(P), "an accepted outline crosses itself");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  const Result<Shape2> shape = fuzz::parseChecked(data, size, DFORM_FUZZ_SOURCE,
                                                  [](std::string text, const std::string& source) {
                                                    return parseOutline(std::move(text), source);
                                                  });
  if (!shape.isOk()) return 0;
  checkOutline(shape.value().outer);
  for (const Outline2& hole : shape.value().holes) checkOutline(hole);
  return 0;
}
