// SPDX-License-Identifier: GPL-3.0-or-later
// The only translation unit that includes svgpp (expensive to compile). svgpp walks the document,
// resolves element transforms, lengths and basic shapes into absolute path commands; this file
// records them per element and flattens them in millimetres once the element's transform is known.
#include "svg_outline.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <map>
#include <new>
#include <optional>
#include <rapidxml_ns/rapidxml_ns.hpp>
#include <string_view>
#include <svgpp/policy/xml/rapidxml_ns.hpp>
#include <svgpp/svgpp.hpp>

#include "dform/core/constants.h"
#include "dform/core/message_text.h"
#include "flatten.h"
#include "io_util.h"
#include "svg_viewport.h"

namespace dform::io_detail {
namespace {

using Vec2 = Eigen::Vector2d;

/// Deeper element nesting is refused before parsing: rapidxml and svgpp recurse per level, and no
/// drawing needs it.
constexpr int kMaxElementDepth = 256;

/// A problem found during the traversal; the catch site adds the file and element names.
struct SvgProblem {
  ErrorCode code;
  std::string what;
};

// ---- Traversal --------------------------------------------------------------------------------

/// State shared by all element contexts of one document.
struct Document {
  svgpp::factory::length::unitless<> lengths;  // 96 px per inch by default, as CSS says
  double tolerance = 1e-4;                     // mm, flattening
  double closeTolerance = 0.01;                // mm, a subpath's end this close to its start
  double maxCoordinate = 1e6;                  // mm
  std::size_t maxPoints = 0;                   // OutlineReadOptions::maxPoints
  std::map<std::string, int> elementCounts;    // per element name, for "path 2"
  std::string currentLabel = "the document";   // element being read, for messages
  Drawing drawing;
  std::size_t totalPoints = 0;

  /// Stops the reading when the document needs more than maxPoints points: every path command
  /// draws at least one, so `pending` counts the commands and points not yet stored in `loops`.
  void checkPoints(std::size_t pending) const {
    if (totalPoints + pending > maxPoints)
      throw SvgProblem{ErrorCode::InputInvalid,
                       "brings the outlines to more than " + std::to_string(maxPoints) +
                           " points (the limit) at a flatten tolerance of " + fmt(tolerance) +
                           " mm"};
  }
};

/// One recorded path command in user coordinates (absolute, no shorthands).
struct Command {
  enum Kind { Move, Line, Quadratic, Cubic, Arc, Close } kind;
  std::array<double, 7> v{};  // operands in SVG order; arc flags as 0/1
};

bool displayNone(const XmlNode* node) {
  if (auto display = attributeValue(node, "display"); display && trim(*display) == "none")
    return true;
  const std::string_view style = attributeValue(node, "style").value_or("");
  for (std::size_t start = 0; start < style.size();) {
    std::size_t end = style.find(';', start);
    if (end == std::string_view::npos) end = style.size();
    const std::string_view declaration = style.substr(start, end - start);
    const std::size_t colon = declaration.find(':');
    if (colon != std::string_view::npos && trim(declaration.substr(0, colon)) == "display" &&
        trim(declaration.substr(colon + 1)) == "none")
      return true;
    start = end + 1;
  }
  return false;
}

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower((unsigned char)x) == std::tolower((unsigned char)y);
         });
}

/// Whether an element marks itself and its content as crease lines: "crease" among its classes,
/// or a layer or group labelled "crease" or "creases" (Inkscape's inkscape:label, or the id).
bool marksCreases(const XmlNode* node) {
  const std::string_view classes = attributeValue(node, "class").value_or("");
  for (std::size_t start = 0; start < classes.size();) {
    std::size_t end = classes.find_first_of(" \t\r\n", start);
    if (end == std::string_view::npos) end = classes.size();
    if (equalsIgnoringCase(classes.substr(start, end - start), "crease")) return true;
    start = end + 1;
  }
  for (const char* name : {"label", "id"}) {
    const std::string_view value = trim(attributeValue(node, name).value_or(""));
    if (equalsIgnoringCase(value, "crease") || equalsIgnoringCase(value, "creases")) return true;
  }
  return false;
}

/// The context svgpp calls for every processed element (<svg>, <g>, <a> and the shapes).
class SvgContext {
 public:
  SvgContext(Document& document, const Affine& transform)
      : document_(&document), transform_(transform) {}

