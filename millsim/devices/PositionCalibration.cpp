#include "millsim/devices/PositionCalibration.h"

#include <cmath>
#include <sstream>

namespace millsim {

namespace {

std::string numbers(const float* m, int n) {
  std::ostringstream os;
  for (int i = 0; i < n; ++i) os << (i ? " " : "") << m[i];
  return os.str();
}

}  // namespace

std::optional<glm::vec3> PositionCalibration::fromH3dMatrix(std::string_view text) {
  std::vector<float> m;
  try {
    m = parseMultiple<float>(text);
  } catch (const ValueError&) {
    return std::nullopt;
  }
  if (m.size() != 16) return std::nullopt;
  // Row-major, as H3DAPI writes a Matrix4f: translation in the last column.
  const float* r = m.data();
  const float lastRow[4] = {r[12], r[13], r[14], r[15]};
  if (std::abs(lastRow[0]) > 1e-6f || std::abs(lastRow[1]) > 1e-6f || std::abs(lastRow[2]) > 1e-6f ||
      std::abs(lastRow[3] - 1.f) > 1e-6f)
    throw ValueError("an H3DAPI 4x4 positionCalibration whose last row is '" + numbers(lastRow, 4) +
                     "' (not 0 0 0 1) is a projection, which MillSim does not apply");
  const float linear[9] = {r[0], r[1], r[2], r[4], r[5], r[6], r[8], r[9], r[10]};
  bool identity = true;
  for (int i = 0; i < 9; ++i) identity &= std::abs(linear[i] - (i % 4 == 0 ? 1.f : 0.f)) <= 1e-6f;
  if (!identity) {
    const float sx = std::sqrt(r[0] * r[0] + r[4] * r[4] + r[8] * r[8]);
    std::ostringstream why;
    why << "an H3DAPI 4x4 positionCalibration is read only as a translation (its 3x3 part the identity), and this "
           "one's 3x3 part is '"
        << numbers(linear, 9) << "'";
    if (std::abs(sx - 1.f) > 1e-4f) why << ", which scales by " << sx;
    why << ": MillSim maps device positions 1:1 in metres; turn them with orientationCalibration (which turns the "
           "tool too) and offset them with positionCalibration='"
        << r[3] << " " << r[7] << " " << r[11] << "'";
    throw ValueError(why.str());
  }
  return glm::vec3(r[3], r[7], r[11]);
}

void PositionCalibration::setFromString(std::string_view text) {
  if (const auto t = fromH3dMatrix(text)) return set(*t);
  SFVec3f::setFromString(text);
}

void PositionCalibration::setFromSceneText(std::string_view text, const UnitScale& units) {
  if (auto t = fromH3dMatrix(text)) {
    if (!units.si()) detail::convertToSI(*t, quantity::length, units);
    return set(*t);
  }
  SFVec3f::setFromSceneText(text, units);
}

}  // namespace millsim
