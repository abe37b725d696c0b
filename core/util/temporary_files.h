// Files a run makes on its way to an output, removed if the run is interrupted.
#pragma once

#include <string>

namespace handlab::util {

// While registered, `path` is unlinked when the process is stopped by SIGINT, SIGTERM, SIGHUP
// or SIGPIPE (Ctrl-C, a batch system's cancel, a closed terminal or reader), before the signal
// takes its usual effect. Nothing can remove it after SIGKILL: whatever opens such a file
// (the names end in ".part-XXXXXX", ".partial" or ".creating") says what it is.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::string path);
  ~TemporaryFile();  // removes the file unless it was kept
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;

  const std::string& path() const { return path_; }
  // The file became the output (renamed): it is no longer removed.
  void keep();

 private:
  std::string path_;
  int slot_;
  bool kept_ = false;
};

// An SQLite database under construction: the file and the companions SQLite makes beside it
// (-wal, -shm, -journal), removed together.
class TemporaryDatabase {
 public:
  explicit TemporaryDatabase(const std::string& path)
      : file_(path), wal_(path + "-wal"), shm_(path + "-shm"), journal_(path + "-journal") {}
  // The database became the output: none of its files is removed.
  void keep() {
    for (TemporaryFile* f : {&file_, &wal_, &shm_, &journal_}) f->keep();
  }

 private:
  TemporaryFile file_, wal_, shm_, journal_;
};

}  // namespace handlab::util
