#include "millsim/session/LessonReport.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace millsim {

using Json = nlohmann::ordered_json;

namespace {
// The mean over the targets of min(1, fraction); negative without targets.
double targetsFraction(const LessonReport& r) {
  double sum = 0.0;
  int targets = 0;
  for (const RegionResult& g : r.regions)
    if (!g.forbidden) sum += std::min(1.0, g.fraction()), ++targets;
  return targets ? sum / targets : -1.0;
}
}  // namespace

double lessonScore(const LessonReport& r) {
  const double done = targetsFraction(r);
  if (done < 0.0) return -1.0;
  int violations = 0;
  for (const RegionResult& g : r.regions) violations += g.forbidden && g.firstViolation >= 0.0;
  const double overPrepared = std::max(0.0, 1.0 - r.removal.overPreparationPenalty * r.removal.overPreparation());
  return 100.0 * done * std::pow(0.5, violations) * overPrepared;
}

std::string reportJson(const LessonReport& r) {
  Json j;
  j["scene"] = r.scene;
  j["renderer"] = r.renderer;
  j["duration_s"] = r.duration;
  j["removed_mm3"] = r.removed * 1e9;
  j["peak_force_N"] = r.peakForce;
  j["peak_torque_Nm"] = r.peakTorque;
  j["targets"] = Json::array();
  j["forbidden"] = Json::array();
  for (const RegionResult& g : r.regions) {
    if (g.forbidden) {
      Json f{{"name", g.name}, {"removed_mm3", g.removed * 1e9}};
      f["first_violation_s"] = g.firstViolation >= 0.0 ? Json(g.firstViolation) : Json(nullptr);
      f["first_entry_s"] = g.firstEntry >= 0.0 ? Json(g.firstEntry) : Json(nullptr);
      f["depth_mm"] = g.depth * 1e3;
      f["swept_mm3"] = g.swept * 1e9;
      f["thinnest_wall_mm"] = g.thinnestWall >= 0.0 ? Json(g.thinnestWall * 1e3) : Json(nullptr);
      j["forbidden"].push_back(f);
    } else {
      j["targets"].push_back(
          Json{{"name", g.name}, {"removed_mm3", g.removed * 1e9}, {"fraction", g.fraction()}, {"initial_mm3", g.initial * 1e9}});
    }
  }
  if (r.removal.hasTargets) {
    j["outside_targets_mm3"] = r.removal.outsideTargets * 1e9;
    j["over_preparation"] = r.removal.overPreparation();
    j["over_preparation_penalty"] = r.removal.overPreparationPenalty;
    j["completed_s"] = r.removal.completed >= 0.0 ? Json(r.removal.completed) : Json(nullptr);
  }
  j["deepest_cut_mm"] = r.removal.deepestCut * 1e3;
  j["tissues"] = Json::array();
  for (const auto& [name, removed] : r.removal.byTissue) j["tissues"].push_back(Json{{"name", name}, {"removed_mm3", removed * 1e9}});
  const double score = lessonScore(r);
  j["score"] = score >= 0.0 ? Json(score) : Json(nullptr);
  return j.dump(2) + "\n";
}

void writeReport(const std::string& path, const LessonReport& r) {
  std::ofstream out(path, std::ios::binary);
  out << reportJson(r);
  out.close();
  if (!out) throw std::runtime_error(path + ": cannot write the report");
}

