#pragma once
// Where something was written, and what was wrong with it. Every user-facing
// error of the loader is a Diagnostic so tools print them the same way:
//   file:line:column: error: message
#include <string>
#include <vector>

namespace millsim {

class LoadProgress;

struct SourceLocation {
  std::string file;  // as given to the loader (or "<string>")
  int line = 0;      // 1-based; 0 = unknown
  int column = 0;    // 1-based; 0 = unknown

  std::string str() const;  // "file:line:column" (omits unknown parts)
};

enum class Severity { Error, Warning, Note };

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceLocation where;
  std::string message;

  std::string str() const;  // "file:line:col: error: message"
};

// Collects diagnostics; stops accepting errors past a limit so a badly broken
// file cannot flood the terminal.
class DiagnosticSink {
public:
  explicit DiagnosticSink(std::size_t maxErrors = 25) : maxErrors_(maxErrors) {}
  void error(SourceLocation where, std::string message);
  void warning(SourceLocation where, std::string message);
  void note(SourceLocation where, std::string message);
  bool hasErrors() const { return errorCount_ > 0; }
  bool full() const { return errorCount_ >= maxErrors_; }
  std::size_t errorCount() const { return errorCount_; }
  const std::vector<Diagnostic>& all() const { return items_; }
  std::vector<Diagnostic> take() { return std::move(items_); }
  // Who hears of the load's long steps (Progress.h); none by default.
  void setProgress(LoadProgress* listener) { progress_ = listener; }
  LoadProgress* progress() const { return progress_; }

private:
  LoadProgress* progress_ = nullptr;
  std::size_t maxErrors_;
  std::size_t errorCount_ = 0;
  std::vector<Diagnostic> items_;
};

}  // namespace millsim
