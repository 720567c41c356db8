// Internal: JSON helpers shared by the outline and curve readers and the writers of reports and
// manifests (nlohmann-json stays private).
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>

#include "dform/core/status.h"

namespace dform::io_detail {

/// Parses `text` holding at most `maxPoints` points, or InputUnreadable naming `path` with the
/// parser's one-line reason. The document is refused (InputInvalid) as soon as it has more values
/// than that many points can have: its tree would take gigabytes long before the points are
/// counted (a megabyte of "[]," is 350 000 arrays).
Result<nlohmann::json> parseJson(const std::string& path, const std::string& text,
                                 std::size_t maxPoints);

/// Millimetres per unit from the object's optional "units" member (mm by default, cm, in).
Result<double> jsonUnitScale(const std::string& path, const nlohmann::json& doc);

/// A list of `dimension`-number points ([[x, y], ...] or [[x, y, z], ...]) scaled by `scale`, as
/// #P by dimension rows. `what` names the list in messages ("the outline").
Result<Eigen::MatrixXd> jsonPointList(const std::string& path, const nlohmann::json& list,
                                      const std::string& what, int dimension, double scale);

/// `value` as a JSON number, or null when it is not finite (JSON has no NaN or infinity): a figure
/// that was not measured.
nlohmann::json numberOrNull(double value);

}  // namespace dform::io_detail
