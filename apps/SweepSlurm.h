#pragma once
// --slurm: the cells as one `sbatch --array` job whose tasks each run
// `millsim sweep cell FILE INDEX`; Slurm schedules them (no daemon of ours).
// OUT/slurm holds the job scripts, the tasks' output and the job ids.
#include <cstdint>
#include <set>

#include "SweepExecutors.h"

namespace millsim::app {

int runSlurm(const SweepRequest& request);
// Cells of this sweep's jobs still in Slurm's queue (pending or running);
// empty when none were submitted. Throws when squeue cannot be asked.
std::set<std::uint64_t> queuedCells(const SweepRequest& request);

}  // namespace millsim::app
