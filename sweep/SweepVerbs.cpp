#include "sweep/SweepVerbs.h"

namespace millsim::sweep {

const std::vector<VerbSpec>& sweepVerbs() {
  static const std::vector<VerbSpec> verbs{
      {"replay",
       {"replay"},
       {{"scene", ParamKind::Path, "", true, 0, 0, "the X3D scene"},
        {"trajectory", ParamKind::Path, "--trajectory", true, 0, 0,
         "a trajectory CSV, or a run's --log (grading a class's sessions: {\"glob\": \"sessions/*.csv\"})"},
        {"renderer", ParamKind::Renderer, "--renderer", false, 0, 0, "replaces the scene's renderer"},
        {"rate", ParamKind::Number, "--rate", false, 1, 20000, "haptic rate, Hz"},
        {"set", ParamKind::Override, "--set", false, 0, 0, "TYPE.FIELD=VALUE, e.g. BarbicRenderer.pointShellScale=2"}},
       {"--log", "log.csv", "--report", "report.json"},
       "report.json",
       "replays a trajectory or reviews a run's log; the cell keeps the frame log and the lesson report"},
      {"bench physical",
       {"bench", "physical"},
       {{"renderer", ParamKind::Renderer, "--renderer", false, 0, 0, "a registered renderer (default: every one)"},
        {"voxel", ParamKind::Number, "--voxel-sizes", false, 0.01, 1.0, "voxel size h, mm"},
        {"scene", ParamKind::Text, "--scene", false, 0, 0, "a physical scene: half-space, ball, ..., mesh-ball"},
        {"set", ParamKind::RendererField, "--set", false, 0, 0, "FIELD=VALUE of the renderers, e.g. pointShellScale=2"},
        {"quick", ParamKind::Flag, "--quick", false, 0, 0, "one sub-voxel phase"}},
       {"--csv", "result.csv", "--md", "result.md"},
       "result.csv",
       "force, torque and pose error against the rigid tool (p50_us and p99_us are timings)"},
      {"bench procedure",
       {"bench", "procedure"},
       {{"renderer", ParamKind::Renderer, "--renderer", false, 0, 0, "a registered renderer (default: every one)"},
        {"field", ParamKind::Text, "--field", false, 0, 0, "a resolution field, e.g. pointShellScale"},
        {"values", ParamKind::Text, "--values", false, 0, 0, "its values, e.g. 1,2"},
        {"scene", ParamKind::Path, "--scene", true, 0, 0, "the scene (its renderer is replaced)"},
        {"trajectory", ParamKind::Path, "--trajectory", true, 0, 0, "the procedure"}},
       {"--csv", "result.csv"},
       "result.csv",
       "frame times by phase of a procedure (its columns are timings)"},
      {"bench stability",
       {"bench", "stability"},
       {{"renderer", ParamKind::Renderer, "--renderer", false, 0, 0, "a registered renderer (default: every one)"},
        {"mass", ParamKind::Number, "--mass", false, 0.01, 10, "hand mass, kg"},
        {"damping", ParamKind::Number, "--damping", false, 0, 1000, "hand damping, N·s/m"},
        {"stiffness", ParamKind::Number, "--stiffness", false, 0, 100000, "hand stiffness, N/m"},
        {"scenario", ParamKind::Text, "--scenario", false, 0, 0, "a scenario, e.g. slide-50mm/s"},
        {"drop", ParamKind::Number, "--drop", false, 0, 0.5, "fraction of device samples dropped"},
        {"seed", ParamKind::Number, "--seed", false, 0, 1e18, "seed of the dropped samples", true}},
       {"--csv", "result.csv"},
       "result.csv",
       "the closed loop's passivity, limit cycles and release per grip and scenario (the soak grid)"},
      {"bench zwidth",
       {"bench", "zwidth"},
       {{"renderer", ParamKind::Renderer, "--renderer", false, 0, 0, "a registered renderer (default: every one)"},
        {"quick", ParamKind::Flag, "--quick", false, 0, 0, "only the measured arm's grip"},
        {"from", ParamKind::Number, "--from", false, 1, 1e9, "lowest stiffness tried, N/m"},
        {"to", ParamKind::Number, "--to", false, 1, 1e9, "highest stiffness tried, N/m"}},
       {"--csv", "result.csv", "--md", "result.md"},
       "result.csv",
       "the stiffness each renderer renders stably under each grip"},
  };
  return verbs;
}

const VerbSpec* findVerb(const std::string& name) {
  for (const VerbSpec& v : sweepVerbs())
    if (v.name == name) return &v;
  return nullptr;
}

const ParamSpec* findParam(const VerbSpec& verb, const std::string& name) {
  for (const ParamSpec& p : verb.params)
    if (p.name == name) return &p;
  return nullptr;
}

std::string kindName(ParamKind kind) {
  switch (kind) {
    case ParamKind::Path: return "a file in the sweep's folder";
    case ParamKind::Text: return "a string";
    case ParamKind::Number: return "a number";
    case ParamKind::Renderer: return "a renderer type";
    case ParamKind::Override: return "TYPE.FIELD=VALUE";
    case ParamKind::RendererField: return "FIELD=VALUE";
    case ParamKind::Flag: return "true or false";
  }
  return "?";
}

}  // namespace millsim::sweep
