// SPDX-License-Identifier: GPL-3.0-or-later
// report.html's pictures, read back as numbers: the 3D view's projection and scale, the
// curvature colours, and the convergence plot's log axis.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iterator>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "dform/core/shape_projection.h"
#include "dform/report/html_report.h"
#include "dform/report/views.h"
#include "dform/validate/metrics.h"
#include "minimal_report.h"
#include "models.h"
#include "report/convergence_plot.h"

namespace dform {
namespace {

using Point = std::pair<double, double>;

// The "x,y x,y ..." lists of every <tag points='...'> in `svg`, in order.
std::vector<std::vector<Point>> pointLists(const std::string& svg, const std::string& tag) {
  std::vector<std::vector<Point>> lists;
  const std::regex element("<" + tag + " points='([^']*)'");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), element);
       it != std::sregex_iterator(); ++it) {
    std::vector<Point> points;
    const std::string text = (*it)[1];
    const std::regex pair("(-?[0-9.]+),(-?[0-9.]+)");
    for (auto p = std::sregex_iterator(text.begin(), text.end(), pair); p != std::sregex_iterator();
         ++p)
      points.emplace_back(std::stod((*p)[1]), std::stod((*p)[2]));
    lists.push_back(points);
  }
  return lists;
}

std::vector<std::string> fills(const std::string& svg) {
  std::vector<std::string> out;
  const std::regex fill("<polygon points='[^']*' fill='(#[0-9a-f]{6})'");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), fill); it != std::sregex_iterator();
       ++it)
    out.push_back((*it)[1]);
  return out;
}

TEST(ReportViews, ShapeFromAboveIsTheSeamAtScale) {
  // A flat disc of radius 50 seen from straight above: the seam is a circle whose diameter is
  // the picture's width less its two 8 px margins, centred; one polygon per triangle turned to
  // the viewer (A's: B's lie under them, turned away) and the seam.
  const DForm disc = test::flatDoubleDisc(6, 48, 50.0);
  View view;
  view.elevationDeg = 90;
  view.azimuthDeg = 37;  // turning about the vertical changes nothing seen from above
  view.widthPx = 300;
  const std::string svg = shapeSvg(disc, view);
  const auto polygons = pointLists(svg, "polygon");
  ASSERT_EQ(polygons.size(), std::size_t(disc.a.F.rows() + 1));
  const std::vector<Point>& seam = polygons.back();
  ASSERT_EQ(seam.size(), disc.a.seam.size());
  for (const Point& p : seam)
    EXPECT_NEAR(std::hypot(p.first - 150.0, p.second - 150.0), 150.0 - 8.0,
                0.2);  // rounding: 0.1 px
  EXPECT_NE(svg.find("viewBox='0 0 300.0 300.0'"), std::string::npos);
}

TEST(ReportViews, AClosedShapeDrawsOnlyTheFacesTurnedToTheViewer) {
  DForm model = test::tetraDForm(6);
  const ShapeCamera camera(30, 25);
  const std::vector<SeenFace> seen = paintersFaces(model, camera);
  const long all = long(model.a.F.rows() + model.b.F.rows());
  EXPECT_GT(long(seen.size()), all / 4);
  EXPECT_LT(long(seen.size()), all) << "the faces turned away are hidden on a closed surface";
  for (const SeenFace& f : seen) {  // turned to the viewer: counter-clockwise on the screen
    const Eigen::Vector2d u = f.corners[1] - f.corners[0], v = f.corners[2] - f.corners[0];
    EXPECT_GT(u.x() * v.y() - u.y() * v.x(), 0.0) << "piece " << f.piece << " face " << f.face;
  }
  for (size_t k = 1; k < seen.size(); ++k) EXPECT_GE(seen[k - 1].depth, seen[k].depth);
  // An open surface (a free boundary) shows both sides: every face is drawn.
  model.a.freeBoundaries = {{model.a.seam[0], model.a.seam[1], model.a.seam[2]}};
  EXPECT_EQ(long(paintersFaces(model, camera).size()), all);
}

