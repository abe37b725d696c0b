#include "core/util/temporary_files.h"

#include <pthread.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>

namespace handlab::util {
namespace {

// Fixed storage the signal handler can read without allocating: a slot is free, being
// written, or holds a path (and whether SQLite's companions go with it).
enum SlotState : int { kFree, kWriting, kHeldFile, kHeldDatabase };
constexpr std::size_t kSlots = 1024;
constexpr std::size_t kPathBytes = 4096;
std::array<std::atomic<int>, kSlots> g_state{};
std::array<std::array<char, kPathBytes>, kSlots> g_path{};

constexpr std::array<int, 4> kSignals = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};
constexpr std::array<const char*, 3> kCompanions = {"-wal", "-shm", "-journal"};

// Async-signal-safe: no allocation, only unlink and byte copies.
void unlink_with_companions(const char* path, bool database) {
  ::unlink(path);
  if (!database) return;
  char name[kPathBytes + 16];
  std::size_t n = 0;
  while (path[n] != '\0') ++n;
  for (const char* suffix : kCompanions) {
    std::memcpy(name, path, n);
    std::size_t k = 0;
    for (; suffix[k] != '\0'; ++k) name[n + k] = suffix[k];
    name[n + k] = '\0';
    ::unlink(name);
  }
}

extern "C" void remove_temporaries_and_stop(int signal_number) {
  for (std::size_t i = 0; i < kSlots; ++i) {
    const int state = g_state[i].load();
    if (state == kHeldFile || state == kHeldDatabase)
      unlink_with_companions(g_path[i].data(), state == kHeldDatabase);
  }
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

sigset_t handled_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (int s : kSignals) sigaddset(&set, s);
  return set;
}

// Only where the signal would stop the process anyway: a program (or nohup) that chose its own
// handling keeps it.
void install_handlers_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int s : kSignals) {
      struct sigaction current {};
      if (sigaction(s, nullptr, &current) != 0 || current.sa_handler != SIG_DFL) continue;
      struct sigaction handler {};
      handler.sa_handler = remove_temporaries_and_stop;
      sigemptyset(&handler.sa_mask);
      sigaction(s, &handler, nullptr);
    }
  });
}

int take_slot(const std::string& path, bool database) {
  if (path.size() >= kPathBytes) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_state[i].compare_exchange_strong(expected, kWriting)) continue;
    std::memcpy(g_path[i].data(), path.c_str(), path.size() + 1);
    g_state[i].store(database ? kHeldDatabase : kHeldFile);
    return int(i);
  }
  return -1;  // more at once than slots: still removed on failure, not on a signal
}

}  // namespace

TemporaryFile::TemporaryFile(std::string path, Kind kind) : path_(std::move(path)), kind_(kind) {
  install_handlers_once();
  slot_ = take_slot(path_, kind_ == Kind::kDatabase);
}

TemporaryFile::~TemporaryFile() {
  if (!kept_) unlink_with_companions(path_.c_str(), kind_ == Kind::kDatabase);
  if (slot_ >= 0) g_state[std::size_t(slot_)].store(kFree);
}

void TemporaryFile::keep() {
  kept_ = true;
  if (slot_ >= 0) g_state[std::size_t(slot_)].store(kFree);
  slot_ = -1;
}

void prepare_temporary_files() {
  install_handlers_once();
}

SignalsHeld::SignalsHeld() {
  const sigset_t block = handled_signals();
  pthread_sigmask(SIG_BLOCK, &block, &saved_);
}

SignalsHeld::~SignalsHeld() {
  pthread_sigmask(SIG_SETMASK, &saved_, nullptr);
}

}  // namespace handlab::util
