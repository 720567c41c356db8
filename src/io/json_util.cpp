#include "io/json_util.h"

#include <algorithm>

#include "core/message_text.h"
#include "io/io_util.h"

namespace dform::io_detail {

Result<nlohmann::json> parseJson(const std::string& path, const std::string& text) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    return Status{ErrorCode::InputUnreadable,
                  path + ": not valid JSON (" + parserReason(e.what()) + ")"};
  }
}

Result<double> jsonUnitScale(const std::string& path, const nlohmann::json& doc) {
  if (!doc.is_object() || !doc.contains("units")) return 1.0;
  const nlohmann::json& units = doc["units"];
  const std::optional<double> scale =
      units.is_string() ? millimetresPerUnit(units.get<std::string>()) : std::nullopt;
  if (!scale)
    return Status{ErrorCode::InputUnreadable,
                  path + ": \"units\" must be \"mm\", \"cm\" or \"in\" (found " +
                      describeJsonValue(units) + ")"};
  return *scale;
}

Result<Eigen::MatrixXd> jsonPointList(const std::string& path, const nlohmann::json& list,
                                      const std::string& what, int dimension, double scale) {
  const std::string shape = dimension == 2 ? "[x, y]" : "[x, y, z]";
  if (!list.is_array())
    return Status{ErrorCode::InputUnreadable,
                  path + ": " + what + " is not a list of " + shape + " points"};
  Eigen::MatrixXd P(Eigen::Index(list.size()), dimension);
  for (std::size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& p = list[i];
    const bool ok =
        p.is_array() && p.size() == std::size_t(dimension) &&
        std::all_of(p.begin(), p.end(), [](const nlohmann::json& v) { return v.is_number(); });
    if (!ok)
      return Status{ErrorCode::InputUnreadable, path + ": " + what + " point " +
                                                    std::to_string(i + 1) + " is not " + shape +
                                                    " with numbers"};
    for (int k = 0; k < dimension; ++k)
      P(Eigen::Index(i), k) = scale * p[std::size_t(k)].get<double>();
  }
  return P;
}

}  // namespace dform::io_detail