// A fine mesh is drawn on about 20k faces (its vertices clustered on a grid of cell c, with
// 2 S / c^2 = 20k for its area S), its outline within a cell of the solved one's; a coarse mesh
// has every face drawn, on its own vertices.
TEST(ReportViews, AFineMeshIsDrawnOnAboutTwentyThousandFaces) {
  DForm fine = test::tetraDForm(150);                                          // 90k faces
  fine.a.freeBoundaries = {{fine.a.seam[0], fine.a.seam[1], fine.a.seam[2]}};  // open: all drawn
  const ShapeCamera camera(30, 25);
  const std::vector<SeenFace> drawn = paintersFaces(fine, camera);
  EXPECT_GT(drawn.size(), 12000u);
  EXPECT_LT(drawn.size(), 28000u);
  double area = 0;
  Eigen::AlignedBox2d solved, seen;
  for (const Piece* p : {&fine.a, &fine.b})
    for (Eigen::Index f = 0; f < p->F.rows(); ++f) {
      const Eigen::Vector3d q0 = p->shape.row(p->F(f, 0)).transpose();
      area += 0.5 * (p->shape.row(p->F(f, 1)).transpose() - q0)
                        .cross(p->shape.row(p->F(f, 2)).transpose() - q0)
                        .norm();
      for (int k = 0; k < 3; ++k)
        solved.extend(camera.screen(p->shape.row(p->F(f, k)).transpose()).head<2>());
    }
  for (const SeenFace& f : drawn)
    for (const Eigen::Vector2d& c : f.corners) seen.extend(c);
  const double cell = std::sqrt(2.0 * area / 20000.0);
  EXPECT_LT((seen.min() - solved.min()).cwiseAbs().maxCoeff(), cell);
  EXPECT_LT((seen.max() - solved.max()).cwiseAbs().maxCoeff(), cell);
  EXPECT_TRUE(solved.contains(seen));
  for (size_t k = 1; k < drawn.size(); ++k) EXPECT_GE(drawn[k - 1].depth, drawn[k].depth);

  DForm coarse = test::tetraDForm(20);  // 3.2k faces
  coarse.a.freeBoundaries = fine.a.freeBoundaries;
  const std::vector<SeenFace> all = paintersFaces(coarse, camera);
  ASSERT_EQ(long(all.size()), long(coarse.a.F.rows() + coarse.b.F.rows()));
  for (const SeenFace& f : all) {
    const Piece& p = f.piece == 0 ? coarse.a : coarse.b;
    EXPECT_EQ(f.corners[0], camera.screen(p.shape.row(p.F(f.face, 0)).transpose()).head<2>());
  }
}

TEST(ReportViews, EveryPointIsInsideThePicture) {
  const DForm tetra = test::tetraDForm(6);
  for (double azimuth : {0.0, 30.0, 120.0, -60.0})
    for (double elevation : {-30.0, 10.0, 25.0, 89.0}) {
      View view;
      view.azimuthDeg = azimuth;
      view.elevationDeg = elevation;
      view.widthPx = 280;
      const std::string svg = shapeSvg(tetra, view);
      std::smatch size;
      ASSERT_TRUE(std::regex_search(svg, size, std::regex("height='([0-9.]+)'")));
      const double height = std::stod(size[1]);
      for (const auto& polygon : pointLists(svg, "polygon"))
        for (const Point& p : polygon) {
          EXPECT_GE(p.first, 7.9);
          EXPECT_LE(p.first, 280 - 7.9);
          EXPECT_GE(p.second, 7.9);
          EXPECT_LE(p.second, height - 7.9);
        }
    }
}

