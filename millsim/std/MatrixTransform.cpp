#include "millsim/std/MatrixTransform.h"

#include <cmath>

#include <glm/matrix.hpp>

namespace millsim {

const NodeType& MatrixTransform::type() {
  static const NodeType t = makeNodeType<MatrixTransform>(
      "MatrixTransform", "children", "H3DAPI grouping",
      "Groups child nodes in the frame a 4x4 matrix gives (H3DAPI's node; not X3D standard).");
  return t;
}

void FrameMatrixField::validate(const glm::mat4& m) const {
  const double det = glm::determinant(glm::dmat4(m));
  if (!std::isfinite(det) || std::abs(det) < 1e-12)
    throw ValueError("the matrix is singular (determinant " + formatNumber(det) +
                     "); expected an invertible matrix, a frame for the children");
}

}  // namespace millsim
