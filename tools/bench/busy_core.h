// A core kept busy for the benches' "one core busy" figures (issue 30): a child process that
// spins until killed, as a second program on a shared workstation or another MPI rank would.
#pragma once

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace kneesim::bench {

// starts the spinning child and gives the scheduler 0.2 s to place it; exits the program with
// a message naming `who` if it cannot fork
inline pid_t start_busy_core(const char* who) {
  const pid_t pid = fork();
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);  // never outlives the bench
    if (getppid() == 1) _exit(0);
    volatile unsigned long x = 0;
    for (;;) x = x + 1;
  }
  if (pid < 0) {
    std::fprintf(stderr, "%s: cannot start the spinning child process (fork failed)\n", who);
    std::exit(1);
  }
  usleep(200000);
  return pid;
}

inline void stop_busy_core(pid_t pid) {
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
}

}  // namespace kneesim::bench
