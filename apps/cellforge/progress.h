// A progress line on standard error for long runs (info, convert): the command and
// the stage it is in, with the seconds so far, redrawn in place while a stage
// lasts and cleared at the end. Only when standard error is a terminal, and only
// once the run has taken a second (short runs print nothing); never into a pipe
// or a file, where it would only be noise in a log. CELLFORGE_PROGRESS_AFTER=S
// (seconds) sets the delay, for tests.
#pragma once

#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

namespace cellforge::cli {

class Progress {
 public:
  explicit Progress(std::string command) : command_(std::move(command)) {
    if (!isatty(STDERR_FILENO)) return;
    if (const char* after = std::getenv("CELLFORGE_PROGRESS_AFTER")) after_ = std::atof(after);
    start_ = std::chrono::steady_clock::now();
    ticker_ = std::thread([this] { run(); });
  }
  ~Progress() { finish(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void stage(std::string_view name) {
    std::lock_guard lock(mutex_);
    stage_ = name;
    if (ticker_.joinable()) draw();
  }
  // Stops the ticker and clears the line (before the command prints its result).
  void finish() {
    if (!ticker_.joinable()) return;
    {
      std::lock_guard lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    ticker_.join();
    if (drawn_) std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::milliseconds(200), [this] { return done_; })) draw();
  }
  // Redraws the line once the run has taken after_ seconds (mutex_ held).
  void draw() {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (s < after_) return;
    std::fprintf(stderr, "\r\033[K%s: %s (%.1f s)", command_.c_str(), stage_.c_str(), s);
    std::fflush(stderr);
    drawn_ = true;
  }

  std::string command_;
  std::string stage_ = "starting";
  std::chrono::steady_clock::time_point start_;
  double after_ = 1.0;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false, drawn_ = false;
  std::thread ticker_;
};

}  // namespace cellforge::cli
