// SPDX-License-Identifier: GPL-3.0-or-later
// io-internal: JSON helpers shared by the outline and curve readers (nlohmann-json stays private).
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "dform/core/status.h"

namespace dform::io_detail {

/// Parses `text` holding at most `maxPoints` points of `dimension` numbers, or InputUnreadable
/// naming `path` with the parser's one-line reason. The document is refused (InputInvalid) as
/// soon as it has more numbers than that many points have, or more lists and objects than they
/// and a handful more need: its tree would take gigabytes long before the points are counted (a
/// megabyte of "[]," is 350 000 arrays). An object with a key twice is refused (InputInvalid): a
/// reader would keep one of them silently.
Result<nlohmann::json> parseJson(const std::string& path, const std::string& text,
                                 std::size_t maxPoints, int dimension);

/// InputInvalid naming the first key of the object `doc` that is not in `allowed` (a misspelt
/// "creaess" would otherwise be passed over, and its creases with it); ok for a non-object.
Status onlyKnownKeys(const std::string& path, const nlohmann::json& doc,
                     const std::vector<std::string>& allowed);

/// Millimetres per unit from the object's optional "units" member (mm by default, cm, in).
Result<double> jsonUnitScale(const std::string& path, const nlohmann::json& doc);

/// A list of `dimension`-number points ([[x, y], ...] or [[x, y, z], ...]) scaled by `scale`, as
/// #P by dimension rows. `what` names the list in messages ("the outline").
Result<Eigen::MatrixXd> jsonPointList(const std::string& path, const nlohmann::json& list,
                                      const std::string& what, int dimension, double scale);

}  // namespace dform::io_detail
