#include "common/progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace flagsim {
namespace {

double Now() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

ProgressBar::ProgressBar(std::FILE* stream) : ProgressBar(stream, isatty(fileno(stream)) != 0) {}

ProgressBar::ProgressBar(std::FILE* stream, bool interactive) : stream_(stream), interactive_(interactive) {}

std::string BarText(double fraction, int width) {
  fraction = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  const int filled = static_cast<int>(std::floor(fraction * width));
  char percent[8];
  std::snprintf(percent, sizeof(percent), "%4d%%", static_cast<int>(std::floor(fraction * 100)));
  return "[" + std::string(filled, '#') + std::string(width - filled, '.') + "]" + percent;
}

void ProgressBar::Update(double fraction, const std::string& detail) {
  if (!interactive_) return;
  const double now = Now();
  if (last_draw_ >= 0 && now - last_draw_ < 1 / kRedrawsPerSecond) return;
  last_draw_ = now;
  // \r back to the line's start; ESC[K clears what a longer line left
  std::fprintf(stream_, "\r%s  %s\x1b[K", BarText(fraction, kWidth).c_str(), detail.c_str());
  std::fflush(stream_);
}

void ProgressBar::Finish(const std::string& line) {
  if (interactive_ && last_draw_ >= 0) std::fprintf(stream_, "\r\x1b[K");
  std::fprintf(stream_, "%s\n", line.c_str());
  std::fflush(stream_);
}

}  // namespace flagsim
