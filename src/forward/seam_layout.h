// SPDX-License-Identifier: GPL-3.0-or-later
// Where the seam goes on the two pieces: which boundary of each is zipped, where the seam starts
// and which way it runs, and where its vertices go along it (internal to src/forward, but for
// seamFractions).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "dform/core/messages.h"
#include "dform/core/status.h"
#include "dform/core/types.h"
#include "dform/exact/exact_gluing.h"
#include "dform/forward/dform_from_shapes.h"

namespace dform {

/// Arc-length fractions (from the starting pair, along the seam) of the n seam vertices: uniform,
/// except that every corner of either outline (`corners`, seam fractions) becomes a vertex, so that
/// no corner of the cut pattern is chamfered off. The stretch between two consecutive corners gets
/// a share of the n vertices in proportion to its length, spaced uniformly; both pieces use the
/// same fractions, so paired seam edges keep equal flat lengths. The first vertex is the starting
/// pair, or the corner nearest it where one lies within half a seam edge of it (the fractions then
/// run from that corner's, which is below 0 for a corner behind the start, to it plus 1). Corners
/// closer than kSameCorner of a seam edge to an earlier one are merged into it; with more than
/// n / 2 corners the seam is uniform.
std::vector<double> seamFractions(int n, std::vector<double> corners);

/// Corners of the seam closer than this share of a seam edge are one vertex: a chord that short
/// (1e-3 of a seam edge, 0.8 um on an 800 mm seam of 1000 points) would only chamfer a corner by
/// as much.
constexpr double kSameCorner = 1e-3;

namespace forward_detail {

/// A piece as drawn, in mm: the boundary that is joined, the outline left free when the joined
/// boundary is a hole, and the creases. Loops are counter-clockwise as read.
struct DrawnPiece {
  Points2 joined;
  std::optional<Points2> freeOutline;
  std::vector<Points2> creases;
  std::string sha256;  ///< of the file's bytes as read
};

/// What messages and errors call a piece: its file, else "piece A" or "piece B".
std::string pieceLabel(const Shape2& shape, const char* name);

/// Picks a piece's joined boundary: a disc joins its outline, an annulus-like piece (one hole) its
/// hole. Says what it found, since the join decides what the D-Form is.
Result<DrawnPiece> drawnPiece(Shape2& shape, JoinedBoundary join, const std::string& name,
                              MessageSink& sink);

/// The closed loop P (counter-clockwise) sampled at `fractions` (ascending from 0, as from
/// seamFractions) measured from `start` in `direction` (+1 counter-clockwise, -1 clockwise). Rows
/// come out counter-clockwise; order[k] is the row of the k-th sample.
struct LoopSamples {
  Points2 rows;
  std::vector<int> order;
};
LoopSamples sampleLoop(const Points2& P, const std::vector<double>& fractions, double start,
                       int direction);

/// The two pieces as the seam is laid out on them: which boundary is zipped, where the seam starts
/// and which way it runs, and the points every level must sample: corners of both joined
/// boundaries and the crease ends on them (as seam fractions from the starting pair), and corners
/// and crease ends on each free outline (as fractions of that outline, sampled from its point
/// nearest the seam's start, so that the mesh does not depend on where its path began).
struct SeamLayout {
  DrawnPiece pieces[2];
  std::string paths[2];
  double startFraction[2] = {0.0, 0.0};
  int direction[2] = {1, -1};
  double freeStart[2] = {0.0, 0.0};
  std::vector<double> seamCorners, freeCorners[2];

  std::string bothPaths() const { return paths[0] + " and " + paths[1]; }
};

/// Checks the joined lengths (fitting B to A when asked), turns B over when asked and resolves
/// the starting pair: what reading left to do before the seam is laid out.
Status matchPieces(const ForwardSettings& job, SeamLayout& layout, SolvedDForm& run,
                   MessageSink& sink);

/// The finest mesh's vertices, for the memory check.
double finestVertices(const ForwardSettings& job, const SeamLayout& layout, double perimeterA);

/// Each seam's direction and start, and the corners, crease ends and ends of straight sides
/// (two seam edges long or longer, at job.resolution) every level samples.
void layOutSeam(const ForwardSettings& job, const SolvedDForm& run, SeamLayout& layout);

/// The two sides of the seam sampled at `fractions` (A's counter-clockwise, B's clockwise from
/// the starting pair), row k of each at seam point k: what the exact engine glues.
exact::SeamPolygons seamPolygons(const DrawnPiece pieces[2], const double startFraction[2],
                                 const int direction[2], const std::vector<double>& fractions);

}  // namespace forward_detail

}  // namespace dform
