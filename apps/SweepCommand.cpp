// millsim sweep FILE --local | --slurm, millsim sweep status | collect FILE,
// millsim sweep cell FILE INDEX: a grid of millsim commands (sweep/SweepFile.h)
// run on this machine's cores or as one Slurm job array, resumable, merged
// into one table (docs/sweeps.md).
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "Commands.h"
#include "SweepExecutors.h"
#include "measure/Renderers.h"
#include "sweep/SweepCells.h"

namespace millsim::app {

void addSweepCommand(CLI::App& app, int& result) {
  struct Args {
    std::vector<std::string> words;  // [status|collect|cell] FILE [INDEX]
    bool local = false, slurm = false, retryFailed = false, yes = false, dryRun = false, wait = false;
    int jobs = 0;
    double timeout = 3600.0;
    std::string out, csv, submitted;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "sweep", "Run a sweep file's grid of millsim commands here (--local) or as a Slurm job array (--slurm); "
               "`sweep status FILE` and `sweep collect FILE` follow and merge it");
  cmd->add_option("words", a->words, "FILE, or status FILE, collect FILE, cell FILE INDEX")->required()->expected(1, 3);
  auto* local = cmd->add_flag("--local", a->local, "Run the cells here, as many at once as -j (resumable)");
  cmd->add_flag("--slurm", a->slurm, "Submit the cells as one sbatch --array job (sbatch, squeue on PATH)")->excludes(local);
  cmd->add_option("-j,--jobs", a->jobs, "--local: cells at once (default: the cores there are)")->check(CLI::Range(1, 1024));
  cmd->add_option("--out", a->out, "Results folder (default: NAME.sweep beside the sweep file)");
  cmd->add_flag("--retry-failed", a->retryFailed, "Run the failed cells again too (finished ones never are)");
  cmd->add_flag("--yes", a->yes, "Allow a grid of more than 10 000 cells");
  cmd->add_flag("--dry-run", a->dryRun, "Print each cell's command and state; run nothing");
  cmd->add_flag("--wait", a->wait, "--slurm: wait until the job's cells have left the queue, then sum up");
  cmd->add_option("--timeout", a->timeout, "--wait: give up after this many seconds (default 3600)")
      ->check(CLI::Range(1.0, 1e7));
  cmd->add_option("--csv", a->csv, "collect: the merged table (default: OUT/results.csv; and .json beside it)");
  cmd->add_option("--submitted", a->submitted,
                  "cell: the submission's list of cells (what a Slurm task is given): refuse a cell whose command "
                  "has changed since");
  cmd->callback([a, &result] {
    std::string verb = "run";
    std::vector<std::string> w = a->words;
    if (w[0] == "status" || w[0] == "collect" || w[0] == "cell") verb = w[0], w.erase(w.begin());
    const std::string usage = "expected `millsim sweep FILE --local|--slurm`, `sweep status FILE`, `sweep collect "
                              "FILE` or `sweep cell FILE INDEX`";
    if (w.size() != (verb == "cell" ? 2u : 1u)) {
      std::cerr << "millsim sweep: error: " << usage << "\n";
      result = kExitBadInput;
      return;
    }
    SweepRequest r;
    r.verb = verb;
    r.retryFailed = a->retryFailed;
    r.dryRun = a->dryRun;
    r.wait = a->wait;
    r.timeout = a->timeout;
    r.jobs = a->jobs;
    r.csv = a->csv;
    try {
      sweep::SweepContext context;
      context.renderers = measure::registeredRenderers();
      context.yes = a->yes || verb != "run";  // looking at a sweep, or running a cell of it, runs no grid
      r.sweep = sweep::readSweep(w[0], context);
      r.out = a->out.empty() ? sweep::defaultOutput(r.sweep) : std::filesystem::absolute(a->out);
      if (verb == "cell") {
        std::size_t used = 0;
        unsigned long long index = 0;
        try {
          index = w[1].find_first_not_of("0123456789") == std::string::npos ? std::stoull(w[1], &used) : 0;
        } catch (const std::exception&) {
          used = 0;
        }
        if (used == 0 || used != w[1].size() || index >= r.sweep.cellCount())
          throw std::invalid_argument("cell " + w[1] + ": expected an index from 0 to " +
                                      std::to_string(r.sweep.cellCount() - 1));
        r.cell = index;
        r.submitted = a->submitted;
      }
      if (verb == "run" && !a->dryRun && a->local == a->slurm)
        throw std::invalid_argument("say where the cells run: --local (here) or --slurm (a Slurm cluster)");
      if (verb == "collect" && !a->csv.empty() && std::filesystem::path(a->csv).extension() == ".json")
        throw std::invalid_argument("--csv " + a->csv + ": name the CSV .csv; the JSON is written beside it");
      r.slurm = a->slurm;
    } catch (const std::exception& e) {
      std::cerr << "millsim sweep: error: " << e.what() << "\n";
      result = kExitBadInput;
      return;
    }
    result = runSweepRequest(r);
  });
}

}  // namespace millsim::app
