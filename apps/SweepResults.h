#pragma once
// `millsim sweep status` and `collect`: the cells' states, and their result
// tables merged into one CSV (the cell, its grid values, where it ran and
// for how long, then its own table's columns).
#include <ostream>

#include "SweepExecutors.h"

namespace millsim::app {

// Counts of done, failed, queued and pending cells, the failed ones listed
// with their logs. 0 when every cell is done, else 1.
int printSummary(std::ostream& os, const SweepRequest& request);
// Writes the merged table (request.csv, default OUT/results.csv, and the same
// as JSON beside it: per cell its grid values, host, time and rows) from the
// cells that are done; lists the others. 0 when every cell is done, else 1.
int collect(std::ostream& os, const SweepRequest& request);

}  // namespace millsim::app