LessonReport readReport(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read the report");
  Json j;
  try {
    j = Json::parse(in);
  } catch (const Json::parse_error& e) {
    throw std::runtime_error(path + ": not a JSON report (" + e.what() + ")");
  }
  auto need = [&](const Json& o, const char* key, const char* where) -> const Json& {
    if (!o.is_object() || !o.contains(key))
      throw std::runtime_error(path + ": " + where + " has no \"" + key + "\" (is it a millsim report?)");
    return o[key];
  };
  auto number = [&](const Json& o, const char* key, const char* where) {
    const Json& v = need(o, key, where);
    if (!v.is_number()) throw std::runtime_error(path + ": \"" + key + "\" in " + where + " must be a number, found " + v.dump());
    return v.get<double>();
  };
  auto text = [&](const Json& o, const char* key, const char* where) {
    const Json& v = need(o, key, where);
    if (!v.is_string()) throw std::runtime_error(path + ": \"" + key + "\" in " + where + " must be a string, found " + v.dump());
    return v.get<std::string>();
  };
  LessonReport r;
  r.scene = text(j, "scene", "the report");
  r.renderer = text(j, "renderer", "the report");
  r.duration = number(j, "duration_s", "the report");
  r.removed = number(j, "removed_mm3", "the report") * 1e-9;
  r.peakForce = number(j, "peak_force_N", "the report");
  r.peakTorque = number(j, "peak_torque_Nm", "the report");
  for (const Json& t : need(j, "targets", "the report")) {
    RegionResult g;
    g.name = text(t, "name", "a target");
    g.removed = number(t, "removed_mm3", "a target") * 1e-9;
    const double fraction = number(t, "fraction", "a target");
    g.initial = t.contains("initial_mm3") && t["initial_mm3"].is_number() ? t["initial_mm3"].get<double>() * 1e-9
                : fraction > 0.0                                         ? g.removed / fraction
                                                                         : 0.0;
    r.regions.push_back(g);
  }
  for (const Json& f : need(j, "forbidden", "the report")) {
    RegionResult g;
    g.forbidden = true;
    g.name = text(f, "name", "a forbidden region");
    g.removed = number(f, "removed_mm3", "a forbidden region") * 1e-9;
    const Json& first = need(f, "first_violation_s", "a forbidden region");
    g.firstViolation = first.is_null() ? -1.0 : number(f, "first_violation_s", "a forbidden region");
    // Reports written before soft tissues were entered have none of these.
    if (f.contains("first_entry_s") && !f["first_entry_s"].is_null())
      g.firstEntry = number(f, "first_entry_s", "a forbidden region");
    if (f.contains("depth_mm")) g.depth = number(f, "depth_mm", "a forbidden region") * 1e-3;
    if (f.contains("swept_mm3")) g.swept = number(f, "swept_mm3", "a forbidden region") * 1e-9;
    if (f.contains("thinnest_wall_mm") && !f["thinnest_wall_mm"].is_null())
      g.thinnestWall = number(f, "thinnest_wall_mm", "a forbidden region") * 1e-3;
    r.regions.push_back(g);
  }
  // Reports written before over-preparation and tissues were counted have none of these.
  for (const RegionResult& g : r.regions) r.removal.hasTargets |= !g.forbidden;
  if (j.contains("outside_targets_mm3")) r.removal.outsideTargets = number(j, "outside_targets_mm3", "the report") * 1e-9;
  if (j.contains("over_preparation_penalty"))
    r.removal.overPreparationPenalty = number(j, "over_preparation_penalty", "the report");
  if (j.contains("over_preparation")) {
    const double share = number(j, "over_preparation", "the report");
    r.removal.targetsInitial = share > 0.0 ? r.removal.outsideTargets / share : 0.0;
  }
  if (r.removal.targetsInitial == 0.0)
    for (const RegionResult& g : r.regions) r.removal.targetsInitial += g.forbidden ? 0.0 : g.initial;
  if (j.contains("completed_s") && !j["completed_s"].is_null()) r.removal.completed = number(j, "completed_s", "the report");
  if (j.contains("deepest_cut_mm")) r.removal.deepestCut = number(j, "deepest_cut_mm", "the report") * 1e-3;
  if (j.contains("tissues"))
    for (const Json& t : j["tissues"]) r.removal.byTissue.emplace_back(text(t, "name", "a tissue"), number(t, "removed_mm3", "a tissue") * 1e-9);
  return r;
}

namespace {
std::string completedText(const RemovalSummary& s) {
  if (s.completed < 0.0) return "not reached";
  return (std::ostringstream() << std::fixed << std::setprecision(2) << "at " << s.completed << " s").str();
}

// ", entered at 6.612 s, 0.42 mm deep, 0.213 mm³ swept" for a forbidden soft tissue the burr entered;
// ", thinnest wall left 0.84 mm" for one it did not.
std::string entered(const RegionResult& g) {
  if (g.firstEntry < 0.0 && g.thinnestWall > 0.0)
    return (std::ostringstream() << std::fixed << std::setprecision(2) << ", thinnest wall left " << g.thinnestWall * 1e3
                                 << " mm")
        .str();
  if (g.firstEntry < 0.0) return {};
  std::ostringstream o;
  o << std::fixed << ", entered at " << std::setprecision(3) << g.firstEntry << " s, " << std::setprecision(2)
    << g.depth * 1e3 << " mm deep, " << std::setprecision(3) << g.swept * 1e9 << " mm³ swept";
  return o.str();
}
}  // namespace

