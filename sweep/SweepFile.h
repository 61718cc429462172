#pragma once
// A sweep file (docs/sweeps.md): one verb, the parameters every cell shares
// ("fixed") and the grid the cells vary ("grid"), read and checked before
// anything runs or is submitted, every mistake with its line and what was
// expected. The grid's cells are numbered in file order, the last axis
// fastest; cell i's command is a function of the file alone, so a cell runs
// the same wherever it runs.
//
//   {
//     "sweep": "rates",
//     "verb": "replay",
//     "fixed": {"scene": "default.x3d", "trajectory": "trajectories/mill-and-lean.csv"},
//     "grid": {"renderer": ["LineProxyRenderer", "BarbicRenderer"], "rate": [990, 1000, 1010]},
//     "slurm": {"max_parallel": 8, "partition": "batch", "time": "00:30:00"}
//   }
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sweep/JsonPlaces.h"
#include "sweep/SweepVerbs.h"

namespace millsim::sweep {

// A grid of more cells needs --yes; more than kMaxCells is refused.
inline constexpr std::uint64_t kCellsWithoutYes = 10'000;
inline constexpr std::uint64_t kMaxCells = 1'000'000;

struct SweepParam {
  const ParamSpec* spec = nullptr;
  std::vector<std::string> values;  // a path absolute; a number as written; a flag "true"/"false"
  Place at;
};

struct SlurmSettings {
  int maxParallel = 0;    // the array's %cap; 0: no cap
  std::string partition;  // empty: the cluster's default
  std::string time;       // the cells' time limit, Slurm's format; empty: the partition's
};

struct Sweep {
  std::filesystem::path file;    // absolute
  std::filesystem::path folder;  // the file's folder: every path lies inside it
  std::string name;
  const VerbSpec* verb = nullptr;
  std::vector<SweepParam> fixed;  // one value each, except a repeatable set
  std::vector<SweepParam> axes;   // the grid, in file order
  SlurmSettings slurm;
  std::uint64_t cellCount() const;
};

struct SweepContext {
  std::vector<std::string> renderers;  // registered renderer types
  bool yes = false;                    // allow more than kCellsWithoutYes cells
};

// Throws SweepError "FILE:LINE:COLUMN: what is wrong; what was expected".
Sweep readSweep(const std::filesystem::path& file, const SweepContext& context);

struct Cell {
  std::uint64_t index = 0;
  std::string id;                   // the index zero-padded to the grid's width: its folder's name
  std::vector<std::string> values;  // one per axis
  std::vector<std::string> args;    // the millsim command line after the program's name
};
Cell cellAt(const Sweep& sweep, std::uint64_t index);

// A value as a table shows it: a path relative to the sweep's folder.
std::string shownValue(const Sweep& sweep, const SweepParam& param, const std::string& value);

}  // namespace millsim::sweep
