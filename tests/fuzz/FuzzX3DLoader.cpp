// libFuzzer target for the X3D loader: any byte string must yield either a
// Scene or diagnostics, never a crash, hang, leak or undefined behaviour.
// Built by tests/fuzz/standalone (clang only) and run by scripts/fuzz-parser.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "millsim/core/NodeRegistry.h"
#include "millsim/core/Scene.h"
#include "millsim/x3d/X3DLoader.h"

namespace {

// The standard X3D nodes, built once. Not builtinRegistry(): that one
// (nodes/BuiltinNodes.cpp) also registers the volume and haptics nodes, which
// would pull OpenVDB, VTK and the device code into this small clang build.
const millsim::NodeRegistry& registry() {
  static const millsim::NodeRegistry r = [] {
    millsim::NodeRegistry reg;
    millsim::registerStandardNodes(reg);
    return reg;
  }();
  return r;
}

const millsim::LoadOptions& options() {
  static const millsim::LoadOptions o = [] {
    millsim::LoadOptions opts;
    opts.allowFileAccess = false;  // no Inline / ImportLibrary: the fuzzer must not touch files
    opts.plugins.searchPath = {};
    opts.plugins.allowAnyPath = false;
    return opts;
  }();
  return o;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  millsim::LoadResult result = millsim::loadSceneString(text, "fuzz.x3d", registry(), options());
  // Exercise the diagnostics' formatting too.
  std::string report = result.report();
  if (result.ok()) {
    std::string tree = millsim::describeScene(*result.scene);
    (void)tree;
    (void)result.scene->nodeCount();
  }
  (void)report;
  return 0;
}
