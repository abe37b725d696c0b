#include "core/util/temporary_files.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstring>
#include <mutex>
#include <stdexcept>

namespace handlab::util {
namespace {

// Fixed storage the signal handler can read without allocating: a slot is free, being
// written, or holds a path to remove.
enum SlotState : int { kFree, kWriting, kHeld };
constexpr std::size_t kSlots = 1024;  // a 250-person simulated study's parts
constexpr std::size_t kPathBytes = 4096;
std::array<std::atomic<int>, kSlots> g_state{};
std::array<std::array<char, kPathBytes>, kSlots> g_path{};

constexpr std::array<int, 4> kSignals = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};

extern "C" void remove_temporaries_and_stop(int signal_number) {
  for (std::size_t i = 0; i < kSlots; ++i)
    if (g_state[i].load() == kHeld) ::unlink(g_path[i].data());
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
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

int take_slot(const std::string& path) {
  if (path.size() >= kPathBytes) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_state[i].compare_exchange_strong(expected, kWriting)) continue;
    std::memcpy(g_path[i].data(), path.c_str(), path.size() + 1);
    g_state[i].store(kHeld);
    return int(i);
  }
  return -1;  // more at once than slots: still removed on failure, not on a signal
}

}  // namespace

TemporaryFile::TemporaryFile(std::string path) : path_(std::move(path)) {
  install_handlers_once();
  slot_ = take_slot(path_);
}

TemporaryFile::~TemporaryFile() {
  if (!kept_) ::unlink(path_.c_str());
  if (slot_ >= 0) g_state[std::size_t(slot_)].store(kFree);
}

void TemporaryFile::keep() {
  kept_ = true;
  if (slot_ >= 0) g_state[std::size_t(slot_)].store(kFree);
  slot_ = -1;
}

}  // namespace handlab::util
