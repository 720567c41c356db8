// Fuzzes the gate-file reader. Limits it accepts must be usable: finite and non-negative.
#include <cmath>

#include "fuzz_check.h"
#include "validate/gate.h"

extern "C" int LLVMFuzzerTestOneInput(const unsigned char* data, std::size_t size) {
  using namespace dform;
  const Result<GateLimits> gate = fuzz::parseChecked(data, size, "gate.json", parseGateJson);
  if (!gate.isOk()) return 0;
  const GateLimits& g = gate.value();
  for (const double limit : {g.L_error, g.L_max, g.B_error, g.D_error, g.seam_gap_mm,
                             g.gauss_max_rad, g.seam_length_rel, g.hull_distance_rel})
    fuzz::require(std::isfinite(limit) && limit >= 0.0, "an accepted limit is unusable");
  fuzz::require(g.flipped >= 0 && g.degenerate >= 0, "an accepted count is negative");
  return 0;
}
