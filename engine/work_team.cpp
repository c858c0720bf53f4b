#include "engine/work_team.h"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

namespace kneesim::engine {
namespace {

using Clock = std::chrono::steady_clock;

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

double microseconds(Clock::duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

// spins until ready() or kSpinMicroseconds have passed; true if ready
template <class Ready>
bool spin_until(Ready ready) {
  const Clock::time_point t0 = Clock::now();
  for (;;) {
    for (int i = 0; i < 32; ++i) {
      if (ready()) return true;
      cpu_relax();
    }
    if (microseconds(Clock::now() - t0) > WorkTeam::kSpinMicroseconds) return ready();
  }
}

// generation a precedes b (wrap-around safe)
bool before(uint32_t a, uint32_t b) { return static_cast<int32_t>(a - b) < 0; }

}  // namespace

int resolve_thread_count(int requested) {
  if (requested > 0) return requested;
  cpu_set_t set;
  CPU_ZERO(&set);
  int cpus = 1;
  if (sched_getaffinity(0, sizeof set, &set) == 0) cpus = std::max(1, CPU_COUNT(&set));
  // /proc/loadavg's fourth field is "runnable/total" scheduling entities, this thread included
  std::ifstream f("/proc/loadavg");
  std::string a, b, c, running;
  int others = 0;
  if (f >> a >> b >> c >> running) {
    others = std::max(0, std::atoi(running.c_str()) - 1);
  }
  return std::clamp(cpus - others, 1, cpus);
}

WorkTeam::WorkTeam(int threads) : slots_(new Slot[kMaxTasks]) {
  const int helpers = std::max(1, threads) - 1;
  helpers_.reserve(helpers);
  for (int h = 0; h < helpers; ++h) helpers_.emplace_back([this, h] { helper_main(h + 1); });
}

WorkTeam::~WorkTeam() {
  stop_.store(true, std::memory_order_seq_cst);
  generation_.fetch_add(1, std::memory_order_seq_cst);
  generation_.notify_all();
  for (std::thread& t : helpers_) t.join();
}

bool WorkTeam::claim(int task, uint32_t generation) {
  std::atomic<uint32_t>& c = slots_[task].claimed;
  uint32_t seen = c.load(std::memory_order_relaxed);
  while (before(seen, generation)) {
    if (c.compare_exchange_weak(seen, generation, std::memory_order_acq_rel)) return true;
  }
  return false;
}

void WorkTeam::execute(int task) {
  fn_(context_, task);
  const uint32_t n = static_cast<uint32_t>(loop_.load(std::memory_order_relaxed));
  if (done_.fetch_add(1, std::memory_order_seq_cst) + 1 == n &&
      caller_sleeping_.load(std::memory_order_seq_cst)) {
    done_.notify_one();
  }
}

void WorkTeam::helper_main(int index) {
  uint32_t seen = 0;
  for (;;) {
    uint32_t g = generation_.load(std::memory_order_acquire);
    if (g == seen && !stop_.load(std::memory_order_relaxed)) {
      spin_until([&] {
        g = generation_.load(std::memory_order_acquire);
        return g != seen || stop_.load(std::memory_order_relaxed);
      });
    }
    if (g == seen && !stop_.load(std::memory_order_relaxed)) {
      sleeping_.fetch_add(1, std::memory_order_seq_cst);
      while ((g = generation_.load(std::memory_order_seq_cst)) == seen &&
             !stop_.load(std::memory_order_seq_cst)) {
        generation_.wait(seen, std::memory_order_seq_cst);
      }
      sleeping_.fetch_sub(1, std::memory_order_seq_cst);
    }
    if (stop_.load(std::memory_order_acquire)) return;
    // the loop as one word: its generation may already be later than g (then so is its count)
    const uint64_t loop = loop_.load(std::memory_order_acquire);
    g = static_cast<uint32_t>(loop >> 32);
    seen = g;
    const int n = static_cast<int>(static_cast<uint32_t>(loop));
    // its own task first, then the others in order
    if (index < n && claim(index, g)) execute(index);
    for (int k = 0; k < n; ++k) {
      if (k != index && claim(k, g)) execute(k);
    }
  }
}

void WorkTeam::run_solo(int n, Fn fn, void* context) {
  ++stats_.solo_loops;
  for (int i = 0; i < n; ++i) fn(context, i);
}

void WorkTeam::run_erased(int n, Fn fn, void* context) {
  ++stats_.loops;
  if (n <= 0) return;
  if (n > kMaxTasks) {
    std::fprintf(stderr, "WorkTeam: %d tasks exceed the limit of %d\n", n, kMaxTasks);
    std::abort();
  }
  if (helpers_.empty() || n == 1 || forced_solo_) return run_solo(n, fn, context);
  if (adaptive_ && solo_left_ > 0) {
    --solo_left_;
    return run_solo(n, fn, context);
  }
  // publish the loop: its description, then the generation the helpers wait on
  fn_ = fn;
  context_ = context;
  done_.store(0, std::memory_order_relaxed);
  const uint32_t g = generation_.load(std::memory_order_relaxed) + 1;
  // a slot left unclaimed for 2^31 loops (a task index beyond the loops' counts meanwhile)
  // would look claimed after the 32-bit wrap: bring its stamp to the previous loop. No helper
  // can claim here (every earlier loop is finished; a late helper's generation is <= g - 1)
  for (int k = 0; k < n; ++k) {
    std::atomic<uint32_t>& c = slots_[k].claimed;
    if (g - c.load(std::memory_order_relaxed) > (1u << 30)) c.store(g - 1, std::memory_order_relaxed);
  }
  loop_.store((static_cast<uint64_t>(g) << 32) | static_cast<uint32_t>(n), std::memory_order_release);
  generation_.store(g, std::memory_order_seq_cst);
  if (sleeping_.load(std::memory_order_seq_cst) > 0) generation_.notify_all();
  const Clock::time_point t0 = Clock::now();
  // the caller's own task (0) first, then any other still unclaimed
  int mine = 0;
  for (int k = 0; k < n; ++k) {
    if (!claim(k, g)) continue;
    if (k != 0) ++stats_.stolen_tasks;
    ++mine;
    execute(k);
  }
  const Clock::time_point t1 = Clock::now();
  const uint32_t un = static_cast<uint32_t>(n);
  if (done_.load(std::memory_order_acquire) != un &&
      !spin_until([&] { return done_.load(std::memory_order_acquire) == un; })) {
    caller_sleeping_.store(1, std::memory_order_seq_cst);
    uint32_t d;
    while ((d = done_.load(std::memory_order_seq_cst)) != un) done_.wait(d, std::memory_order_seq_cst);
    caller_sleeping_.store(0, std::memory_order_relaxed);
  }
  const Clock::time_point t2 = Clock::now();
  if (!adaptive_) return;
  // the policy: a wait longer than the caller's own work is a stall; a loop whose every task
  // the caller ran itself is one the helpers did not help (they were not scheduled in time).
  // What the loop would have cost the caller alone: its own tasks' time per task, times n
  const double own = microseconds(t1 - t0), wait = microseconds(t2 - t1);
  ++window_loops_;
  if (mine > 0) {  // (a helper can take every task, the caller's own too, if it was late)
    window_team_us_ += own + wait;
    window_solo_us_ += own / mine * n;
  }
  if (wait > own && wait > 5.0) {
    ++window_stalls_;
    ++stats_.stalls;
  }
  if (mine == n) {
    ++window_unhelped_;
    ++stats_.unhelped_loops;
  }
  const bool window_done = window_loops_ >= kWindow;
  // go solo on a net loss, not on stalls alone: a host that deschedules a helper now and then
  // (a virtual machine's neighbours) costs a few loops while the rest of the window gains;
  // decided at the window's end, or at once when the stalls have made the window so far take
  // more than twice the caller alone
  const bool net_loss = window_team_us_ > window_solo_us_;
  const bool gross_loss = window_team_us_ > 2.0 * window_solo_us_;
  if ((window_stalls_ >= kStallsToGoSolo && gross_loss) ||
      (window_done && (net_loss || window_unhelped_ >= kUnhelpedToGoSolo))) {
    solo_left_ = backoff_;
    backoff_ = std::min(2 * backoff_, kMaxBackoff);
    ++stats_.solo_switches;
    reset_window();
  } else if (window_done) {
    backoff_ = kFirstBackoff;  // a window the team won
    reset_window();
  }
}

void WorkTeam::reset_window() {
  window_loops_ = window_stalls_ = window_unhelped_ = 0;
  window_team_us_ = window_solo_us_ = 0.0;
}

}  // namespace kneesim::engine
