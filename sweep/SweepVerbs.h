#pragma once
// The verbs a sweep can run, and for each the parameters a sweep file may fix
// or vary: how each becomes the cell's command line, and which file the cell
// leaves as its result. One table, read by the sweep file's validation, the
// cells' commands, `collect` and docs/sweeps.md.
#include <string>
#include <vector>

namespace millsim::sweep {

enum class ParamKind {
  Path,      // a file in the sweep's folder (or a {"glob": ...} of them on a grid axis)
  Text,      // any string
  Number,    // a finite number in [lo, hi]
  Renderer,  // a registered renderer type
  Override,  // TYPE.FIELD=VALUE (the verb's --set)
  RendererField,  // FIELD=VALUE of the renderers measured (bench's --set)
  Flag,      // true or false: the option is given or not
};

struct ParamSpec {
  std::string name;    // as the sweep file writes it
  ParamKind kind;
  std::string option;  // "--trajectory"; empty: a positional argument
  bool required = false;
  double lo = 0.0, hi = 0.0;  // Number's range
  std::string help;
  bool integer = false;  // Number: whole numbers only
};

struct VerbSpec {
  std::string name;                // "replay", "bench physical"
  std::vector<std::string> words;  // its words on the command line
  std::vector<ParamSpec> params;
  std::vector<std::string> resultArgs;  // what the cell adds for its result files
  std::string table;                    // the file collect reads: a CSV, or a report JSON
  std::string help;
};

const std::vector<VerbSpec>& sweepVerbs();
const VerbSpec* findVerb(const std::string& name);
const ParamSpec* findParam(const VerbSpec& verb, const std::string& name);
std::string kindName(ParamKind kind);

}  // namespace millsim::sweep
