// millsim bench accuracy | physical | rates | procedure | resolution | stability | zwidth: the measurements behind docs/results.md
// and docs/accuracy.md
// (scripts/bench runs them). Renderers are named by registry type and
// configured by field name, so a new renderer type needs no change here.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "BenchResolution.h"
#include "Commands.h"
#include "measure/Accuracy.h"
#include "measure/Physical.h"
#include "measure/PhysicalScenes.h"
#include "measure/Procedure.h"
#include "measure/Rates.h"
#include "measure/Stability.h"
#include "measure/ZWidth.h"
#include "millsim/volume/VoxelSizeRange.h"

namespace millsim::app {

namespace {

using namespace millsim::measure;

std::string fmt(double v, int precision = 3) {
  if (!std::isfinite(v)) return "–";
  std::ostringstream o;
  o << std::setprecision(precision) << v;
  return o.str();
}

std::ofstream openOut(const std::string& path) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  return f;
}

// Rows appended to `path` (none if empty); the header only when the file is new.
std::ofstream appendCsv(const std::string& path, const char* header) {
  std::ofstream csv;
  if (path.empty()) return csv;
  const bool fresh = !std::ifstream(path).good();
  csv.open(path, std::ios::app);
  if (!csv) throw std::runtime_error("cannot write " + path);
  if (fresh) csv << header;
  return csv;
}

// One renderer configuration of a --field/--values sweep ("" is the defaults),
// and its label ("default" or "field=value").
RendererSpec sweepSpec(const std::string& type, const std::string& field, const std::string& value,
                       std::string& label) {
  RendererSpec spec{type, {}};
  label = "default";
  if (!field.empty() && !value.empty()) spec.fields.push_back({field, value}), label = field + "=" + value;
  return spec;
}

struct AccuracyArgs {
  std::vector<std::string> renderers;
  std::vector<double> voxelMm{0.2, 0.1, 0.05};
  double sweepVoxelMm = 0.1;
  bool quick = false;
  std::string csv, md;
};

int runAccuracy(const AccuracyArgs& a) {
  AccuracyConfig cfg;
  if (a.quick) cfg.depths = 3, cfg.tiltsDeg = {0, 30, 60}, cfg.phases = 1, cfg.settleFrames = 10;
  std::vector<std::string> types = a.renderers.empty() ? registeredRenderers() : a.renderers;
  std::vector<AccuracyRow> rows;
  std::ostringstream orders;
  auto progress = [](const AccuracyRow& r) {
    std::cerr << r.renderer << " " << r.resolution << " h=" << r.h * 1e3 << "mm: force RMS " << fmt(r.forceRms)
              << ", torque RMS " << fmt(r.torqueRms) << ", p99 " << fmt(r.p99Us) << " us\n";
  };
  for (const std::string& type : types) {
    // Voxel size at the default resolution.
    std::vector<double> hs, fe, te;
    for (double mm : a.voxelMm) {
      auto r = measureAccuracy({type, {}}, mm * 1e-3, cfg);
      progress(r.back());
      hs.push_back(mm), fe.push_back(r.back().forceRms), te.push_back(r.back().torqueRms);
      rows.insert(rows.end(), r.begin(), r.end());
    }
    orders << "| " << type << " | voxel size h | " << fmt(convergenceOrder(hs, fe), 2) << " | "
           << fmt(convergenceOrder(hs, te), 2) << " |\n";
    // Each resolution field, at one voxel size.
    auto probe = makeRenderer({type, {}});
    for (const auto& [field, values] : probe->traits().resolutionSweeps) {
      if (!probe->field(field)) {
        std::cerr << type << " has no field '" << field << "': its resolution sweep is skipped\n";
        continue;
      }
      std::vector<double> xs, f2, t2;
      for (const std::string& v : values) {
        auto r = measureAccuracy({type, {{field, v}}}, a.sweepVoxelMm * 1e-3, cfg, field + "=" + v);
        progress(r.back());
        xs.push_back(std::stod(v)), f2.push_back(r.back().forceRms), t2.push_back(r.back().torqueRms);
        rows.insert(rows.end(), r.begin(), r.end());
      }
      // err ∝ n^(−p): report p (positive = converging).
      orders << "| " << type << " | " << field << " (h = " << a.sweepVoxelMm << " mm) | "
             << fmt(-convergenceOrder(xs, f2), 2) << " | " << fmt(-convergenceOrder(xs, t2), 2) << " |\n";
    }
  }
  if (!a.csv.empty()) {
    auto f = openOut(a.csv);
    f << accuracyCsvHeader() << "\n";
    for (const auto& r : rows) f << toCsv(r) << "\n";
  }
  std::ostringstream md;
  md << "| renderer | resolution | h (mm) | poses (counted) | force RMS | force p95 | direction RMS (°) | torque RMS | "
        "torque p95 | drawn RMS (voxels) | p50 (µs) | p99 (µs) |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    if (r.scene == "all")
      md << "| " << r.renderer << " | " << r.resolution << " | " << fmt(r.h * 1e3) << " | " << r.poses << " ("
         << r.counted << ") | " << fmt(r.forceRms) << " | " << fmt(r.forceP95) << " | " << fmt(r.directionRms) << " | "
         << fmt(r.torqueRms) << " | " << fmt(r.torqueP95) << " | " << fmt(r.drawnRms) << " | " << fmt(r.p50Us)
         << " | " << fmt(r.p99Us) << " |\n";
  md << "\nPer scene, default resolution, h = 0.1 mm:\n\n| renderer | scene | poses (counted) | force RMS | force p95 | "
        "direction RMS (°) | torque RMS | torque p95 | drawn RMS (voxels) |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    if (r.scene != "all" && r.resolution == "default" && std::abs(r.h - 1e-4) < 1e-9)
      md << "| " << r.renderer << " | " << r.scene << " | " << r.poses << " (" << r.counted << ") | "
         << fmt(r.forceRms) << " | " << fmt(r.forceP95) << " | " << fmt(r.directionRms) << " | " << fmt(r.torqueRms)
         << " | " << fmt(r.torqueP95) << " | " << fmt(r.drawnRms) << " |\n";
  md << "\nConvergence order p (force and torque RMS; error ∝ h^p for the voxel size, ∝ n^−p for a resolution "
        "field):\n\n| renderer | swept | p (force) | p (torque) |\n|---|---|---|---|\n"
     << orders.str();
  if (!a.md.empty()) openOut(a.md) << md.str();
  else std::cout << md.str();
  return kExitOk;
}

struct PhysicalArgs {
  std::vector<std::string> renderers;
  std::vector<double> voxelMm{0.2, 0.1, 0.05};
  double sweepVoxelMm = 0.0;  // > 0: also each resolution field's values at this voxel size
  std::vector<std::string> sets;  // FIELD=VALUE overrides of the renderers' defaults
  std::vector<std::string> scenes;  // empty: the suite's set
  bool quick = false, ownLaw = true;
  std::string csv, md, poses;
};

// The force's convergence order per scene: which scenes hold a renderer's
// pooled order down (a scene whose error the voxels do not set stays flat).
// "exact" where every h measured under 1e-6 (the half-space for #1 and #2).
std::string sceneForceOrders(const std::vector<PhysicalRow>& rows) {
  std::vector<std::string> scenes, renderers;
  std::map<std::pair<std::string, std::string>, std::pair<std::vector<double>, std::vector<double>>> series;
  for (const PhysicalRow& r : rows) {
    if (r.scene == "all") continue;
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
    if (std::find(renderers.begin(), renderers.end(), r.renderer) == renderers.end()) renderers.push_back(r.renderer);
    auto& [hs, errors] = series[{r.renderer, r.scene}];
    hs.push_back(r.h), errors.push_back(r.forceRms);
  }
  if (series.empty() || series.begin()->second.first.size() < 2) return "";
  std::ostringstream md;
  md << "\nForce convergence order per scene (error ∝ h^p):\n\n| renderer |";
  for (const auto& s : scenes) md << " " << s << " |";
  md << "\n|---|";
  for (std::size_t i = 0; i < scenes.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& type : renderers) {
    md << "| " << type << " |";
    for (const auto& scene : scenes) {
      const auto& [hs, errors] = series[{type, scene}];
      const bool exact = std::all_of(errors.begin(), errors.end(), [](double e) { return e < 1e-6; });
      md << " " << (exact ? std::string("exact") : fmt(convergenceOrder(hs, errors), 2)) << " |";
    }
    md << "\n";
  }
  return md.str();
}

// Each renderer at its defaults against the physical reference (measure/Physical.h),
// with today's own-law figure (bench accuracy's "all" row) beside it; with
// --sweep-voxel, also over each resolution field (the run time against
// physical error that docs/results.md plots).
int runPhysical(const PhysicalArgs& a) {
  PhysicalConfig cfg;
  cfg.scenes = a.scenes;
  AccuracyConfig own;
  if (a.quick) cfg.phases = 1, own.depths = 3, own.tiltsDeg = {0, 30, 60}, own.phases = 1, own.settleFrames = 10;
  std::ofstream poses;
  if (!a.poses.empty()) {
    poses = openOut(a.poses);
    poses << physicalPoseCsvHeader() << "\n";
    cfg.poses = &poses;
  }
  const std::vector<std::string> types = a.renderers.empty() ? registeredRenderers() : a.renderers;
  FieldValues overrides;
  for (const std::string& set : a.sets) {
    const auto eq = set.find('=');
    if (eq == std::string::npos || eq == 0)
      throw std::invalid_argument("--set expects FIELD=VALUE (e.g. contactStiffness=10000), got '" + set + "'");
    overrides.push_back({set.substr(0, eq), set.substr(eq + 1)});
  }
  std::vector<PhysicalRow> rows, sweepRows;
  std::map<std::pair<std::string, double>, AccuracyRow> ownRows;
  std::ostringstream orders;
  auto pct = [](double v) { return fmt(100.0 * v, 3); };
  for (const std::string& type : types) {
    std::vector<double> hs, fe, de, te, ae, dr;
    for (double mm : a.voxelMm) {
      auto r = measurePhysical({type, overrides}, mm * 1e-3, cfg);
      const PhysicalRow& all = r.back();
      std::cerr << type << " h=" << mm << "mm: force " << pct(all.forceRms) << " %, direction "
                << fmt(all.directionRms) << " deg, torque " << fmt(all.torqueRms) << ", drawn " << fmt(all.drawnRms)
                << " voxels" << (all.refConverged ? "" : " (a reference pose missed its tolerance)") << "\n";
      hs.push_back(mm), fe.push_back(all.forceRms), de.push_back(all.directionRms), te.push_back(all.torqueRms);
      ae.push_back(all.armRelRms), dr.push_back(all.drawnRms * mm);
      rows.insert(rows.end(), r.begin(), r.end());
      if (a.ownLaw) ownRows[{type, mm}] = measureAccuracy({type, overrides}, mm * 1e-3, own).back();
    }
    if (a.sweepVoxelMm > 0.0) {
      const auto probe = makeRenderer({type, {}});
      for (const auto& [field, values] : probe->traits().resolutionSweeps)
        for (const std::string& v : values) {
          std::string label;
          PhysicalConfig sweepCfg = cfg;
          sweepCfg.poses = nullptr;  // per-pose rows are the defaults'
          RendererSpec spec = sweepSpec(type, field, v, label);
          spec.fields.insert(spec.fields.begin(), overrides.begin(), overrides.end());
          auto r = measurePhysical(spec, a.sweepVoxelMm * 1e-3, sweepCfg);
          for (PhysicalRow& row : r) row.resolution = label;
          std::cerr << type << " " << label << " h=" << a.sweepVoxelMm << "mm: force " << pct(r.back().forceRms)
                    << " %, direction " << fmt(r.back().directionRms) << " deg, p50 " << fmt(r.back().p50Us) << " us\n";
          sweepRows.insert(sweepRows.end(), r.begin(), r.end());
        }
    }
    orders << "| " << type << " | " << fmt(convergenceOrder(hs, fe), 2) << " | " << fmt(convergenceOrder(hs, de), 2)
           << " | " << fmt(convergenceOrder(hs, te), 2) << " | " << fmt(convergenceOrder(hs, ae), 2) << " | "
           << fmt(convergenceOrder(hs, dr), 2) << " |\n";
  }
  if (!a.csv.empty()) {
    auto f = openOut(a.csv);
    f << physicalCsvHeader() << ",own_force_rms,own_dir_rms_deg,own_torque_rms\n";
    for (const auto& r : rows) {
      f << toCsv(r);
      const auto it = ownRows.find({r.renderer, r.h * 1e3});
      if (r.scene == "all" && it != ownRows.end())
        f << "," << it->second.forceRms << "," << it->second.directionRms << "," << it->second.torqueRms << "\n";
      else f << ",,,\n";
    }
    for (const auto& r : sweepRows) f << toCsv(r) << ",,,\n";
  }
  double worstViolation = 0.0;
  bool converged = true;
  for (const auto& r : rows) worstViolation = std::max(worstViolation, r.refViolation), converged = converged && r.refConverged;
  std::ostringstream md;
  md << "| renderer | h (mm) | poses | felt k (N/m) | force RMS (%) | own law (%) | direction RMS (°) | own law (°) | "
        "no force (%) | torque RMS | moment arm RMS (mm) | shaft arm RMS (%) | line of action (mm) | drawn (voxels) | "
        "drawn (°) | p99 (µs) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    if (r.scene != "all") continue;
    const auto it = ownRows.find({r.renderer, r.h * 1e3});
    const bool hasOwn = it != ownRows.end();
    md << "| " << r.renderer << " | " << fmt(r.h * 1e3) << " | " << r.poses << " | " << fmt(r.feltStiffness, 4)
       << " | " << pct(r.forceRms) << " | " << (hasOwn ? pct(it->second.forceRms) : "–") << " | " << fmt(r.directionRms)
       << " | " << (hasOwn ? fmt(it->second.directionRms) : "–") << " | " << pct(r.missed) << " | " << fmt(r.torqueRms)
       << " | " << fmt(r.armRms) << " | " << pct(r.armRelRms) << " | " << fmt(r.lineRms) << " | "
       << fmt(r.drawnRms) << " | " << fmt(r.drawnDegRms) << " | " << fmt(r.p99Us) << " |\n";
  }
  md << "\nPer scene, defaults, h = 0.1 mm:\n\n| renderer | scene | poses | force RMS (%) | force p95 (%) | "
        "direction RMS (°) | no force (%) | torque RMS | moment arm RMS (mm) | shaft arm RMS (%) | line of action (mm) | "
        "drawn (voxels) | drawn (°) |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    if (r.scene != "all" && std::abs(r.h - 1e-4) < 1e-9)
      md << "| " << r.renderer << " | " << r.scene << " | " << r.poses << " | " << pct(r.forceRms) << " | "
         << pct(r.forceP95) << " | " << fmt(r.directionRms) << " | " << pct(r.missed) << " | " << fmt(r.torqueRms)
         << " | " << fmt(r.armRms) << " | " << pct(r.armRelRms) << " | " << fmt(r.lineRms) << " | "
         << fmt(r.drawnRms) << " | " << fmt(r.drawnDegRms) << " |\n";
  md << "\nConvergence order p in h (error ∝ h^p; drawn pose in mm):\n\n| renderer | force | direction | torque | "
        "shaft arm | drawn |\n|---|---|---|---|---|---|\n"
     << orders.str();
  md << sceneForceOrders(rows);
  if (!sweepRows.empty()) {
    md << "\nResolution sweep, h = " << fmt(a.sweepVoxelMm) << " mm (all scenes):\n\n| renderer | resolution | force RMS (%) | "
          "direction RMS (°) | torque RMS | p50 (µs) | p99 (µs) |\n|---|---|---|---|---|---|---|\n";
    for (const auto& r : sweepRows)
      if (r.scene == "all")
        md << "| " << r.renderer << " | " << r.resolution << " | " << pct(r.forceRms) << " | " << fmt(r.directionRms)
           << " | " << fmt(r.torqueRms) << " | " << fmt(r.p50Us) << " | " << fmt(r.p99Us) << " |\n";
  }
  for (const auto& r : sweepRows)
    worstViolation = std::max(worstViolation, r.refViolation), converged = converged && r.refConverged;
  md << "\nReference: " << (converged ? "every pose converged" : "SOME POSES MISSED THEIR TOLERANCE")
     << ", largest remaining penetration " << fmt(worstViolation, 2) << " m.\n";
  if (!a.md.empty()) openOut(a.md) << md.str();
  else std::cout << md.str();
  return kExitOk;
}

