#pragma once
// --slurm: the cells as one `sbatch --array` job whose tasks each run
// `millsim sweep cell FILE INDEX`; Slurm schedules them (no daemon of ours).
// OUT/slurm holds the job scripts, the tasks' output and the job ids.
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

#include "SweepExecutors.h"

namespace millsim::app {

int runSlurm(const SweepRequest& request);
// The command a submission gave cell `index` (its OUT/slurm/submit-N.cells),
// empty if it did not submit that cell.
std::string submittedCommand(const std::filesystem::path& cells, std::uint64_t index);
// Cells of this sweep's jobs still in Slurm's queue (pending or running);
// empty when none were submitted. Throws when squeue cannot be asked.
std::set<std::uint64_t> queuedCells(const SweepRequest& request);

}  // namespace millsim::app
