#pragma once
// PositionCalibration: a device's position offset (SFVec3f, m) that also
// reads the 4×4 matrix H3DAPI's devices take for the same field, so that an
// H3DAPI scene's device loads: a matrix that only translates is that
// offset; one that turns, scales or projects is refused with what it does,
// since MillSim maps device positions 1:1 in metres and turns them with
// orientationCalibration (which turns the tool too).
#include "millsim/core/Field.h"

namespace millsim {

class PositionCalibration : public SFVec3f {
public:
  using SFVec3f::SFVec3f;
  void setFromString(std::string_view text) override;
  void setFromSceneText(std::string_view text, const UnitScale& units) override;

private:
  // The translation of an H3DAPI matrix written as 16 numbers row by row, or
  // the ValueError saying why it is not a pure translation; nullopt if the
  // text is not 16 numbers.
  static std::optional<glm::vec3> fromH3dMatrix(std::string_view text);
};

}  // namespace millsim