  SvgContext(SvgContext& parent, const XmlNode* element)
      : document_(parent.document_),
        transform_(parent.transform_),
        parentLabel_(document_->currentLabel),
        hidden_(displayNone(element)),
        crease_(parent.crease_ || marksCreases(element)) {
    const std::string name(element->local_name(), element->local_name_size());
    label_ = name + " " + std::to_string(++document_->elementCounts[name]);
    if (auto id = attributeValue(element, "id")) {
      // XML reads a line break or tab in an attribute value as a space (attribute-value
      // normalisation); printable() then keeps any other control character off the line.
      std::string shown(*id);
      std::replace_if(
          shown.begin(), shown.end(), [](char c) { return c == '\n' || c == '\r' || c == '\t'; },
          ' ');
      label_ += " (id \"" + printable(shown) + "\")";
    }
    document_->currentLabel = label_;
    if (name == "svg")
      throw SvgProblem{ErrorCode::InputInvalid, "is a nested <svg>, which is not supported"};
  }

  // Length policy: lengths with units become user units.
  using length_factory_type = svgpp::factory::length::unitless<>;
  const length_factory_type& length_factory() const { return document_->lengths; }

  // Transform events: the element's own transform, applied before its parents'.
  void transform_matrix(const boost::array<double, 6>& m) {
    Affine local;
    local.linear << m[0], m[2], m[1], m[3];
    local.offset << m[4], m[5];
    transform_ = transform_.then(local);
  }

  // Path events (the path policy makes every command absolute and removes shorthands).
  void path_move_to(double x, double y, svgpp::tag::coordinate::absolute) {
    record({Command::Move, {x, y}});
  }
  void path_line_to(double x, double y, svgpp::tag::coordinate::absolute) {
    record({Command::Line, {x, y}});
  }
  void path_quadratic_bezier_to(double x1, double y1, double x, double y,
                                svgpp::tag::coordinate::absolute) {
    record({Command::Quadratic, {x1, y1, x, y}});
  }
  void path_cubic_bezier_to(double x1, double y1, double x2, double y2, double x, double y,
                            svgpp::tag::coordinate::absolute) {
    record({Command::Cubic, {x1, y1, x2, y2, x, y}});
  }
  void path_elliptical_arc_to(double rx, double ry, double rotation, bool largeArc, bool sweep,
                              double x, double y, svgpp::tag::coordinate::absolute) {
    record({Command::Arc, {rx, ry, rotation, double(largeArc), double(sweep), x, y}});
  }
  void path_close_subpath() { record({Command::Close, {}}); }
  void path_exit() {}

  /// Keeps a path command for flattening. An element with too many is refused as it is read,
  /// before they take memory: every drawing command adds at least one point to the outline, and
  /// moveto and closepath commands, which draw nothing, may not outnumber the point limit either.
  void record(const Command& command) {
    commands_.push_back(command);
    if (command.kind != Command::Move && command.kind != Command::Close)
      document_->checkPoints(++drawingCommands_);
    else if (commands_.size() - drawingCommands_ > document_->maxPoints)
      throw SvgProblem{ErrorCode::InputInvalid, "has more than " +
                                                    std::to_string(document_->maxPoints) +
                                                    " moveto and closepath commands (the limit)"};
  }

  bool displayed() const { return !hidden_; }

  void on_exit_element() {
    // The transform is only certain once all attributes are read, so flattening waits till here.
    if (!hidden_ && !commands_.empty()) flattenCommands();
    document_->currentLabel = parentLabel_;
  }

 private:
  Vec2 toPage(double x, double y) const {
    const Vec2 p = transform_(Vec2(x, y));
    for (int k = 0; k < 2; ++k) {
      if (!(std::abs(p(k)) <= document_->maxCoordinate))
        throw SvgProblem{
            ErrorCode::InputInvalid,
            "has a coordinate that " + describeBadCoordinate(p(k), document_->maxCoordinate)};
    }
    return p;
  }

  void flattenCommands();
  void appendArc(const Vec2& fromUser, const Command& c, std::vector<Vec2>& out) const;
  void finishSubpath(std::vector<Vec2>& points, bool closed, int index, int subpathCount);

  Document* document_;
  Affine transform_;
  std::string parentLabel_;
  std::string label_;
  bool hidden_ = false;
  bool crease_ = false;  // the element draws crease lines, not outlines
  std::vector<Command> commands_;
  std::size_t drawingCommands_ = 0;  // commands_ other than Move and Close
};

