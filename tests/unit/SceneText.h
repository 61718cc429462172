#pragma once
// Loader tests: a scene loaded from text (no plugin search path), and its first error.
#include <stdexcept>
#include <string>

#include "millsim/core/NodeRegistry.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim::test {

inline LoadResult load(const std::string& text) {
  LoadOptions options;
  options.plugins.searchPath.clear();
  return loadSceneString(text, "test.x3d", builtinRegistry(), options);
}

// A whole X3D 4.0 document around `body`, with `head` inside <head> when
// given. The XML declaration is line 1, so the body starts on line 2.
inline std::string x3dScene(const std::string& body, const std::string& head = "") {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Immersive" version="4.0">)" +
         (head.empty() ? std::string() : "<head>" + head + "</head>") + "<Scene>" + body + "</Scene></X3D>";
}

// The node DEF'd `name`, as a T; throws if there is none of that type.
template <class T> T& defNode(const LoadResult& r, const char* name) {
  auto* n = dynamic_cast<T*>(r.scene->def(name).get());
  if (!n) throw std::runtime_error(std::string("no ") + name);
  return *n;
}

// The scene's one node of type T (the last, if several); throws if there is none.
template <class T> T& onlyNode(const LoadResult& r) {
  T* found = nullptr;
  r.scene->forEachNode([&](Node& n) {
    if (auto* t = dynamic_cast<T*>(&n)) found = t;
  });
  if (!found) throw std::runtime_error("no node of the type asked for");
  return *found;
}

inline const Diagnostic& firstError(const LoadResult& r) {
  for (const auto& d : r.diagnostics)
    if (d.severity == Severity::Error) return d;
  static Diagnostic none;
  return none;
}

}  // namespace millsim::test
