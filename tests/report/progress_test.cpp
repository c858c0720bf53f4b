// Progress when stderr is not a terminal (engine/io/progress.h): a line each time the run
// passes another 10 % (never two within the minimum gap), nothing before the delay.
#include <doctest/doctest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "engine/io/progress.h"

namespace {

// runs `f` with stderr sent to a file; returns what it wrote there
template <class F>
std::string capture_stderr(F f) {
  char path[] = "/tmp/kneesim-progress-XXXXXX";
  const int fd = ::mkstemp(path);
  REQUIRE(fd >= 0);
  std::fflush(stderr);
  const int saved = ::dup(STDERR_FILENO);
  ::dup2(fd, STDERR_FILENO);
  f();
  std::fflush(stderr);
  ::dup2(saved, STDERR_FILENO);
  ::close(saved);
  ::close(fd);
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  ::unlink(path);
  return s.str();
}

int count_lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace

TEST_CASE("a log line per 10 % passed, at most one per minimum gap") {
  using namespace std::chrono_literals;
  const std::string out = capture_stderr([] {
    kneesim::io::ProgressBar bar("job", 0.0, 0.02);
    std::this_thread::sleep_for(30ms);
    bar.update(0.05);  // still in the first 10 %: no line
    bar.update(0.15);  // passed 10 %: a line
    bar.update(0.35);  // passed 30 %, but within the gap: none
    std::this_thread::sleep_for(30ms);
    bar.update(0.36);  // gap over, a new tenth since the last line: a line
    bar.update(0.37);
    bar.finish();
  });
  CHECK(count_lines(out) == 2);
  CHECK(out.find("job: 15 % done") != std::string::npos);
  CHECK(out.find("job: 36 % done") != std::string::npos);
  CHECK(out.find('\r') == std::string::npos);  // no bar drawing in a log
}

TEST_CASE("nothing before the delay") {
  const std::string out = capture_stderr([] {
    kneesim::io::ProgressBar bar("job", 60.0, 0.0);
    bar.update(0.5);
    bar.update(0.9);
  });
  CHECK(out.empty());
}
