// Files a run makes on its way to an output, removed if the run fails or is interrupted.
#pragma once

#include <signal.h>

#include <string>

namespace handlab::util {

// While registered, `path` is unlinked when the process is stopped by SIGINT, SIGTERM, SIGHUP
// or SIGPIPE (Ctrl-C, a batch system's cancel, a closed terminal or reader), before the signal
// takes its usual effect, and when the object is destroyed unless kept. Nothing can remove it
// after SIGKILL: whatever opens such a file (the names end in ".part-...", ".partial" or
// ".creating") says what it is.
class TemporaryFile {
 public:
  enum class Kind {
    kFile,
    kDatabase,  // an SQLite database: its -wal, -shm and -journal go with it
  };
  explicit TemporaryFile(std::string path, Kind kind = Kind::kFile);
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::string& path() const { return path_; }
  // The file became the output (renamed): it is no longer removed.
  void keep();

 private:
  std::string path_;
  Kind kind_;
  int slot_;
  bool kept_ = false;
};

// An SQLite database under construction.
class TemporaryDatabase : public TemporaryFile {
 public:
  explicit TemporaryDatabase(std::string path) : TemporaryFile(std::move(path), Kind::kDatabase) {}
};

// Installs the signal handlers now (they are installed with the first TemporaryFile): for a
// caller that makes a file before it can register its name, with the signals blocked between.
void prepare_temporary_files();

// Blocks the four signals for its lifetime: a file made and registered under it cannot be
// left behind by a signal arriving between the two.
class SignalsHeld {
 public:
  SignalsHeld();
  ~SignalsHeld();
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  sigset_t saved_;  // the mask before
};

}  // namespace handlab::util