struct RatesArgs {
  std::string renderer;
  std::string field;
  std::vector<std::string> values;
  long frames = 3000;
  bool fine = false;
  std::string pose = "gentle";
  std::string csv;
};

int runRates(const RatesArgs& a) {
  std::ofstream csv =
      appendCsv(a.csv, "renderer,resolution,frames,mean_us,p50_us,p99_us,rate_hz,max_contacts,grid,pose,p999_us,"
                       "max_us,wall_p99_us,preempted,control_p50_us,control_p99_us,control_p999_us,min_contacts\n");
  const RatePose pose = a.pose == "deep" ? RatePose::Deep : RatePose::Gentle;
  std::vector<std::string> values = a.values.empty() ? std::vector<std::string>{""} : a.values;
  for (const std::string& v : values) {
    std::string label;
    const RendererSpec spec = sweepSpec(a.renderer, a.field, v, label);
    const RateResult r = measureRate(spec, a.frames, label, a.fine, pose);
    std::cout << r.renderer << " " << r.resolution << " on " << r.grid << ", " << r.pose << " pose: CPU mean "
              << fmt(r.meanUs) << " us, p50 " << fmt(r.p50Us) << " us, p99 " << fmt(r.p99Us) << " us, p99.9 "
              << fmt(r.p999Us) << " us, max " << fmt(r.maxUs) << " us (control of equal work: p99 "
              << fmt(r.control.p99) << " us, p99.9 " << fmt(r.control.p999) << " us); wall p99 " << fmt(r.wallP99Us)
              << " us, " << r.preempted << " frames lost the CPU; " << fmt(r.rateHz, 4) << " Hz equivalent, "
              << r.minContacts << "-" << r.maxContacts << " contacts\n";
    if (csv)
      csv << r.renderer << "," << r.resolution << "," << r.frames << "," << r.meanUs << "," << r.p50Us << ","
          << r.p99Us << "," << r.rateHz << "," << r.maxContacts << "," << r.grid << "," << r.pose << "," << r.p999Us
          << "," << r.maxUs << "," << r.wallP99Us << "," << r.preempted << "," << r.control.p50 << ","
          << r.control.p99 << "," << r.control.p999 << "," << r.minContacts << "\n";
  }
  return kExitOk;
}

