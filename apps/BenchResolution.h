#pragma once
// millsim bench resolution (BenchResolution.cpp); its options are wired in
// BenchCommand.cpp with the other bench verbs.
#include <string>
#include <vector>

namespace millsim::app {

struct ResolutionArgs {
  std::vector<std::string> renderers;
  std::vector<double> voxels{1e-4, 5e-5, 2.5e-5};
  std::string scene, trajectory, csv, md;
};

// Prints (or writes) the table and the growth exponents; throws std::exception on bad input.
int runResolution(const ResolutionArgs& args);

}  // namespace millsim::app
