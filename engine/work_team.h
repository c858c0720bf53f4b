// A team of threads for the deformable solid's step loops (issue 30): a few fixed tasks per
// loop, each thread first takes its own and then any other not yet started, and a policy that
// never lets the helpers make a run slower than its calling thread alone.
//
// Why not OpenMP here: with its default spin-wait, a loop whose helper shares a core with
// another program collapses (bench_solid measured 0.47 M element updates/s on 2 threads against
// 16.2 M on 1 with one core busy), and OMP_WAIT_POLICY=passive pays a sleep and a wake-up at
// every one of the four or five barriers per step. The solid's step has two loops and a step of
// 0.1-0.5 ms, so what decides is how a late helper is handled, not how fast a barrier is:
//
// - Tasks are claimed, not assigned. A loop of n tasks (n = the team size for the solid: its
//   element and node ranges, solid.h) is published; each thread claims its own task first and
//   then every other one still unclaimed, with a compare-and-swap on the task's generation
//   stamp. A helper that is asleep or descheduled when the loop starts loses its task to the
//   calling thread instead of holding the loop up; only a task already claimed is waited for.
// - Which thread runs a task never changes a result: a task writes only its own outputs, and
//   the solid sums every shared quantity in a fixed order afterwards (solid_step.h).
// - Waiting: a helper spins (pause) for at most kSpinMicroseconds after a loop, then sleeps on a
//   futex (std::atomic::wait); the caller wakes it only when it is asleep. The calling thread
//   waits for claimed tasks the same way.
// - Never slower: the calling thread times its own work and its wait for claimed tasks in each
//   loop, and from its own time per task what the loop would have cost it alone. Over a window
//   of kWindow loops it compares the two: a window the team lost (a helper descheduled or
//   sharing its core ran at less than half the caller's speed often enough to outweigh the
//   loops it helped) makes the team go solo: the calling thread runs every task itself, the
//   helpers sleep. A loop whose wait is longer than the caller's own work is a stall; after
//   kStallsToGoSolo stalls the team goes solo at once if the window so far took more than
//   twice the caller alone. Stalls alone do not decide: on a virtual machine whose host
//   deschedules a helper now and then, a few loops stall while the rest of the window gains
//   (bench_solid on an idle 2-vCPU VM, 2026-11-29: the stall rule alone ran 42 % of the loops
//   solo). After `backoff` loops solo the team is tried again; the backoff doubles each time
//   the team loses again (up to kMaxBackoff) and resets after a window it won. Solo and team
//   give the same bits.
//   The team also goes solo after a window in which the caller ran every task itself in
//   kUnhelpedToGoSolo of the kWindow loops: the helpers were not scheduled in time (the other
//   cores are taken), and their wake-ups and spinning then only take time from the caller
//   (a 10 080-element gait cycle at load ~3: 44.9 s on 2 threads against 41.4 s on one).
//
// The thread count: solver.threads = 0 means automatic: the CPUs this process may run on
// (sched_getaffinity), less those other runnable processes occupy (/proc/loadavg's running
// count at start), at least 1; the policy above then follows the load as it changes.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace kneesim::engine {

// the thread count for solver.threads = `requested` (0: automatic, see above)
int resolve_thread_count(int requested);

// counts of what the team did, for the benches and the tests
struct WorkTeamStats {
  long loops = 0;         // run() calls
  long solo_loops = 0;    // of which run by the calling thread alone (policy or team of 1)
  long stalls = 0;        // team loops whose caller waited longer than it worked
  long stolen_tasks = 0;  // tasks the calling thread took from a helper's slot
  long unhelped_loops = 0;  // team loops whose every task the calling thread ran
  long solo_switches = 0; // times the policy went solo
};

class WorkTeam {
 public:
  static constexpr int kMaxTasks = 64;
  static constexpr double kSpinMicroseconds = 100.0;
  static constexpr int kWindow = 64;
  static constexpr int kStallsToGoSolo = 3;
  static constexpr int kUnhelpedToGoSolo = 48;
  static constexpr long kFirstBackoff = 256;
  static constexpr long kMaxBackoff = 1L << 16;

  explicit WorkTeam(int threads);  // threads >= 1: the caller and threads - 1 helpers
  ~WorkTeam();
  WorkTeam(const WorkTeam&) = delete;
  WorkTeam& operator=(const WorkTeam&) = delete;

  int size() const { return static_cast<int>(helpers_.size()) + 1; }
  const WorkTeamStats& stats() const { return stats_; }
  // the policy can be switched off (the tests that the team's results do not depend on it,
  // and the benches that measure a fixed mode): true runs every loop on the team
  void set_adaptive(bool adaptive) { adaptive_ = adaptive; }
  void force_solo(bool solo) { forced_solo_ = solo; }

  // runs task(i) for every i in [0, n) and returns when all have finished; n <= kMaxTasks.
  // Called by one thread (the owner) at a time; task must not call run().
  template <class Task>
  void run(int n, Task& task) {
    run_erased(n, [](void* t, int i) { (*static_cast<Task*>(t))(i); }, &task);
  }

 private:
  using Fn = void (*)(void*, int);
  void run_erased(int n, Fn fn, void* context);
  void helper_main(int index);
  bool claim(int task, uint32_t generation);
  void execute(int task);
  void run_solo(int n, Fn fn, void* context);
  void reset_window();

  std::vector<std::thread> helpers_;
  // the published loop: fn_ and context_ are written before loop_ (release) and read only
  // after a successful claim of one of its tasks, when they cannot change. loop_ holds the
  // generation (high 32 bits) and the task count as one word, so a helper never pairs one
  // loop's generation with another's count; generation_ repeats the generation as the 32-bit
  // word the helpers sleep on
  Fn fn_ = nullptr;
  void* context_ = nullptr;
  alignas(64) std::atomic<uint64_t> loop_{0};
  std::atomic<uint32_t> generation_{0};
  alignas(64) std::atomic<int> sleeping_{0};
  alignas(64) std::atomic<uint32_t> done_{0};
  alignas(64) std::atomic<int> caller_sleeping_{0};
  struct alignas(64) Slot {
    std::atomic<uint32_t> claimed{0};  // generation of the last claim
  };
  std::unique_ptr<Slot[]> slots_;
  std::atomic<bool> stop_{false};

  // the policy (owner thread only)
  bool adaptive_ = true;
  bool forced_solo_ = false;
  long solo_left_ = 0;
  long backoff_ = kFirstBackoff;
  int window_loops_ = 0;
  int window_stalls_ = 0;
  int window_unhelped_ = 0;
  double window_team_us_ = 0.0;  // the window's team loops, wall [us]
  double window_solo_us_ = 0.0;  // what they would have cost the caller alone [us]
  WorkTeamStats stats_;
};

}  // namespace kneesim::engine
