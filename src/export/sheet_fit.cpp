// SPDX-License-Identifier: GPL-3.0-or-later
// Fitting the pattern to its sheet or page: the region a sheet's pieces and title lines may use,
// where the title block goes, the tiles of a print piece too large for a page, the messages of a
// piece that does not fit, and the check that each bare outline fits before anything is drawn.
#include <algorithm>
#include <cmath>
#include <limits>

#include "pattern_layout.h"

namespace dform::fab {

Box SheetFit::artRegion(double W, double H, const Vec2& at) const {
  double inset = m;
  if (profile->registration == Registration::Silhouette)  // clear of the square's far edge
    inset = kRegInset + kRegSquare + profile->registrationClearMm;
  Box r = Box::spanning(at + Vec2(inset, inset), at + Vec2(W - inset, H - inset));
  if (profile->registration == Registration::Cricut) {  // the Print Then Cut area, centred
    const Vec2 half(0.5 * std::min(kCricutW, W - 2 * m), 0.5 * std::min(kCricutH, H - 2 * m));
    const Vec2 centre = at + 0.5 * Vec2(W, H);
    r = Box::spanning(centre - half, centre + half);
  }
  return r;
}

double SheetFit::markRoom() const {
  const double line = kTitlePitch * kMinTitleH;
  return m + (profile->calibrationBar ? kBarRow : line) + (scaleNote.empty() ? 0.0 : line);
}

bool SheetFit::fits(const Vec2& size, double W, double H) const {
  const Box r = artRegion(W, H);
  return r.w() > 0 && size.x() <= r.w() + 1e-9 && size.y() <= r.h() + 1e-9;
}

bool SheetFit::fitsSomeWay(const Vec2& size) const {
  return fits(size, pageW, pageH) || (mayTurnPage && fits(size, pageH, pageW));
}

Status SheetFit::tooLarge(const std::string& what, const std::vector<Vec2>& sizes,
                          const std::string& contents) const {
  *tooLargeOut = true;
  const Box r = artRegion(pageW, pageH);
  Vec2 need = Vec2::Zero(), size = Vec2::Zero();
  double least = std::numeric_limits<double>::infinity();
  for (const Vec2& candidate : sizes) {
    const Vec2 n(candidate.x() + (pageW - r.w()), candidate.y() + (pageH - r.h()));
    if (std::max(n.x() / pageW, n.y() / pageH) < least) {
      least = std::max(n.x() / pageW, n.y() / pageH);
      need = n;
      size = candidate;
    }
  }
  if (profile->registration == Registration::Cricut) {  // the area, not the paper, is the limit
    const bool fullArea = std::abs(r.w() - kCricutW) < 1e-6 && std::abs(r.h() - kCricutH) < 1e-6;
    return Status{ErrorCode::Usage,
                  what + " does not fit the Cricut Print Then Cut area: " + contents + ", " +
                      formatMm(size.x()) + " x " + formatMm(size.y()) +
                      " mm, is larger than the area, which is " +
                      (fullArea ? "6.75 x 9.25 in, " : "") + formatMm(r.w(), 2) + " x " +
                      formatMm(r.h(), 2) + " mm on " + pageName +
                      " paper, and no larger on larger paper"};
  }
  const std::string area = pageName.empty() ? "sheet" : pageName + " page's cutting area";
  return Status{ErrorCode::Usage, what + " does not fit the " + area + ": it needs at least " +
                                      formatMm(need.x()) + " x " + formatMm(need.y()) + " mm (" +
                                      formatMm(size.x()) + " x " + formatMm(size.y()) + " mm of " +
                                      contents + ", plus margins); the " + sheetWord + " is " +
                                      formatMm(pageW) + " x " + formatMm(pageH) + " mm"};
}

Vec2 SheetFit::tiledExtent(const Vec2& size) const {
  return Vec2(size.x() + 2 * m, size.y() + 2 * m);
}

std::pair<long, long> SheetFit::tileGrid(const Vec2& size) const {
  auto count = [&](double length, double window) {
    return std::max(1L, long(std::ceil((length - overlap) / (window - overlap) - 1e-9)));
  };
  const Vec2 extent = tiledExtent(size);
  return std::pair<long, long>(count(extent.x(), tileW), count(extent.y(), tileH));
}

Status SheetFit::tooManyTiles(long tiles) const {
  *tooLargeOut = true;
  return Status{ErrorCode::Usage, "the pattern needs at least " + std::to_string(tiles) + " " +
                                      pageName + " pages when tiled, more than the " +
                                      std::to_string(kMaxTiles) +
                                      " a print profile makes; use a sheet profile"};
}

// The sheet or page for the options and profile, and its title block's height for a pattern at
// `scale`. `tooLargeOut` is the build's flag for failing because a piece does not fit.
Result<SheetFit> sheetFit(const ExportOptions& o, const Profile& profile, bool creased,
                          double scale, bool& tooLargeOut) {
  SheetFit fit;
  fit.profile = &profile;
  fit.tooLargeOut = &tooLargeOut;
  fit.m = profile.marginMm;
  fit.edge = std::max(kTickOut, profile.bleedMm);
  fit.textH = std::clamp(profile.labelHeightMm, 2.0, 4.0);
  const double barH = profile.calibrationBar ? kBarRow : 0.0;
  fit.scale = scale;
  // Tabs fold away from the printed (outer) side: a line says so on every sheet that has them.
  fit.tabbed = o.tabWidthMm > 0 && profile.tabs != TabSide::None;
  // A pattern not at true size says so in words on every sheet, title or not: a scale printed
  // only as a figure in the title line is easily missed.
  if (scale != 1.0)
    fit.scaleNote = "printed at " + percentText(scale) + ": the D-Form is " + percentText(scale) +
                    " of the designed size (ticks, tabs and labels keep theirs)";
  // The full block's lines: title and note, a legend line for creases, the tab line, the scale
  // note (the depth a tiled piece's page map keeps for them).
  const int titleLines = 2 + int(creased) + int(fit.tabbed) + int(!fit.scaleNote.empty()) +
                         int(profile.registration == Registration::Silhouette);
  const double titleH = titleLines * kTitlePitch * fit.textH + barH;
  fit.titleBlock = titleH > 0 ? fit.m + titleH : 0.0;
  // The page: --page over the profile's. A page profile refuses a sheet size and a sheet profile
  // a page, rather than ignore them.
  fit.pageName = o.page.empty() ? profile.page : o.page;
  if (!o.page.empty() && profile.page.empty())
    return Status{ErrorCode::Usage, mention(Setting::Page) +
                                        " is for page profiles (print, print-and-cut); profile " +
                                        profile.name +
                                        " cuts a material sheet: give its size with " +
                                        mention(Setting::Sheet) + " WxHmm"};
  if (!profile.page.empty() && o.sheetGiven)
    return Status{ErrorCode::Usage, "profile " + profile.name + " prints on " + fit.pageName +
                                        " pages, so " + mention(Setting::Sheet) +
                                        " does not apply; choose the paper with " +
                                        mention(Setting::Page) + " A4|Letter|A3|Tabloid|WxHmm"};
  fit.pageW = o.sheetWidthMm;
  fit.pageH = o.sheetHeightMm;
  if (!fit.pageName.empty()) {
    const auto size = pageSizeMm(fit.pageName);
    if (!size)
      return Status{ErrorCode::Usage, "unknown page \"" + fit.pageName +
                                          "\": use A4, Letter, A3, Tabloid or a size such as "
                                          "200x300mm"};
    fit.pageW = size->first;
    fit.pageH = size->second;
  }
  fit.sheetWord = fit.pageName.empty() ? "sheet" : "page";
  // Only a print profile's page may turn to landscape or tile; a print-and-cut page keeps its
  // marks (the cutter reads one page's), and a laser sheet is the size it is.
  fit.mayTurnPage = profile.kind == ProfileKind::Print && !fit.pageName.empty();
  fit.mayTile = profile.kind == ProfileKind::Print && profile.tile;
  fit.tileW = fit.pageW - 2 * kTileMargin;
  fit.tileH = fit.pageH - 2 * kTileMargin - kTileHeader;
  fit.overlap = profile.tileOverlapMm;
  return fit;
}

// Fit first, before any tick or tab is made. A piece's cut path contains its outer outline (tabs
// and kerf only add to it), so at every turn the layout may choose (2-degree steps; a half turn
// gives the same box) the outline's extent bounds the cut path's from below. Each piece may get a
// sheet (or page) of its own, so the pattern fits when each bare outline fits one alone, or, on a
// tiling profile, when its tiles are not too many. When that fails, say so now, at a cost
// independent of the seam's length in ticks and tabs.
Status checkOutlinesFit(const SheetFit& fit, const FlatPieces& flat) {
  long fewestTiles = 0;
  for (int p = 0; p < 2; ++p) {
    std::vector<Vec2> sizes;
    for (int deg = 0; deg < 180; deg += kTurnStepDeg) {
      const Box b = extentAt({flat.material[p].front()}, deg, fit.edge);
      sizes.emplace_back(b.w(), b.h());
    }
    if (std::any_of(sizes.begin(), sizes.end(),
                    [&](const Vec2& size) { return fit.fitsSomeWay(size); }))
      continue;
    if (!fit.mayTile) return fit.tooLarge("piece " + flat.names[p], sizes, "the piece");
    long fewest = std::numeric_limits<long>::max();
    for (const Vec2& size : sizes) {
      const auto [nx, ny] = fit.tileGrid(size);
      fewest = std::min(fewest, nx * ny);
    }
    fewestTiles += fewest;
  }
  if (fewestTiles > kMaxTiles) return fit.tooManyTiles(fewestTiles);
  return Status::ok();
}

}  // namespace dform::fab
