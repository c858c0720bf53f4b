// Output folders never mix or fake a result (engine/io/output_folder.h, engine/io/interrupt.h):
// a second kneesim process writing into a folder in use is refused naming the first; a stale
// lock of a dead process is taken over; a folder holding another command's results is refused;
// SIGINT (to the whole process group, as a terminal sends it) and SIGTERM stop a wear run with
// exit 130 / 143, its table renamed wear.partial.csv, no summary.json, no temporary file, no
// lock and no Python traceback; a later run removes temporary files a killed run left; a full
// disk (a small tmpfs, when this process may mount one) ends with exit 1 and only partial
// names, for `wear`, `run` (also when only its PNG plots no longer fit) and `study`; SIGTERM
// stops `compare` and `study` the same way; compare
// refuses a material listed twice and study a negative thread count; a command refused after
// its folder check removes the folder it created.
#include <doctest/doctest.h>

#include <sys/mount.h>
#include <sys/statvfs.h>
#include <sys/wait.h>

#include <chrono>
#include <cstring>
#include <csignal>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "tests/cli_wear/cli_helpers.h"

namespace fs = std::filesystem;
using namespace kneesim::test;

namespace {

// a wear run long enough to be interrupted (minutes): 3 mm elements, one cycle per update
std::vector<std::string> long_wear(const fs::path& out) {
  return {"wear", "--cycles", "5000", "--update-every", "1", "--set",
          "implant.edge_length_mm=3", "--out", out.string(), "--no-report", "--no-depth-maps"};
}

// kneesim in a process group of its own (as a shell job), so a signal can go to the group
pid_t start_group(const std::vector<std::string>& args, const fs::path& dir, const std::string& tag) {
  return start_kneesim(args, dir, tag, /*own_group=*/true);
}

bool wait_for(const fs::path& p, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (fs::exists(p)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

int exit_status(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  return out;
}

bool any_temporary(const fs::path& dir) {
  for (const auto& n : names_in(dir)) {
    if (n.find(".tmp") != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("a folder in use is refused naming the process; signals stop a run cleanly") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  for (const int sig : {SIGTERM, SIGINT}) {
    CAPTURE(sig);
    const fs::path out = tmp.path / ("w" + std::to_string(sig));
    const std::string tag = "sig" + std::to_string(sig);
    const pid_t pid = start_group(long_wear(out), tmp.path, tag);
    REQUIRE(wait_for(out / "wear.csv", 120.0));  // the first update is written

    // a second process into the same folder: refused, naming the first
    const Result second = run_kneesim({"run", "--cycles", "1", "--set", "implant.edge_length_mm=3",
                                       "--out", out.string(), "--quiet"},
                                      tmp.path, "second");
    CHECK(second.exit_code == 2);
    CHECK(second.err.find("is in use by another kneesim process (pid " + std::to_string(pid) +
                          ": kneesim wear") != std::string::npos);

    ::kill(sig == SIGINT ? -pid : pid, sig);  // SIGINT to the group, as a terminal sends it
    const int code = exit_status(pid);
    CHECK(code == 128 + sig);
    const std::string err = slurp(tmp.path / (tag + ".stderr"));
    INFO(err);
    CHECK(err.find("Traceback") == std::string::npos);
    CHECK(err.find("KeyboardInterrupt") == std::string::npos);
    CHECK(fs::exists(out / "wear.partial.csv"));
    CHECK(!fs::exists(out / "wear.csv"));
    CHECK(!fs::exists(out / "summary.json"));
    CHECK(!fs::exists(out / ".kneesim.lock"));
    CHECK(!any_temporary(out));
    // a resumed run continues in the same folder (same command) and completes
    spit(out / "wear.csv.tmp.999999", "left by a killed run\n");
    std::vector<std::string> resume = long_wear(out);
    resume[2] = "3";  // fewer cycles: a new, short run of the same command
    const Result again = run_kneesim(resume, tmp.path, "again");
    INFO(again.err);
    CHECK(again.exit_code == 0);
    CHECK(fs::exists(out / "summary.json"));
    CHECK(!fs::exists(out / "wear.partial.csv"));
    CHECK(!fs::exists(out / "wear.csv.tmp.999999"));
    CHECK(!fs::exists(out / ".kneesim.lock"));
  }
}

TEST_CASE("a stale lock is taken over; another command's results are not mixed in") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "o";
  fs::create_directories(out);
  spit(out / ".kneesim.lock", "pid 999999: kneesim run, since 2026-01-01 00:00:00\n");
  const std::vector<std::string> run = {"run", "--cycles", "1", "--set", "implant.edge_length_mm=3",
                                        "--out", out.string(), "--quiet", "--no-plots",
                                        "--no-report"};
  const Result r = run_kneesim(run, tmp.path, "stale");
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.empty());
  CHECK(fs::exists(out / "summary.json"));
  CHECK(!fs::exists(out / ".kneesim.lock"));

  // wear into the folder of a run: refused, nothing of the run's removed
  const Result w = run_kneesim({"wear", "--cycles", "2", "--update-every", "1", "--set",
                                "implant.edge_length_mm=3", "--out", out.string(), "--quiet"},
                               tmp.path, "other");
  CHECK(w.exit_code == 2);
  CHECK(w.err.find("holds the results of 'kneesim run'") != std::string::npos);
  CHECK(fs::exists(out / "summary.json"));
  CHECK(!fs::exists(out / "wear.csv"));
  // the same command again is fine
  CHECK(run_kneesim(run, tmp.path, "same").exit_code == 0);
}

TEST_CASE("a command refused after its folder check leaves no folder it created") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  // the measured file is read after the output folder is claimed: the refusal removes the
  // folder the command created, and keeps a folder that was there before
  const fs::path created = tmp.path / "new";
  const Result r = run_kneesim({"diagnose", "bor", "--measured", (tmp.path / "none.csv").string(),
                                "--out", created.string()}, tmp.path, "refused");
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("none.csv") != std::string::npos);
  CHECK(!fs::exists(created));
  const fs::path existing = tmp.path / "old";
  fs::create_directories(existing);
  CHECK(run_kneesim({"diagnose", "bor", "--measured", (tmp.path / "none.csv").string(), "--out",
                     existing.string()}, tmp.path, "refused2").exit_code == 2);
  CHECK(fs::is_directory(existing));
}

TEST_CASE("compare refuses a material listed twice; study a negative thread count") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const Result c = run_kneesim({"compare", "--materials", "uhmwpe,uhmwpe", "--out",
                                (tmp.path / "c").string()}, tmp.path, "c");
  CHECK(c.exit_code == 2);
  CHECK(c.err.find("--materials lists 'uhmwpe' twice") != std::string::npos);
  CHECK(!fs::exists(tmp.path / "c"));
  const Result s = run_kneesim({"study", "--threads", "-1", "--out", (tmp.path / "s").string()},
                               tmp.path, "s");
  CHECK(s.exit_code == 2);
  CHECK(s.err.find("--threads") != std::string::npos);
}