struct ProcedureArgs {
  std::vector<std::string> renderers;
  std::string field;
  std::vector<std::string> values;
  std::string scene, trajectory;
  long bruteEvery = 100;
  std::string csv;
};

int runProcedure(const ProcedureArgs& a) {
  std::ofstream csv =
      appendCsv(a.csv, "renderer,resolution,phase,frames,p50_us,p99_us,p999_us,max_us,control_p99_us,control_p999_us,"
                       "brute_samples,brute_p50_us,brute_max_us,preempted,max_contacts,removed_mm3\n");
  const std::vector<std::string> types = a.renderers.empty() ? registeredRenderers() : a.renderers;
  const std::vector<std::string> values = a.values.empty() ? std::vector<std::string>{""} : a.values;
  for (const std::string& type : types) {
    for (const std::string& v : values) {
      std::string label;
      const RendererSpec spec = sweepSpec(type, a.field, v, label);
      const ProcedureResult r = measureProcedure(spec, label, a.scene, a.trajectory, a.bruteEvery);
      std::cout << r.renderer << " " << r.resolution << ": removed " << fmt(r.removedMm3) << " mm3, "
                << r.maxContacts << " contacts at most, " << r.preempted << " frames lost the CPU\n";
      for (const ProcedurePhase& p : r.phases) {
        std::cout << "  " << std::left << std::setw(8) << p.name << std::right << std::setw(6) << p.frames
                  << " frames: p50 " << fmt(p.cpu.p50) << ", p99 " << fmt(p.cpu.p99) << ", p99.9 " << fmt(p.cpu.p999)
                  << ", max " << fmt(p.cpu.max) << " us (control p99 " << fmt(p.control.p99) << ", p99.9 "
                  << fmt(p.control.p999) << " us)";
        if (p.name == "milling" && r.bruteSamples > 0)
          std::cout << "; compiled afresh instead: p50 " << fmt(r.brute.p50) << " us (" << r.bruteSamples
                    << " samples, " << fmt(r.brute.p50 / std::max(1e-9, p.cpu.p50)) << "x)";
        std::cout << "\n";
        if (csv)
          csv << r.renderer << "," << r.resolution << "," << p.name << "," << p.frames << "," << p.cpu.p50 << ","
              << p.cpu.p99 << "," << p.cpu.p999 << "," << p.cpu.max << "," << p.control.p99 << ","
              << p.control.p999 << "," << r.bruteSamples << "," << r.brute.p50 << "," << r.brute.max << ","
              << r.preempted << "," << r.maxContacts << "," << r.removedMm3 << "\n";
      }
    }
  }
  return kExitOk;
}

