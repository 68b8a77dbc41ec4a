// A progress bar with ETA on stderr for work longer than a second. It stays silent when stderr is not a
// terminal (logs, CI) unless forced, and during the first second, so quick commands print nothing.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace shadelab::cli {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label, bool force = false)
      : m_label(std::move(label)), m_enabled(force || ::isatty(STDERR_FILENO) != 0),
        m_start(std::chrono::steady_clock::now()) {}
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;
  ~ProgressBar() { finish(); }

  void update(double fraction) {
    if (!m_enabled) return;
    const double elapsed = seconds();
    if (elapsed < 1.0 && fraction < 1.0) return;
    const int width = 30;
    const int filled = static_cast<int>(fraction * width + 0.5);
    const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    std::fprintf(stderr, "\r%s [%s%s] %3d%% ETA %.0fs ", m_label.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(width - filled), ' ').c_str(), static_cast<int>(fraction * 100.0 + 0.5), eta);
    std::fflush(stderr);
    m_shown = true;
  }

  void finish() {
    if (m_shown) {
      std::fprintf(stderr, "\n");
      m_shown = false;
    }
  }

 private:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  }
  std::string m_label;
  bool m_enabled;
  bool m_shown = false;
  std::chrono::steady_clock::time_point m_start;
};

}  // namespace shadelab::cli
