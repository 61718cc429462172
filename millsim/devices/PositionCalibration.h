#pragma once
// PositionCalibration: a device's position offset (SFVec3f, m) that also
// reads the 4×4 matrix H3DAPI's devices take for the same field, so that an
// H3DAPI scene's device loads: the matrix's translation is the offset, and a
// uniform scale in it goes to the device's positionScale. A matrix that
// turns, scales unevenly, shears or projects is refused with what it does
// and what to write instead: MillSim turns device poses with
// orientationCalibration (which turns the tool too), and only a uniform
// scale keeps the felt forces those of the scene (docs/devices.md).
#include "millsim/core/Field.h"

namespace millsim {

class PositionCalibration : public SFVec3f {
public:
  using SFVec3f::SFVec3f;
  // Where a matrix's uniform scale goes (HapticsDevice::positionScale).
  void scaleInto(SFFloat& scale) { scale_ = &scale; }
  void setFromString(std::string_view text) override;
  void setFromSceneText(std::string_view text, const UnitScale& units) override;

private:
  struct Affine {
    glm::vec3 translation;
    float scale;
  };
  // The translation and uniform scale of an H3DAPI matrix written as 16
  // numbers row by row, or the ValueError saying what it does instead;
  // nullopt if the text is not 16 numbers.
  static std::optional<Affine> fromH3dMatrix(std::string_view text);
  void setScale(float s);

  SFFloat* scale_ = nullptr;
};

}  // namespace millsim