struct StabilityArgs {
  std::vector<std::string> renderers, scenarios;
  std::vector<double> masses, dampings, stiffnesses;  // empty: the hand grid's
  double drop = 0.0;
  std::uint64_t seed = 1;
  std::string csv;
};

// The stability suite's closed loop (docs/stability.md) over a grid of grips
// and scenarios, one CSV row each: what the soak grid runs, a cell at a time
// when a sweep spreads it (x3d/stability-soak.json). No waivers here: a row
// says what failed; the test suite decides what is excused.
int runStability(const StabilityArgs& a) {
  const std::vector<std::string> types = a.renderers.empty() ? registeredRenderers() : a.renderers;
  auto pick = [](const std::vector<double>& given, std::vector<double> all) { return given.empty() ? all : given; };
  const std::vector<double> ms = pick(a.masses, {0.1, 0.55}), bs = pick(a.dampings, {2.0, 6.5, 10.0}),
                            ks = pick(a.stiffnesses, {135.0, 500.0, 1000.0});
  std::vector<Scenario> scenarios;
  for (const Scenario& sc : standardScenarios())
    if (a.scenarios.empty() || std::find(a.scenarios.begin(), a.scenarios.end(), sc.name()) != a.scenarios.end())
      scenarios.push_back(sc);
  if (scenarios.empty()) {
    std::string names;
    for (const Scenario& sc : standardScenarios()) names += (names.empty() ? "" : ", ") + sc.name();
    throw std::invalid_argument("no scenario of that name; the scenarios are " + names);
  }
  std::ostringstream rows;
  int failed = 0;
  for (const std::string& type : types)
    for (double m : ms)
      for (double b : bs)
        for (double k : ks) {
          HandModel hand;
          hand.handMass = m, hand.handDamping = b, hand.handStiffness = k;
          for (const Scenario& sc : scenarios) {
            const ScenarioResult r = runScenario({type, {}}, sc, hand, a.drop, a.seed);
            std::string why = r.failure;
            for (char& c : why)
              if (c == ',' || c == '"') c = ';';
            rows << r.renderer << "," << r.scenario << "," << m << "," << b << "," << k << "," << a.drop << "," << a.seed
                 << "," << (r.passed ? "pass" : "fail") << "," << r.minEnergy << "," << r.energyBound << ","
                 << r.limitCycle << "," << r.peakForce << "," << r.maxPenetration << "," << r.contactSpeed << "," << why
                 << "\n";
            failed += !r.passed;
            std::cerr << type << " " << r.scenario << " " << r.hand << (a.drop > 0 ? " drop " + fmt(a.drop) : "") << ": "
                      << (r.passed ? "passes" : "FAILS: " + r.failure) << "\n";
          }
        }
  const std::string header = "renderer,scenario,hand_mass_kg,hand_damping_Ns_per_m,hand_stiffness_N_per_m,drop,seed,"
                             "result,min_energy_J,energy_bound_J,limit_cycle_m,peak_force_N,max_penetration_m,"
                             "contact_speed_m_per_s,failure\n";
  if (!a.csv.empty()) openOut(a.csv) << header << rows.str();
  else std::cout << header << rows.str();
  std::cerr << failed << " runs failed a stability check\n";
  return kExitOk;
}