TEST_CASE("a full disk ends a wear run with exit 1 and only partial names") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path disk = tmp.path / "disk";
  fs::create_directories(disk);
  // 300 kB: the checkpoint (about 120 kB, twice while it is replaced) and the first updates'
  // rows fit, the later ones do not
  if (::mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=300k") != 0) {
    MESSAGE("skipped: cannot mount a small tmpfs here (needs root): " << std::strerror(errno));
    return;
  }
  struct Unmount {
    fs::path p;
    ~Unmount() { ::umount2(p.c_str(), MNT_DETACH); }
  } unmount{disk};
  const fs::path out = disk / "w";
  const Result r = run_kneesim({"wear", "--cycles", "400", "--update-every", "1", "--set",
                                "implant.edge_length_mm=3", "--out", out.string(), "--quiet",
                                "--no-depth-maps"},
                               tmp.path, "full");
  INFO(r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("No space left on device") != std::string::npos);
  CHECK(count_lines(r.err) == 1);
  CHECK(!fs::exists(out / "summary.json"));
  CHECK(!fs::exists(out / "wear.csv"));
  CHECK(fs::exists(out / "wear.partial.csv"));
  CHECK(!any_temporary(out));
  CHECK(!fs::exists(out / ".kneesim.lock"));
}

namespace {

// a tmpfs of `size` at `dir` (unmounted by the destructor); false when this process may not
// mount one (needs root)
struct SmallDisk {
  fs::path dir;
  bool mounted = false;
  SmallDisk(const fs::path& d, const std::string& size) : dir(d) {
    fs::create_directories(dir);
    mounted = ::mount("tmpfs", dir.c_str(), "tmpfs", 0, ("size=" + size).c_str()) == 0;
    if (!mounted) MESSAGE("skipped: cannot mount a small tmpfs here (needs root): " << std::strerror(errno));
  }
  ~SmallDisk() {
    if (mounted) ::umount2(dir.c_str(), MNT_DETACH);
  }
  double used_bytes() const {
    struct statvfs v {};
    ::statvfs(dir.c_str(), &v);
    return static_cast<double>(v.f_blocks - v.f_bfree) * static_cast<double>(v.f_frsize);
  }
};

// a command that failed for a full disk: exit 1, one sentence naming the cause, no summary,
// no traceback, nothing under a final result name (only X.partial.Y, the journal that
// --resume reads, and the folder's dot files)
void ended_full(const Result& r, const fs::path& out) {
  INFO(r.err);
  CHECK(r.exit_code == 1);
  CHECK(r.err.find("No space left on device") != std::string::npos);
  CHECK(count_lines(r.err) == 1);
  CHECK(r.err.find("Traceback") == std::string::npos);
  CHECK(!fs::exists(out / "summary.json"));
  CHECK(!fs::exists(out / ".kneesim.lock"));
  for (const auto& n : names_in(out)) {
    CAPTURE(n);
    CHECK((n[0] == '.' || n.find(".partial.") != std::string::npos ||
           n.rfind("trials.journal.", 0) == 0));
  }
}

}  // namespace

