// Progress of a long job (flagd render, flagctl export) on stderr. On a terminal: one line
// redrawn in place, at most kRedrawsPerSecond times a second. Elsewhere (a pipe, a file, a
// test) nothing until the end, then a plain final line, so logs do not fill with bars.
#pragma once

#include <cstdio>
#include <string>

namespace flagsim {

class ProgressBar {
 public:
  static constexpr int kWidth = 30;  ///< characters between the brackets
  static constexpr double kRedrawsPerSecond = 10;

  /// Draws on `stream`, as a bar only if it is a terminal.
  explicit ProgressBar(std::FILE* stream = stderr);
  ProgressBar(std::FILE* stream, bool interactive);

  /// `fraction` done (0 .. 1) and a short note on what is being done.
  void Update(double fraction, const std::string& detail);
  /// Clears the bar and writes `line` (always, terminal or not).
  void Finish(const std::string& line);

 private:
  std::FILE* stream_;
  bool interactive_;
  double last_draw_ = -1;  ///< s, monotonic
};

/// "[#######.......]  45%": `width` characters between the brackets; fraction clamped to 0 .. 1.
std::string BarText(double fraction, int width);

}  // namespace flagsim
