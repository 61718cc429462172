// millsim bench resolution: the cost of a lesson against its voxel size
// (issue 44). The scene's tooth phantom at each --voxel size (its extent
// kept), per size: the load's wall time and peak resident memory, then every
// renderer over the procedure (`bench procedure`'s per-phase frame times, on
// the haptic thread's CPU clock); a Markdown table and how each cost grows.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "BenchResolution.h"
#include "Commands.h"
#include "measure/Resolution.h"

namespace millsim::app {

namespace {

using namespace millsim::measure;

// A figure; "–" for one not measured (NaN, or a negative memory size).
std::string num(double v, int precision = 3) {
  if (!std::isfinite(v) || v < 0.0) return "–";
  std::ostringstream o;
  o << std::setprecision(precision) << v;
  return o.str();
}

std::string exponent(double v) {  // a growth exponent, negative when the cost falls
  if (!std::isfinite(v)) return "– (fewer than two sizes)";
  std::ostringstream o;
  o << std::fixed << std::setprecision(2) << v;
  return o.str();
}

// The least-squares slope of log y against log x: y grows as x^slope.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(x[i] > 0.0 && y[i] > 0.0)) continue;
    const double a = std::log(x[i]), b = std::log(y[i]);
    n += 1, sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  return n < 2 ? NAN : (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

int runResolution(const ResolutionArgs& a) {
  std::vector<double> voxels = a.voxels;
  std::sort(voxels.rbegin(), voxels.rend());  // coarse first: a slow fine size comes last
  const std::vector<std::string> types = a.renderers.empty() ? registeredRenderers() : a.renderers;
  std::ofstream csv;
  if (!a.csv.empty()) {
    csv.open(a.csv);
    if (!csv) throw std::runtime_error("cannot write " + a.csv);
    csv << "voxel_um,dims,material_voxels,load_s,load_peak_mib,renderer,phase,frames,p50_us,p99_us,p999_us,max_us,"
           "control_p99_us,preempted,removed_mm3,peak_mib\n";
  }
  std::ostringstream md, growth;
  md << "| voxel | voxels (box) | material | load | load peak | renderer | milling p50 · p99 · max (µs) | all frames "
        "p99 · max (µs) | control p99 (µs) | removed (mm³) |\n|---|---|---|---|---|---|---|---|---|---|\n";
  std::vector<double> material, loadSeconds, loadPeak;
  std::map<std::string, std::vector<double>> millingP50, millingP99;
  for (double h : voxels) {
    const ResolutionLoad load = measureLoad(a.scene, h);
    std::cerr << "voxel " << h * 1e6 << " µm: " << load.dims.x << "x" << load.dims.y << "x" << load.dims.z << ", "
              << load.materialVoxels << " voxels of material, loaded in " << num(load.seconds) << " s, peak "
              << num(load.peakMiB, 4) << " MiB\n";
    material.push_back(double(load.materialVoxels)), loadSeconds.push_back(load.seconds), loadPeak.push_back(load.peakMiB);
    const std::string label = num(h * 1e6) + " µm";
    for (const std::string& type : types) {
      resetPeakResident();
      const ProcedureResult r = measureProcedure({type, {}}, label, a.scene, a.trajectory, 0, load.overrides);
      const double peak = peakResidentMiB();
      const ProcedurePhase* milling = nullptr;
      const ProcedurePhase* all = nullptr;
      for (const ProcedurePhase& p : r.phases) {
        if (p.name == "milling") milling = &p;
        if (p.name == "all") all = &p;
        if (csv)
          csv << h * 1e6 << "," << load.dims.x << "x" << load.dims.y << "x" << load.dims.z << "," << load.materialVoxels
              << "," << load.seconds << "," << load.peakMiB << "," << type << "," << p.name << "," << p.frames << ","
              << p.cpu.p50 << "," << p.cpu.p99 << "," << p.cpu.p999 << "," << p.cpu.max << "," << p.control.p99 << ","
              << r.preempted << "," << r.removedMm3 << "," << peak << "\n";
      }
      if (!milling || !all) throw std::runtime_error("the procedure reported no milling or no 'all' phase");
      millingP50[type].push_back(milling->cpu.p50), millingP99[type].push_back(milling->cpu.p99);
      std::cerr << "  " << type << ": milling p50 " << num(milling->cpu.p50) << ", p99 " << num(milling->cpu.p99)
                << " µs; all p99 " << num(all->cpu.p99) << ", max " << num(all->cpu.max) << " µs\n";
      md << "| " << label << " | " << load.dims.x << "·" << load.dims.y << "·" << load.dims.z << " | "
         << num(double(load.materialVoxels) / 1e6) << " M | " << num(load.seconds) << " s | " << num(load.peakMiB, 4)
         << " MiB | " << type << " | " << num(milling->cpu.p50) << " · " << num(milling->cpu.p99) << " · "
         << num(milling->cpu.max) << " | " << num(all->cpu.p99) << " · " << num(all->cpu.max) << " | "
         << num(all->control.p99) << " | " << num(r.removedMm3) << " |\n";
    }
  }
  // How each cost grows: against the material's voxel count for the load, and
  // against 1/h for a frame (a cost that follows the contact stays flat).
  std::vector<double> inverseH;
  for (double h : voxels) inverseH.push_back(1.0 / h);
  growth << "\nLoad time grows as (material voxels)^" << exponent(slope(material, loadSeconds))
         << ", the process's peak memory while loading as (material voxels)^" << exponent(slope(material, loadPeak))
         << ".\n";
  for (const std::string& type : types)
    growth << type << "'s milling frame grows as (1/h)^" << exponent(slope(inverseH, millingP50[type]))
           << " at p50, (1/h)^" << exponent(slope(inverseH, millingP99[type])) << " at p99.\n";
  const std::string text = md.str() + growth.str();
  if (!a.md.empty()) {
    std::ofstream out(a.md);
    if (!(out << text)) throw std::runtime_error("cannot write " + a.md);
  } else {
    std::cout << text;
  }
  return kExitOk;
}

}  // namespace millsim::app