TEST_CASE("a full disk ends run and study with exit 1 and only partial names") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  {
    // the run's tables and maps take most of 600 kB: a map does not fit
    SmallDisk disk(tmp.path / "d1", "600k");
    if (!disk.mounted) return;
    const fs::path out = disk.dir / "r";
    ended_full(run_kneesim({"run", "--quiet", "--no-report", "--no-plots", "--out", out.string()},
                           tmp.path, "run_maps"),
               out);
  }
  double tables = 0.0;
  {
    // how much the run writes without its PNG plots
    SmallDisk disk(tmp.path / "d2", "16m");
    const fs::path out = disk.dir / "r";
    REQUIRE(run_kneesim({"run", "--quiet", "--no-report", "--no-plots", "--out", out.string()},
                        tmp.path, "run_size").exit_code == 0);
    tables = disk.used_bytes();
  }
  {
    // every table and map fits, the PNG plots (about 90 kB each) do not
    char size[32];
    std::snprintf(size, sizeof size, "%.0fk", tables / 1024.0 + 24.0);
    SmallDisk disk(tmp.path / "d3", size);
    const fs::path out = disk.dir / "r";
    const Result r = run_kneesim({"run", "--quiet", "--no-report", "--out", out.string()},
                                 tmp.path, "run_plots");
    ended_full(r, out);
    CHECK(r.err.find("cannot write the PNG plots of") != std::string::npos);
    CHECK(fs::exists(out / "kinematics.partial.csv"));
  }
  {
    // 20 trials' journal and tables fit in 150 kB, their PNG plots do not
    SmallDisk disk(tmp.path / "d4", "150k");
    const fs::path out = disk.dir / "s";
    ended_full(run_kneesim({"study", "--trials", "20", "--quiet", "--out", out.string()},
                           tmp.path, "study"),
               out);
  }
}

TEST_CASE("SIGTERM and SIGINT stop a study with only its journal and partial names") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  for (const int sig : {SIGTERM, SIGINT}) {
    CAPTURE(sig);
    const fs::path out = tmp.path / ("s" + std::to_string(sig));
    const std::string tag = "study" + std::to_string(sig);
    // minutes of trials: the signal comes while they run
    const pid_t pid = start_group({"study", "--trials", "5000", "--quiet", "--threads", "1",
                                   "--out", out.string()},
                                  tmp.path, tag);
    REQUIRE(wait_for(out / "trials.journal.0", 120.0));
    ::kill(sig == SIGINT ? -pid : pid, sig);
    CHECK(exit_status(pid) == 128 + sig);
    const std::string err = slurp(tmp.path / (tag + ".stderr"));
    INFO(err);
    CHECK(err.find("Traceback") == std::string::npos);
    CHECK(!fs::exists(out / "summary.json"));
    CHECK(!fs::exists(out / ".kneesim.lock"));
    CHECK(!any_temporary(out));
    for (const auto& n : names_in(out)) {
      CAPTURE(n);
      CHECK((n[0] == '.' || n.find(".partial.") != std::string::npos ||
             n.rfind("trials.journal.", 0) == 0));
    }
  }
}

TEST_CASE("SIGTERM stops a compare with every material's table renamed partial") {
  REQUIRE(!find_kneesim().empty());
  TempDir tmp;
  const fs::path out = tmp.path / "c";
  const pid_t pid = start_group({"compare", "--materials", "uhmwpe,peek", "--cycles", "5000",
                                 "--update-every", "1", "--jobs", "2", "--set",
                                 "implant.edge_length_mm=3", "--no-break-even", "--no-report",
                                 "--quiet", "--out", out.string()},
                                tmp.path, "cmp");
  REQUIRE(wait_for(out / "uhmwpe" / "wear.csv", 120.0));
  REQUIRE(wait_for(out / "peek" / "wear.csv", 120.0));
  ::kill(pid, SIGTERM);
  CHECK(exit_status(pid) == 143);
  const std::string err = slurp(tmp.path / "cmp.stderr");
  INFO(err);
  CHECK(err.find("Traceback") == std::string::npos);
  CHECK(!fs::exists(out / ".kneesim.lock"));
  for (const char* m : {"uhmwpe", "peek"}) {
    CAPTURE(m);
    CHECK(fs::exists(out / m / "wear.partial.csv"));
    CHECK(!fs::exists(out / m / "wear.csv"));
    CHECK(!fs::exists(out / m / "summary.json"));
    CHECK(!any_temporary(out / m));
  }
  CHECK(!fs::exists(out / "comparison.csv"));
  CHECK(!fs::exists(out / "comparison.json"));
}
