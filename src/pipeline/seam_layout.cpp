#include "pipeline/seam_layout.h"

#include <algorithm>

namespace dform {

std::vector<double> seamFractions(int n, std::vector<double> corners) {
  std::vector<double> uniform(n);
  for (int k = 0; k < n; ++k) uniform[k] = double(k) / n;
  if (int(corners.size()) > n / 4) return uniform;
  std::sort(corners.begin(), corners.end());
  std::vector<double> breaks{0.0};
  const double merge = 0.5 / n;
  for (double c : corners)
    if (c - breaks.back() >= merge && 1.0 - c >= merge) breaks.push_back(c);
  const int m = int(breaks.size());
  std::vector<double> lengths(m);
  for (int j = 0; j < m; ++j) lengths[j] = (j + 1 < m ? breaks[j + 1] : 1.0) - breaks[j];
  // Largest-remainder apportionment with at least one vertex per stretch.
  std::vector<int> counts(m);
  int assigned = 0;
  for (int j = 0; j < m; ++j) assigned += counts[j] = std::max(1, int(lengths[j] * n));
  while (assigned != n) {
    int pick = -1;
    double bestGap = 0;
    for (int j = 0; j < m; ++j) {
      const double gap = lengths[j] * n - counts[j];  // > 0: the stretch wants more vertices
      const bool eligible = assigned < n || counts[j] > 1;
      if (eligible && (pick < 0 || (assigned < n ? gap > bestGap : gap < bestGap))) pick = j, bestGap = gap;
    }
    counts[pick] += assigned < n ? 1 : -1;
    assigned += assigned < n ? 1 : -1;
  }
  std::vector<double> fractions;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < counts[j]; ++i) fractions.push_back(breaks[j] + lengths[j] * i / counts[j]);
  return fractions;
}

}  // namespace dform
