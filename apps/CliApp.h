#pragma once
// The millsim command's application object and its parse-and-run, shared by
// the command's own fast path (main.cpp: --version, nodes) and the full set
// of verbs in libmillsim_cli (CliMain.cpp), so that both print the same
// title, version and errors.
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include "Commands.h"
#include "MillSimVersion.h"

namespace millsim::app {

inline void describeApp(CLI::App& app) {
  app.description("MillSim: 6-DOF haptic milling on X3D scenes.");
  app.name("millsim");
  app.set_version_flag("--version", std::string("millsim ") + MILLSIM_VERSION);
  app.require_subcommand(1);
}

// True, having said so, when the first word that is not an option (the
// command's own options are flags) is not a verb: CLI11 would only say that
// one is required, not which word it did not know.
inline bool unknownVerb(const CLI::App& app, int argc, char** argv) {
  int first = 1;
  while (first < argc && argv[first][0] == '-') ++first;
  if (first >= argc) return false;
  std::string verbs;
  bool known = false;
  for (const CLI::App* verb : app.get_subcommands([](const CLI::App*) { return true; })) {
    known = known || verb->check_name(argv[first]);
    verbs += (verbs.empty() ? "" : ", ") + verb->get_name();
  }
  if (!known)
    std::cerr << "millsim: error: unknown command '" << argv[first] << "' (expected one of: " << verbs
              << ")\nRun with --help for more information.\n";
  return !known;
}

// Parses the arguments and runs the chosen verb; `result` is what the verb set.
inline int parseAndRun(CLI::App& app, int argc, char** argv, const int& result) {
  if (unknownVerb(app, argc, argv)) return kExitBadInput;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, version or the usage error
    return code == 0 ? kExitOk : kExitBadInput;
  } catch (const std::bad_alloc&) {
    // The verbs report their own errors; what still escapes must not abort the process.
    std::cerr << "millsim: error: out of memory\n";
    return kExitFailure;
  } catch (const std::exception& e) {
    std::cerr << "millsim: error: " << e.what() << "\n";
    return kExitFailure;
  }
  return result;
}

}  // namespace millsim::app