void SvgContext::flattenCommands() {
  int subpathCount = 0;
  for (const Command& c : commands_) subpathCount += c.kind == Command::Move;
  const double tolerance = document_->tolerance;
  std::vector<Vec2> points;  // current subpath in page mm
  Vec2 startUser = Vec2::Zero(), currentUser = Vec2::Zero();
  int index = 0;
  bool closed = false;
  for (const Command& c : commands_) {
    if (c.kind == Command::Move || c.kind == Command::Close) {
      if (c.kind == Command::Close) closed = true;
      finishSubpath(points, closed, index, subpathCount);
      closed = false;
      if (c.kind == Command::Move) {
        startUser = currentUser = {c.v[0], c.v[1]};
        ++index;
      } else {
        currentUser = startUser;  // after Z the pen is back at the subpath's start
      }
      continue;
    }
    if (points.empty()) points.push_back(toPage(currentUser.x(), currentUser.y()));
    switch (c.kind) {
      case Command::Line:
        points.push_back(toPage(c.v[0], c.v[1]));
        currentUser = {c.v[0], c.v[1]};
        break;
      case Command::Quadratic:
      case Command::Cubic: {
        std::vector<Vec2> control = {points.back()};
        const int operands = c.kind == Command::Quadratic ? 4 : 6;
        for (int k = 0; k < operands; k += 2) control.push_back(toPage(c.v[k], c.v[k + 1]));
        if (!appendBezier(control, tolerance, points))
          throw SvgProblem{ErrorCode::InputInvalid,
                           "needs more than " + fmt(kMaxStepsPerCurve) +
                               " points per curve at a flatten tolerance of " + fmt(tolerance) +
                               " mm"};
        currentUser = {c.v[operands - 2], c.v[operands - 1]};
        break;
      }
      case Command::Arc:
        appendArc(currentUser, c, points);
        currentUser = {c.v[5], c.v[6]};
        break;
      default: break;
    }
    document_->checkPoints(points.size());
  }
  finishSubpath(points, closed, index, subpathCount);
}

/// Elliptical arc per SVG 1.1 appendix F.6.5 (endpoint to centre parameterisation, radii scaled
/// up when too small), sampled in equal angle steps chosen for the chord deviation in mm.
void SvgContext::appendArc(const Vec2& fromUser, const Command& c, std::vector<Vec2>& out) const {
  const Vec2 toUser(c.v[5], c.v[6]);
  const Vec2 end = toPage(toUser.x(), toUser.y());
  double rx = std::abs(c.v[0]), ry = std::abs(c.v[1]);
  if (fromUser == toUser) return;  // the spec omits such an arc
  if (rx == 0.0 || ry == 0.0) {    // ... and draws a straight line for a zero radius
    out.push_back(end);
    return;
  }
  const double phi = c.v[2] * kPi / 180.0;
  const bool largeArc = c.v[3] != 0.0, sweep = c.v[4] != 0.0;
  const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(phi).toRotationMatrix();
  const Vec2 half = rotation.transpose() * (0.5 * (fromUser - toUser));  // x1', y1'
  const double lambda = half.x() * half.x() / (rx * rx) + half.y() * half.y() / (ry * ry);
  if (lambda > 1.0) {
    rx *= std::sqrt(lambda);
    ry *= std::sqrt(lambda);
  }
  const double rx2 = rx * rx, ry2 = ry * ry;
  const double num = rx2 * ry2 - rx2 * half.y() * half.y() - ry2 * half.x() * half.x();
  const double den = rx2 * half.y() * half.y() + ry2 * half.x() * half.x();
  const double coef = (largeArc == sweep ? -1.0 : 1.0) * std::sqrt(std::max(0.0, num / den));
  const Vec2 centreRotated(coef * rx * half.y() / ry, -coef * ry * half.x() / rx);
  const Vec2 centre = rotation * centreRotated + 0.5 * (fromUser + toUser);
  const double theta1 =
      std::atan2((half.y() - centreRotated.y()) / ry, (half.x() - centreRotated.x()) / rx);
  const double theta2 =
      std::atan2((-half.y() - centreRotated.y()) / ry, (-half.x() - centreRotated.x()) / rx);
  double delta = theta2 - theta1;
  if (sweep && delta < 0.0) delta += 2.0 * kPi;
  if (!sweep && delta > 0.0) delta -= 2.0 * kPi;

  // In page mm the arc is C + U cos(t) + V sin(t); |second derivative| <= sqrt(|U|^2 + |V|^2).
  const Vec2 pageCentre = transform_(centre);
  const Vec2 u = transform_.linear * rotation * Vec2(rx, 0.0);
  const Vec2 v = transform_.linear * rotation * Vec2(0.0, ry);
  if (!pageCentre.allFinite() || !u.allFinite() || !v.allFinite() || !std::isfinite(delta)) {
    out.push_back(end);  // radii so large that the arc is a straight line in double precision
    return;
  }
  const long steps = stepsForDeviation(std::sqrt(u.squaredNorm() + v.squaredNorm()),
                                       std::abs(delta), document_->tolerance);
  if (steps == 0)
    throw SvgProblem{ErrorCode::InputInvalid,
                     "has an arc that needs more than " + fmt(kMaxStepsPerCurve) +
                         " points at a flatten tolerance of " + fmt(document_->tolerance) + " mm"};
  for (long k = 1; k < steps; ++k) {
    const double t = theta1 + delta * double(k) / double(steps);
    out.push_back(pageCentre + u * std::cos(t) + v * std::sin(t));
  }
  out.push_back(end);  // exactly the commanded end point
}

