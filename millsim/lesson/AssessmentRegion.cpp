#include "millsim/lesson/AssessmentRegion.h"

namespace millsim {

void AssessmentRegion::initialize(DiagnosticSink& sink) {
  if (name.get().empty()) sink.error(location(), typeName() + " has no name (reports name each region)");
  if (children.get().empty() && tissues.get().empty())
    sink.error(location(), typeName() + " '" + name.get() +
                               "' is empty: give Box, Sphere or Cylinder shapes among its children, or tissues");
}

}  // namespace millsim
