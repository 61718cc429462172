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

std::optional<PositionCalibration::Affine> PositionCalibration::fromH3dMatrix(std::string_view text) {
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
  // A uniform scale s is s times the identity: its diagonal is its scale.
  const float s = (linear[0] + linear[4] + linear[8]) / 3.f;
  bool uniform = s > 0.f;
  for (int i = 0; i < 9; ++i) uniform &= std::abs(linear[i] - (i % 4 == 0 ? s : 0.f)) <= 1e-6f * std::max(1.f, s);
  if (!uniform) {
    std::ostringstream why;
    why << "an H3DAPI 4x4 positionCalibration is read as a translation and a uniform scale (its 3x3 part s times the "
           "identity, s > 0), and this one's 3x3 part is '"
        << numbers(linear, 9)
        << "': MillSim scales device positions only uniformly (positionScale), so that the felt forces stay the "
           "scene's, and turns them with orientationCalibration (which turns the tool too); write "
           "positionScale='s' and positionCalibration='"
        << r[3] << " " << r[7] << " " << r[11] << "' instead";
    throw ValueError(why.str());
  }
  return Affine{glm::vec3(r[3], r[7], r[11]), s};
}

void PositionCalibration::setScale(float s) {
  // A matrix that only translates leaves a positionScale written beside it.
  if (scale_ && std::abs(s - 1.f) > 1e-6f) scale_->setFromString(formatNumber(double(s)));
}

void PositionCalibration::setFromString(std::string_view text) {
  if (const auto a = fromH3dMatrix(text)) {
    setScale(a->scale);
    return set(a->translation);
  }
  SFVec3f::setFromString(text);
}

void PositionCalibration::setFromSceneText(std::string_view text, const UnitScale& units) {
  if (auto a = fromH3dMatrix(text)) {
    if (!units.si()) detail::convertToSI(a->translation, quantity::length, units);
    setScale(a->scale);
    return set(a->translation);
  }
  SFVec3f::setFromSceneText(text, units);
}

}  // namespace millsim