void SvgContext::finishSubpath(std::vector<Vec2>& points, bool closed, int index,
                               int subpathCount) {
  if (points.size() < 2) {  // a lone moveto draws nothing
    points.clear();
    return;
  }
  const std::string label =
      label_ + (subpathCount > 1 ? " (subpath " + std::to_string(index) + ")" : "");
  const double gap = (points.back() - points.front()).norm();
  // A gap below the closing tolerance is below what a designer sees: they meant it closed, and
  // dropping the end point moves the outline by less than that.
  const bool closedLoop = closed || gap <= document_->closeTolerance;
  if (crease_ && closedLoop) {
    document_->currentLabel = label;
    throw SvgProblem{
        ErrorCode::InputInvalid,
        "is a closed crease line (its ends meet); a crease runs from boundary to boundary"};
  }
  if (!crease_ && gap <= document_->closeTolerance) {
    points.pop_back();
  } else if (!crease_ && !closed) {
    document_->currentLabel = label;
    throw SvgProblem{ErrorCode::InputInvalid,
                     "is open (its end is " + fmt(gap) + " mm from its start)"};
  }
  DrawnLine line;
  line.points.resize(Eigen::Index(points.size()), 2);
  for (std::size_t i = 0; i < points.size(); ++i)
    line.points.row(Eigen::Index(i)) = points[i].transpose();
  line.label = label;
  document_->totalPoints += points.size();
  (crease_ ? document_->drawing.creases : document_->drawing.loops).push_back(std::move(line));
  points.clear();
}

// ---- svgpp configuration ------------------------------------------------------------------------

struct ChildContextFactories {
  template <class ParentContext, class ElementTag>
  struct apply {
    using type = svgpp::factory::context::on_stack_with_xml_element<SvgContext>;
  };
};

/// Hidden groups (display:none) are not entered.
struct TraversalControl {
  template <class Context>
  static bool proceed_to_element_content(const Context& context) {
    return context.displayed();
  }
  template <class Context>
  static bool proceed_to_next_child(const Context&) {
    return true;
  }
  template <class Context, class XMLElement>
  static bool process_child(const Context&, const XMLElement&) {
    return true;
  }
};

/// Unknown or misplaced elements and attributes (editor metadata, CSS we do not need) are
/// skipped; values we need but cannot parse stop the reading with a message.
struct ErrorPolicy {
  using context_type = SvgContext;
  template <class Context, class XMLElement, class Name>
  static bool unknown_element(const Context&, const XMLElement&, const Name&) {
    return true;
  }
  template <class Context, class XMLAttribute, class Name, class Source>
  static bool unknown_attribute(const Context&, const XMLAttribute&, const Name&, Source) {
    return true;
  }
  template <class Context, class XMLAttribute, class Name, class Namespace, class Source>
  static bool unknown_attribute(const Context&, const XMLAttribute&, const Name&, Namespace,
                                Source) {
    return true;
  }
  template <class Context>
  static bool unexpected_attribute(const Context&, svgpp::detail::attribute_id,
                                   svgpp::tag::source::attribute) {
    return true;
  }
  template <class Context, class AttributeTag>
  static bool required_attribute_not_found(const Context&, AttributeTag) {
    return true;
  }
  template <class Context, class XMLElement>
  static bool unexpected_element(const Context&, const XMLElement&) {
    return true;
  }
  template <class Context, class AttributeTag, class Value>
  static bool parse_failed(const Context&, AttributeTag, const Value& value) {
    const std::string name = svgpp::attribute_name<char>::get<AttributeTag>();
    if (const auto token = nonFiniteNumber(std::string(boost::begin(value), boost::end(value))))
      throw SvgProblem{ErrorCode::InputInvalid,
                       "has a non-finite number '" + *token + "' in its '" + name + "' attribute"};
    throw SvgProblem{ErrorCode::InputUnreadable, "has a malformed '" + name + "' attribute"};
  }
  template <class Context, class AttributeTag>
  static bool negative_value(const Context&, AttributeTag) {
    throw SvgProblem{
        ErrorCode::InputInvalid,
        std::string("has a negative '") + svgpp::attribute_name<char>::get<AttributeTag>() + "'"};
  }
};

