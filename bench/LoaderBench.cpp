// The X3D loader's cost against scene size: n sibling Transforms, and n
// nested ones. Loading must stay linear in the number of nodes (issue 16:
// 100 000 nodes within 2 s on the 2-core box): items_per_second (nodes per
// second) should not fall as n grows. Nesting past 256 levels is refused with
// MillSim's own message: BM_RefuseDeepNesting times that refusal at 10 000
// levels (it must be quick, and it fails the benchmark if the message changes).
#include <benchmark/benchmark.h>

#include <string>

#include "millsim/core/NodeRegistry.h"
#include "millsim/x3d/X3DLoader.h"

namespace {

std::string siblings(int n) {
  std::string s = "<?xml version=\"1.0\"?>\n<X3D profile=\"Immersive\" version=\"3.3\"><Scene>\n";
  for (int i = 0; i < n; ++i) s += "<Transform translation=\"0 0 " + std::to_string(i % 100) + "\"/>\n";
  return s + "</Scene></X3D>\n";
}

std::string nested(int n) {
  std::string s = "<?xml version=\"1.0\"?>\n<X3D profile=\"Immersive\" version=\"3.3\"><Scene>\n";
  for (int i = 0; i < n; ++i) s += "<Transform>";
  for (int i = 0; i < n; ++i) s += "</Transform>";
  return s + "\n</Scene></X3D>\n";
}

void load(benchmark::State& state, const std::string& text) {
  const millsim::NodeRegistry registry = millsim::builtinRegistry();
  for (auto _ : state) {
    millsim::LoadResult r = millsim::loadSceneString(text, "bench.x3d", registry);
    if (!r.ok()) state.SkipWithError(r.report().c_str());
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));  // nodes per second
}

// The refusal of a document nested deeper than the loader reads: an error in
// MillSim's words (not libxml2's "use XML_PARSE_HUGE"), quickly.
void BM_RefuseDeepNesting(benchmark::State& state) {
  const millsim::NodeRegistry registry = millsim::builtinRegistry();
  const std::string text = nested(int(state.range(0)));
  for (auto _ : state) {
    millsim::LoadResult r = millsim::loadSceneString(text, "deep.x3d", registry);
    if (r.ok() || r.report().find("elements nest deeper than 256 levels, the most MillSim reads") == std::string::npos) {
      state.SkipWithError(("expected the nesting-limit error, got: " + r.report()).c_str());
      break;
    }
    benchmark::DoNotOptimize(r);
  }
}

void BM_LoadSiblings(benchmark::State& state) { load(state, siblings(int(state.range(0)))); }
void BM_LoadNested(benchmark::State& state) { load(state, nested(int(state.range(0)))); }

}  // namespace

BENCHMARK(BM_LoadSiblings)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LoadNested)->Arg(100)->Arg(250)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RefuseDeepNesting)->Arg(10000)->Unit(benchmark::kMillisecond);
