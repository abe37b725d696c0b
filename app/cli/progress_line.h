// A long command's progress on standard error: one line rewritten in place on a terminal; in
// a log file (or a pipe) a whole line each time a unit of work is done, never a carriage
// return.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <string>

namespace handlab::cli {

class ProgressLine {
 public:
  explicit ProgressLine(bool quiet) : quiet_(quiet), terminal_(isatty(fileno(stderr)) == 1) {}
  ~ProgressLine() { finish(); }
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // Ends the line on a terminal, before the command prints its results.
  void finish() {
    if (shown_ && terminal_) std::fputc('\n', stderr);
    shown_ = false;
  }
  // `text` for the units done so far; off a terminal only when `done` has grown.
  void show(long done, const std::string& text) {
    if (quiet_ || (!terminal_ && done == done_)) return;
    done_ = done;
    shown_ = true;
    std::fprintf(stderr, terminal_ ? "\r%s " : "%s\n", text.c_str());
    std::fflush(stderr);
  }

 private:
  bool quiet_, terminal_;
  bool shown_ = false;
  long done_ = -1;
};

}  // namespace handlab::cli
