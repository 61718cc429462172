#pragma once
#include "millsim/std/Transform.h"

namespace millsim {

// MatrixTransform.matrix: an SFMatrix4f that must be a frame, so invertible:
// a singular matrix is refused as a bad value (the loader reports it at the attribute).
class FrameMatrixField : public SFMatrix4f {
public:
  using SFMatrix4f::SFMatrix4f;

protected:
  void validate(const glm::mat4& m) const override;
};

// H3DAPI's MatrixTransform (not X3D standard): places its children in the
// frame a 4×4 matrix gives, exactly as a Transform's matrix does.
class MatrixTransform : public TransformingNode {
public:
  static const NodeType& type();
  const NodeType& nodeType() const override { return type(); }

  FrameMatrixField matrix{this, "matrix", Access::InputOutput, glm::mat4(1.f),
                          "Child frame to parent frame, written row by row as H3DAPI writes it: the translation is "
                          "the 4th, 8th and 12th number (m, the only numbers <unit> converts). Must be invertible.",
                          Range::closed(-1e4, 1e4).in({.length = 1, .translationOnly = true})};

  glm::mat4 localMatrix() const override { return matrix.get(); }
};

}  // namespace millsim
