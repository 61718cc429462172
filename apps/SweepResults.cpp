#include "SweepResults.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "Commands.h"
#include "SweepSlurm.h"
#include "millsim/session/LessonReport.h"
#include "sweep/SweepCells.h"

namespace millsim::app {
namespace fs = std::filesystem;

namespace {

struct Census {
  std::vector<std::pair<sweep::Cell, sweep::CellStatus>> done, failed;
  std::vector<sweep::Cell> pending, queued;
};

Census census(const SweepRequest& r) {
  std::set<std::uint64_t> queued;
  try {
    queued = queuedCells(r);
  } catch (const std::exception&) {
    // No Slurm here: what the files say.
  }
  Census c;
  for (std::uint64_t i = 0; i < r.sweep.cellCount(); ++i) {
    const sweep::Cell cell = sweep::cellAt(r.sweep, i);
    std::optional<sweep::CellStatus> status;
    const sweep::CellState s = sweep::stateOf(r.out, cell, &status);
    if (queued.count(i) && s != sweep::CellState::Done) c.queued.push_back(cell);
    else if (s == sweep::CellState::Done) c.done.emplace_back(cell, *status);
    else if (s == sweep::CellState::Failed) c.failed.emplace_back(cell, *status);
    else c.pending.push_back(cell);
  }
  return c;
}

void listFailed(std::ostream& os, const SweepRequest& r, const Census& c) {
  for (const auto& [cell, status] : c.failed)
    os << "  failed: cell " << cell.id << " (exit " << status.exitCode << ", " << status.executor << " on " << status.host
       << "): " << (sweep::cellFolder(r.out, cell) / "stderr.txt").string() << "\n";
}

// One CSV line's fields (quoted ones unquoted).
std::vector<std::string> csvFields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else out.back() += c;
  }
  return out;
}

// A number where the whole field is one, null where it is empty, else the text.
nlohmann::json jsonValue(const std::string& v) {
  if (v.empty()) return nullptr;
  double d = 0.0;
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), d);
  if (!v.empty() && ec == std::errc() && end == v.data() + v.size() && std::isfinite(d)) return d;
  return v;
}

