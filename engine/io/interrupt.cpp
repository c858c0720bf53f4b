#include "engine/io/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>

namespace kneesim::io {
namespace {

constexpr int kSlots = 256;
constexpr int kPathMax = 1024;

// one registry entry: `used` is set after the paths are written and cleared before reuse
struct Slot {
  std::atomic<int> used{0};  // 0 free, 1 claimed (being written), 2 published
  char a[kPathMax];
  char b[kPathMax];
  pid_t pid = -1;
};

enum Kind { kPartial, kTemp, kChild, kLock, kKinds };
Slot g_slots[kKinds][kSlots];
std::atomic<bool> g_warned{false};

int claim(Kind kind, const std::filesystem::path& a, const std::filesystem::path& b, pid_t pid) {
  const std::string sa = a.string(), sb = b.string();
  if (sa.size() >= kPathMax || sb.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    Slot& s = g_slots[kind][i];
    if (!s.used.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(s.a, sa.c_str(), sa.size() + 1);
    std::memcpy(s.b, sb.c_str(), sb.size() + 1);
    s.pid = pid;
    s.used.store(2, std::memory_order_release);
    return i;
  }
  if (!g_warned.exchange(true)) {
    std::fprintf(stderr, "warning: more than %d files in progress; an interrupted run may leave "
                 "some under their final names\n", kSlots);
  }
  return -1;
}

void release(Kind kind, int id) {
  if (id >= 0 && id < kSlots) g_slots[kind][id].used.store(0, std::memory_order_release);
}

// async-signal-safe: reads published slots, calls kill, rename and unlink only
void clean_up() {
  for (Slot& s : g_slots[kChild]) {
    if (s.used.load(std::memory_order_acquire) == 2 && s.pid > 0) ::kill(s.pid, SIGTERM);
  }
  for (Slot& s : g_slots[kTemp]) {
    if (s.used.load(std::memory_order_acquire) == 2) ::unlink(s.a);
  }
  for (Slot& s : g_slots[kPartial]) {
    int expected = 2;  // each rename once, even if a signal comes during an error exit
    if (s.used.compare_exchange_strong(expected, 3)) ::rename(s.a, s.b);
  }
  for (Slot& s : g_slots[kLock]) {
    int expected = 2;
    if (s.used.compare_exchange_strong(expected, 3)) ::unlink(s.a);
  }
}

void write_all(const char* text) {
  size_t n = std::strlen(text);
  while (n > 0) {
    const ssize_t w = ::write(2, text, n);
    if (w <= 0) return;
    text += w;
    n -= static_cast<size_t>(w);
  }
}

pid_t g_main_pid = 0;

extern "C" void on_signal(int sig) {
  // a child between fork and exec (engine/io/plot.cpp blocks the signals there; this is the
  // second guard) must not clean up its parent's files
  if (::getpid() != g_main_pid) ::_exit(128 + sig);
  clean_up();
  write_all(sig == SIGINT ? "\nkneesim: interrupted (SIGINT); tables in progress are kept as "
                            "*.partial.*, no summary.json was written\n"
                          : "kneesim: terminated (SIGTERM); tables in progress are kept as "
                            "*.partial.*, no summary.json was written\n");
  ::_exit(128 + sig);
}

}  // namespace

void install_interrupt_handlers() {
  g_main_pid = ::getpid();
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sigaddset(&sa.sa_mask, SIGINT);
  sigaddset(&sa.sa_mask, SIGTERM);
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
}

void abandon_outputs() { clean_up(); }

int register_partial(const std::filesystem::path& final, const std::filesystem::path& partial) {
  return claim(kPartial, final, partial, -1);
}
void unregister_partial(int id) { release(kPartial, id); }

void PartialOutputs::add(const std::filesystem::path& final, const std::filesystem::path& partial) {
  entries_.push_back({register_partial(final, partial), final, partial});
}

void PartialOutputs::commit() {
  for (const Entry& e : entries_) unregister_partial(e.slot);
  entries_.clear();
}

PartialOutputs::~PartialOutputs() {
  for (const Entry& e : entries_) {
    unregister_partial(e.slot);
    std::error_code ec;
    if (std::filesystem::exists(e.final, ec)) std::filesystem::rename(e.final, e.partial, ec);
  }
}

int register_temp(const std::filesystem::path& file) { return claim(kTemp, file, {}, -1); }
void unregister_temp(int id) { release(kTemp, id); }

int register_child(pid_t pid) { return claim(kChild, {}, {}, pid); }
void unregister_child(int id) { release(kChild, id); }

int register_lock(const std::filesystem::path& file) { return claim(kLock, file, {}, -1); }
void unregister_lock(int id) { release(kLock, id); }

}  // namespace kneesim::io