using ProcessedElements =
    boost::mpl::set<svgpp::tag::element::svg, svgpp::tag::element::g, svgpp::tag::element::a,
                    svgpp::tag::element::path, svgpp::tag::element::rect,
                    svgpp::tag::element::circle, svgpp::tag::element::ellipse,
                    svgpp::tag::element::line, svgpp::tag::element::polyline,
                    svgpp::tag::element::polygon>::type;

using ProcessedAttributes = boost::mpl::insert<svgpp::traits::shapes_attributes_by_element,
                                               svgpp::tag::attribute::transform>::type;

using DocumentTraversal = svgpp::document_traversal<
    svgpp::processed_elements<ProcessedElements>, svgpp::processed_attributes<ProcessedAttributes>,
    svgpp::context_factories<ChildContextFactories>,
    svgpp::length_policy<svgpp::policy::length::forward_to_method<SvgContext>>,
    svgpp::document_traversal_control_policy<TraversalControl>, svgpp::error_policy<ErrorPolicy>>;

}  // namespace

Result<Drawing> readSvgDrawing(const std::string& path, std::string text,
                               const OutlineReadOptions& options) {
  auto fail = [&](ErrorCode code, const std::string& what) {
    return Status{code, path + ": " + what};
  };
  if (elementDepth(text) > kMaxElementDepth)
    return fail(ErrorCode::InputUnreadable,
                "elements are nested more than " + std::to_string(kMaxElementDepth) + " deep");

  // Parse; a root <svg> without the SVG namespace (common in hand-written files) gets it, since
  // svgpp only reads elements in that namespace.
  std::vector<char> buffer;
  rapidxml_ns::xml_document<char> xml;
  const XmlNode* root = nullptr;
  for (int attempt = 0; attempt < 2; ++attempt) {
    buffer.assign(text.begin(), text.end());
    buffer.push_back('\0');
    try {
      xml.clear();
      xml.parse<rapidxml_ns::parse_no_data_nodes>(buffer.data());
    } catch (const rapidxml_ns::parse_error& e) {
      const std::size_t offset = std::size_t(e.where<char>() - buffer.data());
      return fail(ErrorCode::InputUnreadable, std::string("not well-formed XML (") + e.what() +
                                                  " at byte " + std::to_string(offset) + ")");
    }
    root = xml.first_node();
    while (root && root->type() != rapidxml_ns::node_element) root = root->next_sibling();
    if (!root || std::string_view(root->local_name(), root->local_name_size()) != "svg")
      return fail(ErrorCode::InputUnreadable, "not an SVG file (no <svg> root element)");
    if (root->namespace_uri_size() != 0 || attempt == 1) break;
    const std::size_t nameEnd = std::size_t(root->name() - buffer.data()) + root->name_size();
    text.insert(nameEnd, " xmlns=\"http://www.w3.org/2000/svg\"");
  }

  const Result<RootViewport> viewport = rootViewport(root);
  if (!viewport.isOk()) return fail(viewport.status().code(), viewport.status().message());
  // The page frame is y-up (outlines are counter-clockwise in it); flipping about the page
  // height keeps coordinates positive and what the designer sees unmirrored.
  Affine flip;
  flip.linear(1, 1) = -1.0;
  flip.offset.y() = viewport.value().pageHeight.value_or(0.0);

  Document document;
  document.tolerance = options.flattenTolerance;
  document.closeTolerance = options.closeTolerance;
  document.maxCoordinate = options.maxCoordinate;
  document.maxPoints = options.maxPoints;
  const Vec2 size = viewport.value().userViewportSize;
  document.lengths.set_viewport_size(size.x(), size.y());
  SvgContext rootContext(document, flip.then(viewport.value().userToPage));
  try {
    DocumentTraversal::load_document(root, rootContext);
    rootContext.on_exit_element();
  } catch (const SvgProblem& problem) {
    return fail(problem.code, document.currentLabel + " " + problem.what);
  } catch (const std::bad_alloc&) {  // the machine's limit, not the file's fault (exit 2)
    return fail(ErrorCode::Usage, "out of memory while reading it");
  } catch (const std::exception& e) {
    return fail(ErrorCode::InputUnreadable,
                document.currentLabel + ": " + printable(e.what(), 200));
  } catch (...) {  // never let a parser surprise cross the module boundary
    return fail(ErrorCode::InputUnreadable, document.currentLabel + " could not be read");
  }
  return std::move(document.drawing);
}

}  // namespace dform::io_detail