TEST(ReportViews, CurvatureIsWhiteWhereTheSheetIsFlatAndColouredAtABump) {
  // The tetrahedral D-Form is exactly developable (defects of rounding size): every triangle white.
  DForm tetra = test::tetraDForm(6);
  for (const std::string& fill : fills(flatCurvatureSvg(tetra, 400))) EXPECT_EQ(fill, "#ffffff");
  View curvature;
  curvature.curvature = true;
  for (const std::string& fill : fills(shapeSvg(tetra, curvature))) EXPECT_EQ(fill, "#ffffff");

  // A bump: one interior vertex of A pushed out. Only triangles touching it or its neighbours
  // (whose angles it changes) are coloured, and the scale is the largest |defect|.
  Eigen::Index v;
  (tetra.a.flat.rowwise() - tetra.a.flat.colwise().mean()).rowwise().squaredNorm().minCoeff(&v);
  tetra.a.shape(v, 2) -= 3.0;
  const Eigen::VectorXd K = curvatureMap(tetra.a);
  ASSERT_GT(K.cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_DOUBLE_EQ(curvatureScale(tetra), K.cwiseAbs().maxCoeff());
  std::set<int> near{int(v)};
  for (Eigen::Index f = 0; f < tetra.a.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (tetra.a.F(f, k) == v)
        for (int j = 0; j < 3; ++j) near.insert(tetra.a.F(f, j));
  const std::vector<std::string> flat = fills(flatCurvatureSvg(tetra, 400));
  ASSERT_EQ(flat.size(), std::size_t(tetra.a.F.rows() + tetra.b.F.rows()));
  int coloured = 0;
  for (Eigen::Index f = 0; f < tetra.a.F.rows(); ++f) {
    bool touches = false;
    for (int k = 0; k < 3; ++k) touches = touches || near.count(tetra.a.F(f, k));
    if (flat[std::size_t(f)] != "#ffffff") {
      ++coloured;
      EXPECT_TRUE(touches) << "triangle " << f;
    }
  }
  EXPECT_GT(coloured, 0);
  for (std::size_t f = std::size_t(tetra.a.F.rows()); f < flat.size(); ++f)
    EXPECT_EQ(flat[f], "#ffffff");
}

// Whether q lies inside the triangle (a, b, c), either orientation.
bool inTriangle(const Point& q, const Point& a, const Point& b, const Point& c) {
  auto side = [&](const Point& u, const Point& v) {
    return (v.first - u.first) * (q.second - u.second) -
           (v.second - u.second) * (q.first - u.first);
  };
  const double s1 = side(a, b), s2 = side(b, c), s3 = side(c, a);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// The `points` of every element carrying this attribute text (e.g. "class='crease mountain'").
std::vector<std::vector<Point>> pointListsWith(const std::string& svg, const std::string& tag,
                                               const std::string& attribute) {
  std::vector<std::vector<Point>> lists;
  const std::regex element("<" + tag + " [^>]*" + attribute + "[^>]*>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), element);
       it != std::sregex_iterator(); ++it)
    for (const auto& list : pointLists(it->str(), tag)) lists.push_back(list);
  return lists;
}

TEST(ReportViews, FlatPiecesShowTheirHolesEmptyAndOutlined) {
  // An anti D-Form: each annulus's hole is outlined and no triangle covers its centre.
  const DForm anti = test::annulusDForm();
  const std::string svg = flatCurvatureSvg(anti, 500);
  const auto outlines = pointListsWith(svg, "polygon", "fill='none'");
  ASSERT_EQ(outlines.size(), 4u);  // per piece: the seam (the hole) and the free outline
  for (int p = 0; p < 2; ++p) {
    const std::vector<Point>& hole = outlines[size_t(2 * p)];
    const std::vector<Point>& outer = outlines[size_t(2 * p + 1)];
    ASSERT_EQ(hole.size(), anti.a.seam.size());
    ASSERT_EQ(outer.size(), anti.a.freeBoundaries[0].size());
    Point centre{0, 0};
    for (const Point& q : hole)
      centre = {centre.first + q.first / hole.size(), centre.second + q.second / hole.size()};
    const auto triangles = pointLists(svg, "polygon");
    int covering = 0, total = 0;
    for (const auto& t : triangles)
      if (t.size() == 3) {
        ++total;
        covering += inTriangle(centre, t[0], t[1], t[2]);
      }
    EXPECT_EQ(total, int(anti.a.F.rows() + anti.b.F.rows()));
    EXPECT_EQ(covering, 0) << "piece " << p;
  }
}

TEST(ReportViews, CreasesAreDrawnByTheirFoldAndTheSurfaceStaysWhite) {
  for (double h : {0.25, -0.25}) {
    const DForm model = test::creasedTetraDForm(6, 40.0, h);
    const std::string fold = h > 0 ? "class='crease mountain'" : "class='crease valley'";
    const std::string flat = flatCurvatureSvg(model, 500);
    for (const std::string& fill : fills(flat)) EXPECT_EQ(fill, "#ffffff");
    const auto lines = pointListsWith(flat, "polyline", fold);
    ASSERT_EQ(lines.size(), 2u) << fold;  // one hinge per piece
    // Each runs between two corners of its piece's outline (the seam polygon drawn before it).
    const auto outlines = pointListsWith(flat, "polygon", "fill='none'");
    for (int p = 0; p < 2; ++p) {
      EXPECT_EQ(lines[size_t(p)].size(), 7u);
      for (const Point& end : {lines[size_t(p)].front(), lines[size_t(p)].back()}) {
        double nearest = 1e9;
        for (const Point& q : outlines[size_t(p)])
          nearest = std::min(nearest, std::hypot(q.first - end.first, q.second - end.second));
        EXPECT_LT(nearest, 0.11);  // the same pixel, up to the printed tenth
      }
    }
    View curvature;
    curvature.curvature = true;
    const std::string shape = shapeSvg(model, curvature);
    EXPECT_EQ(pointListsWith(shape, "polyline", fold).size(), 2u);
    for (const std::string& fill : fills(shape)) EXPECT_EQ(fill, "#ffffff");
  }
  // A classic D-Form has no crease lines.
  EXPECT_EQ(flatCurvatureSvg(test::tetraDForm(6), 400).find("crease"), std::string::npos);
}

// report.html for `model`, rendered from a minimal report.json and an assembly sheet (empty: none).
std::string reportHtml(const DForm& model, const std::string& assemblySvg = "") {
  ReportSources sources = test::minimalReportSources();
  sources.assemblySvg = assemblySvg;
  const Result<std::string> html = renderReportHtml(sources, model, DFORM_TEMPLATES_DIR);
  EXPECT_TRUE(html.isOk()) << html.status().message();
  return html.isOk() ? html.value() : std::string();
}

TEST(ReportHtml, ANotJsonReportIsAnUnreadableInputNamingIt) {
  ReportSources sources;
  sources.reportJson = "{\"mode\": ";
  sources.reportPath = "out/report.json";
  const Result<std::string> html =
      renderReportHtml(sources, test::tetraDForm(6), DFORM_TEMPLATES_DIR);
  ASSERT_FALSE(html.isOk());
  EXPECT_EQ(html.status().code(), ErrorCode::InputUnreadable);
  EXPECT_EQ(html.status().message().rfind("out/report.json: not valid JSON", 0), 0u)
      << html.status().message();
}

TEST(ReportHtml, ListsEachCreaseWithItsFold) {
  // The disphenoid's hinges, drawn as creases, fold by acos(0.6) = 53.1 degrees: mountains.
  const std::string html = reportHtml(test::creasedTetraDForm(6, 40.0, 0.25));
  ASSERT_NE(html.find("<h2>Creases</h2>"), std::string::npos);
  for (const char* piece : {"A", "B"})
    EXPECT_NE(
        html.find(std::string("<tr><td>") + piece +
                  "</td><td class=\"num\">1</td><td>mountain</td><td class=\"num\">53.1</td>"),
        std::string::npos)
        << piece;
  EXPECT_NE(html.find("53.1 to 53.1"), std::string::npos);
  EXPECT_NE(html.find("class='crease mountain'"), std::string::npos);  // in the pictures
  const std::string classic = reportHtml(test::tetraDForm(6));
  EXPECT_EQ(classic.find("<h2>Creases</h2>"), std::string::npos);
  EXPECT_EQ(classic.find("crease"), std::string::npos);
}

TEST(ReportHtml, ShowsTheAssemblyPageWhenTheResultHasOne) {
  const std::string page =
      "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"><path id=\"view-seam\" "
      "d=\"M 0 0 L 1 1\"/></svg>\n";
  const std::string html = reportHtml(test::tetraDForm(6), page);
  const size_t heading = html.find("<h2>Assembly</h2>");
  ASSERT_NE(heading, std::string::npos);
  EXPECT_NE(html.find("<svg xmlns=\"http://www.w3.org/2000/svg\"><path id=\"view-seam\"", heading),
            std::string::npos)
      << "the page inline, without its XML declaration";
  EXPECT_EQ(html.find("<?xml"), std::string::npos);
  EXPECT_EQ(reportHtml(test::tetraDForm(6)).find("<h2>Assembly</h2>"), std::string::npos);
}

TEST(ReportPlot, DecadesAreEvenlySpacedAndZerosAreLeftOut) {
  // The total falls a decade per iteration; a term that is 0 at first has no point there.
  const std::vector<PlotSeries> series = {{"total", {{0, 1.0}, {1, 0.1}, {2, 0.01}, {3, 0.001}}},
                                          {"seam", {{1, 0.0}, {2, 1e-3}, {3, 1e-4}}}};
  const std::string svg = convergencePlotSvg(series, 600, 300);
  const auto lines = pointLists(svg, "polyline");
  ASSERT_EQ(lines.size(), 2u);
  const std::vector<Point>& total = lines[0];
  ASSERT_EQ(total.size(), 4u);
  const double decade = total[0].second - total[1].second;  // pixels per decade (y grows down)
  EXPECT_LT(decade, 0);
  for (std::size_t i = 1; i + 1 < total.size(); ++i) {
    EXPECT_NEAR(total[i].second - total[i + 1].second, decade, 0.15);
    EXPECT_NEAR(total[i + 1].first - total[i].first, total[1].first - total[0].first, 0.15);
  }
  EXPECT_EQ(lines[1].size(), 2u);
  EXPECT_NEAR(lines[1][0].second, total[3].second, 0.15);  // 1e-3 on both lines
  EXPECT_NEAR(lines[1][0].first, total[2].first, 0.15);    // at iteration 2
  // One grid label per decade from 1e-4 to 1e0, and both names in the legend.
  for (const char* label : {">1e-4<", ">1e-3<", ">1e-2<", ">1e-1<", ">1e0<", ">total<", ">seam<"})
    EXPECT_NE(svg.find(label), std::string::npos) << label;
}

TEST(ReportPlot, NothingPositiveSaysSo) {
  const std::string svg = convergencePlotSvg({{"total", {{0, 0.0}}}}, 600, 300);
  EXPECT_NE(svg.find("no positive objective"), std::string::npos);
  EXPECT_EQ(svg.find("<polyline"), std::string::npos);
}

}  // namespace
}  // namespace dform
