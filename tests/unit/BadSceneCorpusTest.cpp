// The malformed-scene corpus: every file in tests/data/bad must be refused, and
// the first error must name the right place and say what is wrong. What each
// file should produce is listed in tests/data/bad/expected.txt:
//   FILE|LINE|COLUMN|message substring[|in=HELPER]
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "millsim/core/NodeRegistry.h"
#include "millsim/x3d/X3DLoader.h"

namespace millsim {
namespace {

namespace fs = std::filesystem;

const fs::path& corpusDir() {
  static const fs::path dir = fs::path(MILLSIM_SOURCE_DIR) / "tests" / "data" / "bad";
  return dir;
}

struct Expectation {
  std::string file;          // corpus file name, e.g. "08-unknown-node-near-miss.x3d"
  int line = 0;
  int column = -1;           // -1: not checked
  std::string message;       // substring of the first error
  std::string reportedIn;    // file the error is reported in, relative to the corpus folder
  int manifestLine = 0;
};

// gtest prints the parameter of a failing case; show the corpus file, not bytes.
void PrintTo(const Expectation& e, std::ostream* os) { *os << e.file; }

std::vector<std::string> splitBar(const std::string& s) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (;;) {
    std::size_t bar = s.find('|', start);
    parts.push_back(s.substr(start, bar == std::string::npos ? std::string::npos : bar - start));
    if (bar == std::string::npos) return parts;
    start = bar + 1;
  }
}

// Malformed manifest lines become expectations with an empty message, which the
// test reports as a failure (with the manifest line) rather than skipping them.
std::vector<Expectation> readManifest() {
  std::vector<Expectation> out;
  std::ifstream in(corpusDir() / "expected.txt");
  std::string text;
  int n = 0;
  while (std::getline(in, text)) {
    ++n;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty() || text.front() == '#') continue;
    Expectation e;
    e.manifestLine = n;
    std::vector<std::string> f = splitBar(text);
    e.file = f[0];
    e.reportedIn = f[0];
    if (f.size() < 4 || f.size() > 5) {
      out.push_back(e);
      continue;
    }
    try {
      e.line = std::stoi(f[1]);
      e.column = f[2] == "-" ? -1 : std::stoi(f[2]);
    } catch (const std::exception&) {
      out.push_back(e);
      continue;
    }
    e.message = f[3];
    if (f.size() == 5) {
      if (f[4].rfind("in=", 0) != 0) {
        e.message.clear();
        out.push_back(e);
        continue;
      }
      e.reportedIn = f[4].substr(3);
    }
    out.push_back(e);
  }
  return out;
}

const std::vector<Expectation>& manifest() {
  static const std::vector<Expectation> m = readManifest();
  return m;
}

LoadOptions corpusOptions() {
  LoadOptions options;
  options.plugins.searchPath = {};  // MILLSIM_PLUGIN_PATH must not change the outcome
  options.plugins.allowAnyPath = false;
  return options;
}

const Diagnostic* firstError(const LoadResult& r) {
  for (const auto& d : r.diagnostics)
    if (d.severity == Severity::Error) return &d;
  return nullptr;
}

// "08-unknown-node-near-miss.x3d" -> "08_unknown_node_near_miss"
std::string testName(const ::testing::TestParamInfo<Expectation>& info) {
  std::string s = info.param.file;
  if (s.size() > 4 && s.ends_with(".x3d")) s.resize(s.size() - 4);
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s.empty() ? "line_" + std::to_string(info.param.manifestLine) : s;
}

// Test names contain "bad_scene" so that `ctest -R bad_scene` selects them all:
//   bad_scene/Corpus.FirstErrorMatchesManifest/08_unknown_node_near_miss
//   bad_scene_corpus.EveryFileHasAManifestLine
class Corpus : public ::testing::TestWithParam<Expectation> {};

