#pragma once
// Loader tests: a scene loaded from text (no plugin search path), and its first error.
#include <string>

#include "millsim/core/NodeRegistry.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::test {

inline LoadResult load(const std::string& text) {
  LoadOptions options;
  options.plugins.searchPath.clear();
  return loadSceneString(text, "test.x3d", builtinRegistry(), options);
}

inline const Diagnostic& firstError(const LoadResult& r) {
  for (const auto& d : r.diagnostics)
    if (d.severity == Severity::Error) return d;
  static Diagnostic none;
  return none;
}

}  // namespace millsim::test