struct ZWidthArgs {
  std::vector<std::string> renderers;
  double from = 250.0, to = 1024000.0;
  bool quick = false;
  std::string csv, md;
};

int runZWidth(const ZWidthArgs& a) {
  if (!(a.from > 0.0) || !(a.to >= a.from))
    throw std::invalid_argument("--from and --to must satisfy 0 < from <= to (N/m), got " + fmt(a.from) + " and " +
                                fmt(a.to));
  const std::vector<std::string> types = a.renderers.empty() ? registeredRenderers() : a.renderers;
  // The quick run keeps the measured arm's grip (docs/stability.md); the full one spans loose to firm.
  const std::vector<HandModel> hands = a.quick ? std::vector<HandModel>{handCorners()[1]} : handCorners();
  const std::vector<double> values = sqrt2Steps(a.from, a.to);
  std::vector<ZWidthResult> rows;
  for (const std::string& type : types) {
    if (rendererTraits(type).stiffnessField.empty()) {
      std::cerr << type << ": declares no stiffness field (RendererTraits::stiffnessField), skipped\n";
      continue;
    }
    for (const HandModel& hand : hands) {
      rows.push_back(zWidthSweep(type, hand, values));
      const ZWidthResult& r = rows.back();
      std::cerr << type << " " << r.hand << ": largest stable " << r.field << " = " << fmt(r.largestStable)
                << " N/m (default " << fmt(r.defaultStiffness) << ")"
                << (r.firstUnstable > 0.0 ? ", " + fmt(r.firstUnstable) + " fails: " + r.points.back().failure : "")
                << "\n";
    }
  }
  if (!a.csv.empty()) {
    auto f = openOut(a.csv);
    f << "renderer,field,hand,default,rendered_at_default,largest_stable,first_unstable,rendered_at_largest,failure\n";
    for (const auto& r : rows) {
      std::string why = r.firstUnstable > 0.0 ? r.points.back().failure : "";
      for (char& c : why)
        if (c == ',' || c == '"') c = ';';
      f << r.renderer << "," << r.field << "," << r.hand << "," << r.defaultStiffness << "," << r.renderedAtDefault
        << "," << r.largestStable << "," << r.firstUnstable << "," << r.renderedAtLargest << "," << why << "\n";
    }
  }
  auto n = [](double v) { return std::to_string(std::lround(v)); };
  std::ostringstream md;
  md << "| renderer | field = default (felt, N/m) | grip | largest stable (N/m) | × default | felt there (N/m) | "
        "first unstable (N/m): why |\n|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    md << "| " << r.renderer << " | " << r.field << " = " << n(r.defaultStiffness) << " (" << n(r.renderedAtDefault)
       << ") | " << r.hand << " | " << (r.largestStable > 0.0 ? n(r.largestStable) : "< " + n(a.from))
       << (r.firstUnstable > 0.0 ? "" : " (all tried)") << " | " << fmt(r.largestStable / r.defaultStiffness, 2)
       << " | " << n(r.renderedAtLargest) << " | "
       << (r.firstUnstable > 0.0 ? n(r.firstUnstable) + ": " + r.points.back().failure : "none up to " + n(a.to))
       << " |\n";
  if (!a.md.empty()) openOut(a.md) << md.str();
  else std::cout << md.str();
  return kExitOk;
}

// Runs one bench verb; a bad argument or an unwritable file is a clear error and exit 2.
template <class Args, class Run>
void onRun(CLI::App* verb, std::shared_ptr<Args> args, Run run, int& result) {
  verb->callback([verb, args, run, &result] {
    try {
      result = run(*args);
    } catch (const std::exception& e) {
      std::cerr << "millsim bench " << verb->get_name() << ": error: " << e.what() << "\n";
      result = kExitBadInput;
    }
  });
}

}  // namespace