std::string csvField(const std::string& v) {
  if (v.find_first_of(",\"\n") == std::string::npos) return v;
  std::string q = "\"";
  for (const char ch : v) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

// The cell's own table: its CSV (header, rows), or its lesson report as a class-CSV row.
std::pair<std::string, std::vector<std::string>> cellTable(const SweepRequest& r, const sweep::Cell& cell) {
  const fs::path file = sweep::cellFolder(r.out, cell) / r.sweep.verb->table;
  std::string text;
  if (file.extension() == ".json") {
    // Named by its place in the results folder: the same table wherever the folder is.
    text = reportsCsv({{(fs::path("cells") / cell.id / r.sweep.verb->table).string(), readReport(file.string())}});
  } else {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error(file.string() + ": the cell finished but left no result table");
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
  // Records, not lines: a quoted field may hold a line break.
  std::vector<std::string> records(1);
  bool quoted = false;
  for (const char ch : text) {
    if (ch == '"') quoted = !quoted;
    if (ch == '\n' && !quoted) {
      records.emplace_back();
      continue;
    }
    records.back() += ch;
  }
  std::vector<std::string> rows;
  for (std::size_t i = 1; i < records.size(); ++i)
    if (!records[i].empty()) rows.push_back(records[i]);
  return {records[0], rows};
}

}  // namespace

int printSummary(std::ostream& os, const SweepRequest& r) {
  const Census c = census(r);
  os << "sweep " << r.sweep.name << " (" << r.sweep.verb->name << "): " << r.sweep.cellCount() << " cells: " << c.done.size()
     << " done, " << c.failed.size() << " failed, " << c.queued.size() << " in Slurm's queue, " << c.pending.size()
     << " not run; results in " << r.out.string() << "\n";
  double seconds = 0.0;
  for (const auto& d : c.done) seconds += d.second.seconds;
  if (!c.done.empty())
    os << "  the done cells took " << std::fixed << std::setprecision(1) << seconds << " s of wall time in all, "
       << seconds / double(c.done.size()) << " s each on average\n";
  os.unsetf(std::ios::fixed);
  listFailed(os, r, c);
  if (!c.failed.empty()) os << "  `millsim sweep FILE --local|--slurm --retry-failed` runs the failed cells again\n";
  return c.done.size() == r.sweep.cellCount() ? kExitOk : kExitFailure;
}

int collect(std::ostream& os, const SweepRequest& r) {
  const Census c = census(r);
  const fs::path csv = r.csv.empty() ? r.out / "results.csv" : fs::absolute(r.csv);
  std::string header, firstTable;
  std::ostringstream body;
  std::size_t rows = 0;
  nlohmann::json cells = nlohmann::json::array();
  for (const auto& [cell, status] : c.done) {
    const auto [cellHeader, cellRows] = cellTable(r, cell);
    nlohmann::json entry{{"cell", cell.id}, {"host", status.host}, {"cell_seconds", status.seconds}};
    for (std::size_t a = 0; a < r.sweep.axes.size(); ++a)
      entry["grid"][r.sweep.axes[a].spec->name] = jsonValue(sweep::shownValue(r.sweep, r.sweep.axes[a], cell.values[a]));
    const std::vector<std::string> names = csvFields(cellHeader);
    entry["rows"] = nlohmann::json::array();
    for (const std::string& row : cellRows) {
      const std::vector<std::string> values = csvFields(row);
      nlohmann::json o = nlohmann::json::object();
      for (std::size_t i = 0; i < names.size() && i < values.size(); ++i) o[names[i]] = jsonValue(values[i]);
      entry["rows"].push_back(std::move(o));
    }
    cells.push_back(std::move(entry));
    if (header.empty()) {
      header = "cell";
      for (const sweep::SweepParam& a : r.sweep.axes) header += "," + csvField(a.spec->name);
      header += ",host,cell_seconds," + cellHeader;
      firstTable = cellHeader;
    } else if (cellHeader != firstTable) {
      throw std::runtime_error("cell " + cell.id + "'s table has other columns than the cells before it: " + cellHeader);
    }
    std::ostringstream prefix;
    prefix << cell.id;
    for (std::size_t a = 0; a < r.sweep.axes.size(); ++a)
      prefix << "," << csvField(sweep::shownValue(r.sweep, r.sweep.axes[a], cell.values[a]));
    prefix << "," << csvField(status.host) << "," << std::fixed << std::setprecision(3) << status.seconds;
    for (const std::string& row : cellRows) body << prefix.str() << "," << row << "\n", ++rows;
  }
  fs::create_directories(csv.parent_path());
  std::ofstream out(csv, std::ios::binary);
  out << header << "\n" << body.str();
  out.close();
  if (!out) throw std::runtime_error(csv.string() + ": cannot write the merged table");
  fs::path json = csv;
  json.replace_extension(".json");
  std::ofstream jout(json, std::ios::binary);
  jout << nlohmann::json{{"sweep", r.sweep.name}, {"verb", r.sweep.verb->name}, {"cells", cells}}.dump(
              1, ' ', false, nlohmann::json::error_handler_t::replace)
       << "\n";
  jout.close();
  if (!jout) throw std::runtime_error(json.string() + ": cannot write the merged table");
  os << "collected " << c.done.size() << " of " << r.sweep.cellCount() << " cells (" << rows << " rows) into "
     << csv.string() << " (and " << json.filename().string() << "); host and cell_seconds say where and how long each ran (timings, as are columns named *_us)\n";
  if (header.find(",p99_us,") != std::string::npos || header.find(",force_rms,") != std::string::npos)
    os << "  run time against error: scripts/plot-sweep " << csv.string() << " --out pareto.png\n";
  listFailed(os, r, c);
  if (!c.queued.empty() || !c.pending.empty())
    os << "  " << c.queued.size() << " cells still in Slurm's queue, " << c.pending.size() << " not run\n";
  return c.done.size() == r.sweep.cellCount() ? kExitOk : kExitFailure;
}

}  // namespace millsim::app