TEST_P(Corpus, FirstErrorMatchesManifest) {
  const Expectation& e = GetParam();
  ASSERT_FALSE(e.message.empty()) << "expected.txt line " << e.manifestLine
                                  << " is not FILE|LINE|COLUMN|message[|in=HELPER]";
  const fs::path file = corpusDir() / e.file;
  ASSERT_TRUE(fs::is_regular_file(file)) << file << " is listed in expected.txt but does not exist";

  LoadResult r = loadSceneFile(file, builtinRegistry(), corpusOptions());
  const std::string report = r.report();
  ASSERT_FALSE(r.ok()) << e.file << " loaded without errors:\n" << report;

  const Diagnostic* d = firstError(r);
  ASSERT_NE(d, nullptr) << "no error diagnostic:\n" << report;
  const std::string where = "first error: " + d->str() + "\nall diagnostics:\n" + report;
  EXPECT_TRUE(d->where.file.ends_with(e.reportedIn))
      << "expected the error in a file ending with '" << e.reportedIn << "'\n" << where;
  EXPECT_EQ(d->where.line, e.line) << where;
  if (e.column >= 0) {
    EXPECT_EQ(d->where.column, e.column) << where;
  }
  EXPECT_NE(d->message.find(e.message), std::string::npos)
      << "expected the message to contain: " << e.message << "\n" << where;
}

INSTANTIATE_TEST_SUITE_P(bad_scene, Corpus, ::testing::ValuesIn(manifest()), testName);

TEST(bad_scene_corpus, EveryFileHasAManifestLine) {
  std::set<std::string> listed;
  for (const auto& e : manifest()) {
    EXPECT_TRUE(listed.insert(e.file).second) << e.file << " is listed twice in expected.txt";
  }
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(corpusDir())) {
    if (!entry.is_regular_file() || entry.path().extension() != ".x3d") continue;
    ++files;
    const std::string name = entry.path().filename().string();
    // Fuzzer findings are kept next to the corpus for reference but are not part of it.
    if (name.rfind("fuzz-crash-", 0) == 0) {
      --files;
      continue;
    }
    EXPECT_TRUE(listed.count(name)) << name << " has no line in tests/data/bad/expected.txt";
  }
  for (const auto& name : listed)
    EXPECT_TRUE(fs::is_regular_file(corpusDir() / name)) << name << " is in expected.txt but missing";
  EXPECT_GE(files, 35u) << "the corpus should hold at least 35 malformed scenes";
}

// An internal DTD subset with nested entities (the "billion laughs" attack) must
// be refused quickly and without expanding anything. There is no timing
// assertion: a regression shows up as a hang (ctest's timeout) or an OOM.
TEST(bad_scene_corpus, BillionLaughsIsRefusedWithoutExpansion) {
  const fs::path file = corpusDir() / "45-billion-laughs-entity.x3d";
  ASSERT_TRUE(fs::is_regular_file(file));
  LoadResult r = loadSceneFile(file, builtinRegistry(), corpusOptions());
  ASSERT_FALSE(r.ok());
  const Diagnostic* d = firstError(r);
  ASSERT_NE(d, nullptr);
  std::string lower = d->message;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  EXPECT_NE(lower.find("entity"), std::string::npos) << d->str();
  // Nothing like the 10^9-character expansion may reach the diagnostics either.
  EXPECT_LT(r.report().size(), 10000u);
}

// The same text loaded from memory with file access off (as the fuzzer does).
TEST(bad_scene_corpus, BillionLaughsFromMemoryIsRefused) {
  std::ifstream in(corpusDir() / "45-billion-laughs-entity.x3d");
  std::stringstream ss;
  ss << in.rdbuf();
  ASSERT_FALSE(ss.str().empty());
  LoadOptions options = corpusOptions();
  options.allowFileAccess = false;
  LoadResult r = loadSceneString(ss.str(), "laughs.x3d", builtinRegistry(), options);
  ASSERT_FALSE(r.ok());
  const Diagnostic* d = firstError(r);
  ASSERT_NE(d, nullptr);
  EXPECT_NE(d->message.find("entity"), std::string::npos) << d->str();
}

}  // namespace
}  // namespace millsim
