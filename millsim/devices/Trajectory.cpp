#include "millsim/devices/Trajectory.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <fstream>
#include <iterator>

#include "millsim/core/FieldValues.h"
#include "millsim/devices/RecordedRun.h"
#include "millsim/devices/TrajectoryUnits.h"

namespace millsim {

namespace {
constexpr std::uintmax_t kMaxBytes = std::uintmax_t(1) << 30;  // 1 GiB of CSV text: more than kMaxRows rows need
constexpr const char* kHeader = "t,x,y,z,qw,qx,qy,qz,button";

std::vector<std::string_view> splitCsv(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t start = 0;
  while (true) {
    std::size_t comma = line.find(',', start);
    std::string_view cell = line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    while (!cell.empty() && (cell.front() == ' ' || cell.front() == '\t')) cell.remove_prefix(1);
    while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\t' || cell.back() == '\r')) cell.remove_suffix(1);
    out.push_back(cell);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

// A header may name the length unit of its positions on x, y and z alike
// (t,x_mm,y_mm,z_mm,...): a spreadsheet in millimetres is then read as it
// means. Without one, metres, as a run's log writes them. The cells are
// renamed to x, y, z for the column check that follows; returns metres per unit.
double headerLengthUnit(std::vector<std::string_view>& cells, const std::string& header) {
  const char* const axes[] = {"x", "y", "z"};
  std::string_view unit;
  int named = 0;
  for (int a = 0; a < 3 && std::size_t(a + 1) < cells.size(); ++a) {
    std::string_view& cell = cells[std::size_t(a + 1)];
    if (cell.size() < 3 || cell.substr(0, 2) != std::string(axes[a]) + "_") continue;
    const std::string_view u = cell.substr(2);
    if (std::none_of(std::begin(kTrajectoryLengthUnits), std::end(kTrajectoryLengthUnits),
                     [&](const TrajectoryLengthUnit& k) { return k.name == u; }))
      throw TrajectoryError(header + "column '" + std::string(cell) + "' names the length unit '" + std::string(u) +
                            "'; the units a header may name are m, cm, mm and um (x_mm,y_mm,z_mm)");
    if (named > 0 && u != unit)
      throw TrajectoryError(header + "x, y and z name different units ('" + std::string(unit) + "' and '" +
                            std::string(u) + "'); name one unit on all three");
    unit = u, ++named;
    cell = axes[a];
  }
  if (named == 0) return 1.0;
  if (named != 3)
    throw TrajectoryError(header + "only some of x, y and z name a unit ('" + std::string(unit) +
                          "'); name it on all three (x_" + std::string(unit) + ",y_" + std::string(unit) + ",z_" +
                          std::string(unit) + ")");
  for (const TrajectoryLengthUnit& k : kTrajectoryLengthUnits)
    if (k.name == unit) return k.metres;
  return 1.0;
}
}  // namespace

Trajectory::Trajectory(std::vector<TrajectorySample> samples) : samples_(std::move(samples)) {
  if (samples_.empty()) throw TrajectoryError("a trajectory needs at least one row");
}

std::string readTrajectoryText(const std::filesystem::path& file) {
  // Reading a FIFO would wait forever and a device such as /dev/zero never
  // ends; a file past kMaxBytes cannot hold a valid trajectory's rows anyway.
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(file, ec);
  if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) {
    const char* kind = st.type() == std::filesystem::file_type::fifo        ? "a FIFO (named pipe)"
                       : st.type() == std::filesystem::file_type::directory ? "a folder"
                       : st.type() == std::filesystem::file_type::character ? "a character device"
                       : st.type() == std::filesystem::file_type::block     ? "a block device"
                                                                             : "not a regular file";
    throw TrajectoryError(file.string() + ": is " + kind + "; trajectories are read from regular files");
  }
  if (const auto bytes = std::filesystem::file_size(file, ec); !ec && bytes > kMaxBytes)
    throw TrajectoryError(file.string() + ": is " + std::to_string(bytes) + " bytes; trajectory files over " +
                          std::to_string(kMaxBytes) + " bytes are refused");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw TrajectoryError(file.string() + ": cannot open the trajectory file");
  std::string text;
  in.seekg(0, std::ios::end);
  if (const std::streamoff size = in.tellg(); size > 0) text.reserve(std::size_t(size));
  in.seekg(0);
  text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return text;
}

Trajectory Trajectory::load(const std::filesystem::path& file) {
  return parse(readTrajectoryText(file), file.string());
}

double Trajectory::checkRow(const std::string& where, double t, const glm::dvec3& position, const glm::dquat& q,
                           double previousTime) {
  if (t < 0.0 || t > kMaxTime)
    throw TrajectoryError(where + "time " + formatNumber(t) + " s is outside [0, " + formatNumber(kMaxTime) + "] s");
  if (!std::isnan(previousTime) && !(t > previousTime))
    throw TrajectoryError(where + "time " + formatNumber(t) + " does not increase (previous row: " +
                          formatNumber(previousTime) + ")");
  for (int a = 0; a < 3; ++a)
    if (std::abs(position[a]) > kMaxPosition)
      throw TrajectoryError(where + "column '" + "xyz"[a] + "' = " + formatNumber(position[a]) + " m is outside [-" +
                            formatNumber(kMaxPosition) + ", " + formatNumber(kMaxPosition) + "] m");
  const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  if (std::abs(norm - 1.0) > 1e-3)
    throw TrajectoryError(where + "the quaternion (qw,qx,qy,qz) has length " + formatNumber(norm) +
                          "; expected a unit quaternion");
  return norm;
}

Trajectory Trajectory::parse(const std::string& text, const std::string& file) {
  std::vector<TrajectorySample> rows;
  // A run's frame log is a trajectory too: the device poses and the button it recorded.
  if (RecordedRun::isFrameLog(text)) {
    const RecordedRun run = RecordedRun::parse(text, file);
    rows.reserve(run.frames().size());
    for (const RecordedFrame& f : run.frames())
      rows.push_back(TrajectorySample{f.t, Pose{f.device.position, glm::normalize(f.device.orientation)}, f.button});
    return Trajectory(std::move(rows));
  }
  // A UTF-8 byte-order mark (spreadsheets write one) is not part of the first column's name.
  const bool bom = text.rfind("\xEF\xBB\xBF", 0) == 0;
  // Lines are views into `text`: a 1 GiB file is not copied again.
  std::string_view rest(text);
  if (bom) rest.remove_prefix(3);
  int lineNo = 0;
  bool sawHeader = false;
  double metresPerUnit = 1.0;  // the header's length unit (x_mm,y_mm,z_mm: 0.001)
  const auto expected = splitCsv(kHeader);
  while (!rest.empty()) {
    const std::size_t newline = rest.find('\n');
    std::string_view l = rest.substr(0, newline);
    rest = newline == std::string_view::npos ? std::string_view() : rest.substr(newline + 1);
    ++lineNo;
    const std::string where = file + ":" + std::to_string(lineNo) + ": ";
    if (!l.empty() && l.back() == '\r') l.remove_suffix(1);
    if (l.find_first_not_of(" \t") == std::string_view::npos || l.front() == '#') continue;
    auto cells = splitCsv(l);
    if (!sawHeader) {
      // Every column is used, in this order; an unknown one is an error rather than silently dropped.
      const std::string header = where + "expected the header '" + kHeader + "', found '" + std::string(l) + "': ";
      metresPerUnit = headerLengthUnit(cells, header);
      for (std::size_t c = 0; c < cells.size(); ++c) {
        if (c < expected.size() && cells[c] == expected[c]) continue;
        const bool known = std::find(expected.begin(), expected.end(), cells[c]) != expected.end();
        if (!known)
          throw TrajectoryError(header + "unknown column '" + std::string(cells[c]) + "' (column " +
                                std::to_string(c + 1) + "); the accepted columns are " + kHeader + ", in this order");
        throw TrajectoryError(header + "column " + std::to_string(c + 1) + " is '" + std::string(cells[c]) +
                              "', expected " +
                              (c < expected.size() ? "'" + std::string(expected[c]) + "'" : std::string("no more")));
      }
      if (cells.size() < expected.size())
        throw TrajectoryError(header + "missing column '" + std::string(expected[cells.size()]) + "'");
      sawHeader = true;
      continue;
    }
    if (cells.size() != expected.size())
      throw TrajectoryError(where + "expected " + std::to_string(expected.size()) + " columns (" + kHeader +
                            "), found " + std::to_string(cells.size()));
    double v[9];
    for (int c = 0; c < 9; ++c) {
      std::string_view cell = cells[std::size_t(c)];
      if (!cell.empty() && cell.front() == '+') cell.remove_prefix(1);
      auto [p, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), v[c]);
      if (cell.empty() || ec != std::errc() || p != cell.data() + cell.size())
        throw TrajectoryError(where + "column '" + std::string(expected[std::size_t(c)]) + "' is not a number: '" +
                              std::string(cells[std::size_t(c)]) + "'");
      if (!std::isfinite(v[c]))
        throw TrajectoryError(where + "column '" + std::string(expected[std::size_t(c)]) +
                              "' is not finite: '" + std::string(cells[std::size_t(c)]) + "'");
    }
    if (rows.size() >= Trajectory::kMaxRows)
      throw TrajectoryError(where + "more than " + std::to_string(Trajectory::kMaxRows) + " rows");
    TrajectorySample s;
    s.t = v[0];
    s.pose.position = glm::dvec3(v[1], v[2], v[3]) * metresPerUnit;
    const glm::dquat q(v[4], v[5], v[6], v[7]);
    s.pose.orientation = q / checkRow(where, s.t, s.pose.position, q, rows.empty() ? NAN : rows.back().t);
    if (v[8] != 0.0 && v[8] != 1.0)
      throw TrajectoryError(where + "column 'button' must be 0 or 1, found '" + std::string(cells[8]) + "'");
    s.button = v[8] == 1.0;
    rows.push_back(s);
  }
  if (!sawHeader) throw TrajectoryError(file + ": empty trajectory; expected the header '" + kHeader + "'");
  if (rows.empty()) throw TrajectoryError(file + ": the trajectory has a header but no rows");
  return Trajectory(std::move(rows));
}

TrajectorySample Trajectory::at(double t) const {
  if (t <= samples_.front().t) return samples_.front();
  if (t >= samples_.back().t) return samples_.back();
  auto it = std::upper_bound(samples_.begin(), samples_.end(), t,
                             [](double x, const TrajectorySample& s) { return x < s.t; });
  const TrajectorySample& b = *it;
  const TrajectorySample& a = *(it - 1);
  const double u = (t - a.t) / (b.t - a.t);
  TrajectorySample out;
  out.t = t;
  out.pose.position = a.pose.position + (b.pose.position - a.pose.position) * u;
  out.pose.orientation = glm::normalize(glm::slerp(a.pose.orientation, b.pose.orientation, u));
  out.button = a.button;
  return out;
}

std::string Trajectory::toCsv() const {
  std::string s = std::string(kHeader) + "\n";
  for (const auto& r : samples_) {
    const auto& p = r.pose.position;
    const auto& q = r.pose.orientation;
    for (double v : {r.t, p.x, p.y, p.z, q.w, q.x, q.y, q.z}) s += formatNumber(v) + ",";
    s += r.button ? "1\n" : "0\n";
  }
  return s;
}

}  // namespace millsim