std::string describeReport(const LessonReport& r, bool markdown) {
  std::ostringstream o;
  o << std::fixed;
  const double score = lessonScore(r);
  const std::string scoreText = score >= 0.0 ? (std::ostringstream() << std::fixed << std::setprecision(1) << score).str()
                                             : std::string("none (the lesson has no MillingTarget)");
  if (markdown) {
    o << "# Lesson report: " << r.scene << "\n\n"
      << "| | |\n|---|---|\n"
      << "| renderer | " << r.renderer << " |\n"
      << "| duration | " << std::setprecision(2) << r.duration << " s |\n"
      << "| removed | " << std::setprecision(3) << r.removed * 1e9 << " mm³ |\n"
      << "| peak force | " << std::setprecision(2) << r.peakForce << " N |\n"
      << "| peak torque | " << std::setprecision(4) << r.peakTorque << " N·m |\n";
    if (r.removal.hasTargets)
      o << "| outside the targets | " << std::setprecision(3) << r.removal.outsideTargets * 1e9 << " mm³ ("
        << std::setprecision(1) << 100.0 * r.removal.overPreparation() << " % of the targets' material; penalty "
        << std::setprecision(2) << r.removal.overPreparationPenalty << ") |\n"
        << "| targets done | " << completedText(r.removal) << " |\n";
    o << "| deepest cut | " << std::setprecision(2) << r.removal.deepestCut * 1e3 << " mm below the surface |\n";
    o << "| **score** | **" << scoreText << "** |\n\n";
    if (!r.removal.byTissue.empty()) {
      o << "| tissue | removed (mm³) |\n|---|---|\n";
      for (const auto& [name, removed] : r.removal.byTissue)
        o << "| " << name << " | " << std::setprecision(3) << removed * 1e9 << " |\n";
      o << "\n";
    }
    o << "| region | kind | removed (mm³) | result |\n|---|---|---|---|\n";
    for (const RegionResult& g : r.regions) {
      o << "| " << g.name << " | " << (g.forbidden ? "forbidden" : "target") << " | " << std::setprecision(3)
        << g.removed * 1e9 << " | ";
      if (g.forbidden)
        o << (g.firstViolation >= 0.0 ? "violated at " + (std::ostringstream() << std::fixed << std::setprecision(3) << g.firstViolation).str() + " s"
                                      : std::string("not touched"))
          << entered(g);
      else
        o << std::setprecision(1) << 100.0 * g.fraction() << " % removed";
      o << " |\n";
    }
    return o.str();
  }
  o << "lesson report: " << r.scene << "\n"
    << "  renderer " << r.renderer << ", " << std::setprecision(2) << r.duration << " s, removed "
    << std::setprecision(3) << r.removed * 1e9 << " mm³, peak force " << std::setprecision(2) << r.peakForce
    << " N, peak torque " << std::setprecision(4) << r.peakTorque << " N·m\n";
  for (const RegionResult& g : r.regions) {
    o << "  " << (g.forbidden ? "forbidden " : "target    ") << g.name << ": removed " << std::setprecision(3)
      << g.removed * 1e9 << " mm³";
    if (g.forbidden)
      o << (g.firstViolation >= 0.0
                ? ", VIOLATED at " + (std::ostringstream() << std::fixed << std::setprecision(3) << g.firstViolation).str() + " s"
                : std::string(", not touched"))
        << entered(g);
    else
      o << " (" << std::setprecision(1) << 100.0 * g.fraction() << " % of it)";
    o << "\n";
  }
  if (r.removal.hasTargets)
    o << "  outside the targets: " << std::setprecision(3) << r.removal.outsideTargets * 1e9 << " mm³ ("
      << std::setprecision(1) << 100.0 * r.removal.overPreparation() << " % of the targets' material, penalty "
      << std::setprecision(2) << r.removal.overPreparationPenalty << "); targets done " << completedText(r.removal)
      << "\n";
  o << "  deepest cut " << std::setprecision(2) << r.removal.deepestCut * 1e3 << " mm below the surface\n";
  if (!r.removal.byTissue.empty()) {
    o << "  removed per tissue:";
    for (const auto& [name, removed] : r.removal.byTissue)
      o << " " << name << " " << std::setprecision(3) << removed * 1e9 << " mm³";
    o << "\n";
  }
  o << "  score " << scoreText << "\n";
  return o.str();
}

std::string reportsCsv(const std::vector<std::pair<std::string, LessonReport>>& reports) {
  std::ostringstream o;
  o << "file,scene,renderer,duration_s,removed_mm3,targets_fraction,outside_targets_mm3,over_preparation,"
       "completed_s,deepest_cut_mm,thinnest_wall_mm,violations,first_violation_s,peak_force_N,score\n";
  auto cell = [](const std::string& s) {  // RFC 4180: quote a cell holding a comma, quote or newline
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
  };
  auto number = [](double v) { return (std::ostringstream() << std::setprecision(6) << v).str(); };
  for (const auto& [file, r] : reports) {
    double firstViolation = -1.0, wall = -1.0;
    int violations = 0;
    for (const RegionResult& g : r.regions) {
      if (g.forbidden && g.thinnestWall >= 0.0 && (wall < 0.0 || g.thinnestWall < wall)) wall = g.thinnestWall;
      if (g.forbidden && g.firstViolation >= 0.0) {
        ++violations;
        if (firstViolation < 0.0 || g.firstViolation < firstViolation) firstViolation = g.firstViolation;
      }
    }
    const double score = lessonScore(r), done = targetsFraction(r);
    o << cell(file) << ',' << cell(r.scene) << ',' << cell(r.renderer) << ',' << number(r.duration) << ','
      << number(r.removed * 1e9) << ',' << (done >= 0.0 ? number(done) : "") << ','
      << (r.removal.hasTargets ? number(r.removal.outsideTargets * 1e9) : "") << ','
      << (r.removal.hasTargets ? number(r.removal.overPreparation()) : "") << ','
      << (r.removal.completed >= 0.0 ? number(r.removal.completed) : "") << ',' << number(r.removal.deepestCut * 1e3)
      << ',' << (wall >= 0.0 ? number(wall * 1e3) : "") << ',' << violations << ','
      << (firstViolation >= 0.0 ? number(firstViolation) : "") << ',' << number(r.peakForce) << ','
      << (score >= 0.0 ? number(score) : "") << "\n";
  }
  return o.str();
}

}  // namespace millsim
