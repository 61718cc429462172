#include "millsim/core/Diagnostics.h"

namespace millsim {

std::string SourceLocation::str() const {
  std::string s = file.empty() ? std::string("<unknown>") : file;
  if (line > 0) {
    s += ':' + std::to_string(line);
    if (column > 0) s += ':' + std::to_string(column);
  }
  return s;
}

std::string Diagnostic::str() const {
  const char* kind = severity == Severity::Error ? "error" : severity == Severity::Warning ? "warning" : "note";
  return where.str() + ": " + kind + ": " + message;
}

void DiagnosticSink::error(SourceLocation where, std::string message) {
  if (full()) return;
  ++errorCount_;
  items_.push_back({Severity::Error, std::move(where), std::move(message)});
  if (full()) items_.push_back(Diagnostic{Severity::Note, SourceLocation{}, std::string("too many errors; stopping here")});
}

void DiagnosticSink::warning(SourceLocation where, std::string message) {
  items_.push_back({Severity::Warning, std::move(where), std::move(message)});
}

void DiagnosticSink::note(SourceLocation where, std::string message) {
  items_.push_back({Severity::Note, std::move(where), std::move(message)});
}

}  // namespace millsim
