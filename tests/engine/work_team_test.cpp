// The thread team of the deformable solid's loops (engine/work_team.h). References: every task
// of every loop runs exactly once (counted), whichever thread takes it; the team and the
// caller alone give the same outputs; a helper that takes far longer than the caller's own
// work (a sleep standing for a helper descheduled mid-task) makes the policy go solo, and the
// loops still complete. No speed is measured.
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "engine/work_team.h"

using kneesim::engine::WorkTeam;

TEST_CASE("work team: every task of every loop runs exactly once") {
  for (int threads : {1, 2, 3, 5}) {
    CAPTURE(threads);
    WorkTeam team(threads);
    CHECK(team.size() == threads);
    std::vector<std::atomic<int>> runs(WorkTeam::kMaxTasks);
    for (int loop = 0; loop < 2000; ++loop) {
      const int n = 1 + loop % 7;
      auto task = [&](int i) { runs[i].fetch_add(1, std::memory_order_relaxed); };
      team.run(n, task);
      int total = 0;
      for (int i = 0; i < WorkTeam::kMaxTasks; ++i) {
        const int r = runs[i].exchange(0);
        if (i < n) CHECK(r == 1);
        total += r;
      }
      REQUIRE(total == n);
    }
    CHECK(team.stats().loops == 2000);
  }
}

TEST_CASE("work team: results do not depend on who runs a task, nor on the policy") {
  // each task writes its own slot from the previous loop's slots: a chain that any missing or
  // doubled task, or a task run before the previous loop finished, would break
  auto chain = [](WorkTeam& team) {
    std::vector<double> a(8, 1.0), b(8, 0.0);
    for (int loop = 0; loop < 500; ++loop) {
      auto task = [&](int i) {
        double s = 0.0;
        for (int k = 0; k < 8; ++k) s += a[k] * (1.0 + 0.001 * (i + k));
        b[i] = s / 8.0;
      };
      team.run(8, task);
      std::swap(a, b);
    }
    return a;
  };
  WorkTeam solo(1), team(3), forced(3);
  forced.force_solo(true);
  const std::vector<double> r1 = chain(solo), r2 = chain(team), r3 = chain(forced);
  CHECK(r1 == r2);
  CHECK(r1 == r3);
  CHECK(forced.stats().solo_loops == forced.stats().loops);
}

TEST_CASE("work team: a helper far slower than the caller makes the team go solo") {
  WorkTeam team(2);
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> helper_tasks{0};
  std::atomic<bool> started{false};
  auto task = [&](int) {
    if (std::this_thread::get_id() != caller) {
      helper_tasks.fetch_add(1);
      started.store(true);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    } else if (team.stats().solo_switches == 0) {
      // until the policy acts, the caller's own task waits for the helper to take the other
      // one, so that each loop has a slow helper task (bounded, in case the helper never runs)
      const auto t0 = std::chrono::steady_clock::now();
      while (!started.load() && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(2)) {
        std::this_thread::yield();
      }
    }
  };
  for (int loop = 0; loop < 40; ++loop) {
    started.store(false);
    team.run(2, task);
  }
  CHECK(team.stats().loops == 40);
  CHECK(helper_tasks.load() >= WorkTeam::kStallsToGoSolo);
  // the caller waited about 20 ms for each helper task against microseconds of its own work
  CHECK(team.stats().solo_switches >= 1);
  CHECK(team.stats().solo_loops > 0);
  MESSAGE("helper tasks ", helper_tasks.load(), ", stalls ", team.stats().stalls, ", solo loops ",
          team.stats().solo_loops);
}