void addBenchCommand(CLI::App& app, int& result) {
  auto* bench = app.add_subcommand("bench", "Measure accuracy, frame time and stiffness headroom of the haptics renderers");
  bench->require_subcommand(1);

  auto* acc = bench->add_subcommand("accuracy", "Force/torque error against analytic references, and frame time");
  auto a = std::make_shared<AccuracyArgs>();
  acc->add_option("--renderer", a->renderers, "Renderer type (repeatable; default: every registered one)");
  acc->add_option("--voxel-sizes", a->voxelMm, "Voxel sizes h in mm (default 0.2,0.1,0.05)")->delimiter(',');
  acc->add_option("--sweep-voxel", a->sweepVoxelMm, "Voxel size (mm) of the resolution sweeps (default 0.1)");
  acc->add_flag("--quick", a->quick, "Fewer poses (3 depths, 3 tilts, 1 phase)");
  acc->add_option("--csv", a->csv, "Write every row (per scene and 'all') as CSV");
  acc->add_option("--md", a->md, "Write the Markdown tables here (default: stdout)");
  onRun(acc, a, runAccuracy, result);

  auto* phys = bench->add_subcommand(
      "physical", "Force, torque and drawn-pose error against the rigid tool's constrained pose (docs/accuracy.md)");
  auto ph = std::make_shared<PhysicalArgs>();
  phys->add_option("--renderer", ph->renderers, "Renderer type (repeatable; default: every registered one)");
  phys->add_option("--voxel-sizes", ph->voxelMm, "Voxel sizes h in mm (default 0.2,0.1,0.05)")->delimiter(',');
  phys->add_option("--sweep-voxel", ph->sweepVoxelMm,
                   "Also sweep each renderer's resolution fields at this voxel size in mm (e.g. 0.1; default: no sweep)")
      ->check(CLI::Range(0.01, 1.0));
  phys->add_option("--set", ph->sets,
                   "FIELD=VALUE: set a field of the renderers measured (repeatable), e.g. contactStiffness=10000; "
                   "the rows are labelled with the defaults' names");
  phys->add_option("--scene", ph->scenes,
                   "Physical scene (repeatable; default: half-space, ball, bowl, edge, plate, shaft-on-edge, hole); "
                   "mesh-ball is the ball voxelised from a 20 480-triangle mesh, as a mesh url is")
      ->check(CLI::Validator([](std::string& v) { return isPhysicalSceneName(v) ? std::string() : "unknown physical scene '" + v + "'"; },
                             "SCENE"));
  phys->add_flag("--quick", ph->quick, "One sub-voxel phase, and the quick own-law run");
  phys->add_flag("!--no-own-law", ph->ownLaw, "Skip the own-law column (bench accuracy's figure)");
  phys->add_option("--csv", ph->csv, "Write every row (per scene and 'all') as CSV");
  phys->add_option("--poses", ph->poses, "Write one CSV row per pose (forces, torques, errors) at the default resolution");
  phys->add_option("--md", ph->md, "Write the Markdown tables here (default: stdout)");
  onRun(phys, ph, runPhysical, result);

  auto* stab = bench->add_subcommand(
      "stability", "Closed-loop passivity, limit cycles and release over hand grips and scenarios (docs/stability.md)");
  auto st = std::make_shared<StabilityArgs>();
  stab->add_option("--renderer", st->renderers, "Renderer type (repeatable; default: every registered one)");
  stab->add_option("--mass", st->masses, "Hand mass, kg (repeatable; default 0.1 and 0.55)")->check(CLI::Range(0.01, 10.0));
  stab->add_option("--damping", st->dampings, "Hand damping, N·s/m (repeatable; default 2, 6.5 and 10)")
      ->check(CLI::Range(0.0, 1000.0));
  stab->add_option("--stiffness", st->stiffnesses, "Hand stiffness, N/m (repeatable; default 135, 500 and 1000)")
      ->check(CLI::Range(0.0, 100000.0));
  stab->add_option("--scenario", st->scenarios, "Scenario name, e.g. slide-50mm/s (repeatable; default: all eight)");
  stab->add_option("--drop", st->drop, "Fraction of device samples dropped (default 0)")->check(CLI::Range(0.0, 0.5));
  stab->add_option("--seed", st->seed, "Seed of the dropped samples (default 1)");
  stab->add_option("--csv", st->csv, "Write one row per run here (default: standard output)");
  onRun(stab, st, runStability, result);

  auto* rates = bench->add_subcommand("rates", "Frame time on the tooth phantom (the paper's §8.1 test)");
  auto r = std::make_shared<RatesArgs>();
  rates->add_option("--renderer", r->renderer, "Renderer type")->required();
  rates->add_option("--field", r->field, "Resolution field to set, e.g. vertexCount or slices");
  rates->add_option("--values", r->values, "Values of --field, e.g. 51,101,251")->delimiter(',');
  rates->add_option("--frames", r->frames, "Frames timed per value (default 3000)")->check(CLI::Range(1L, 100000000L));
  rates->add_flag("--fine", r->fine, "8x the voxels: the phantom at 512x512x352 with 0.05 mm voxels");
  rates->add_option("--pose", r->pose,
                    "gentle: the burr 0.3 mm into the unmilled surface; deep: 0.3 mm into the bottom of a 2.5 mm "
                    "hole, the leaning shaft on its wall (the paper's contact counts)")
      ->check(CLI::IsMember({"gentle", "deep"}));
  rates->add_option("--csv", r->csv, "Append rows to this CSV");
  onRun(rates, r, runRates, result);

  auto* proc = bench->add_subcommand(
      "procedure", "Frame times of the paper's §8.2 procedure per phase (free, contact, lean, milling), simulated time");
  auto pr = std::make_shared<ProcedureArgs>();
  proc->add_option("--renderer", pr->renderers, "Renderer type (repeatable; default: every registered one)");
  proc->add_option("--field", pr->field, "Resolution field to set, e.g. pointShellScale");
  proc->add_option("--values", pr->values, "Values of --field, e.g. 1,2,3")->delimiter(',');
  proc->add_option("--scene", pr->scene, "The scene, e.g. x3d/default.x3d (its renderer is replaced)")
      ->required()
      ->check(CLI::ExistingFile);
  proc->add_option("--trajectory", pr->trajectory, "The procedure, e.g. x3d/trajectories/section-8-2.csv")
      ->required()
      ->check(CLI::ExistingFile);
  proc->add_option("--brute-every", pr->bruteEvery,
                   "Compile the renderer afresh on every Nth milling frame (the brute-force variant; 0: never)")
      ->check(CLI::Range(0L, 1000000L));
  proc->add_option("--csv", pr->csv, "Append one row per renderer and phase to this CSV");
  onRun(proc, pr, runProcedure, result);

  auto* res = bench->add_subcommand(
      "resolution", "Load time, peak memory and frame times per renderer of the scene's tooth phantom at each voxel size");
  auto rs = std::make_shared<ResolutionArgs>();
  res->add_option("--scene", rs->scene, "A scene whose VolumeObject is the tooth phantom, e.g. x3d/default.x3d")
      ->required()
      ->check(CLI::ExistingFile);
  res->add_option("--trajectory", rs->trajectory, "The procedure, e.g. x3d/trajectories/section-8-2.csv")
      ->required()
      ->check(CLI::ExistingFile);
  res->add_option("--voxel", rs->voxels, "Voxel sizes in metres (default 0.0001,0.00005,0.000025)")
      ->delimiter(',')
      ->check(CLI::Range(kMinVoxelSize, kMaxVoxelSize));
  res->add_option("--renderer", rs->renderers, "Renderer type (repeatable; default: every registered one)");
  res->add_option("--csv", rs->csv, "Write one row per voxel size, renderer and phase as CSV");
  res->add_option("--md", rs->md, "Write the Markdown table here (default: stdout)");
  onRun(res, rs, runResolution, result);

  auto* zw = bench->add_subcommand(
      "zwidth", "Largest stable stiffness per renderer and grip, closed loop at 1 kHz (Z-width sweep)");
  auto z = std::make_shared<ZWidthArgs>();
  zw->add_option("--renderer", z->renderers, "Renderer type (repeatable; default: every registered one)");
  zw->add_option("--from", z->from, "Lowest stiffness tried, N/m (default 250)");
  zw->add_option("--to", z->to, "Highest stiffness tried, N/m (default 1024000); values rise in sqrt(2) steps");
  zw->add_flag("--quick", z->quick, "Only the measured arm's grip (M=0.554 kg, B=6.45 N s/m, K=135 N/m)");
  zw->add_option("--csv", z->csv, "Write one row per renderer and grip as CSV");
  zw->add_option("--md", z->md, "Write the Markdown table here (default: stdout)");
  onRun(zw, z, runZWidth, result);
}

}  // namespace millsim::app
