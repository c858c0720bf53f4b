// The plot session (engine/io/plot.h): one interpreter runs the queued scripts in order, each
// as `python3 script args` would (its own sys.argv, matplotlib settings as a fresh interpreter
// has them), a failing script does not stop the next, and the session's end waits for all.
// Reference: what the same scripts do, run one interpreter each (run_plot without a session).
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/io/source_tree.h"
#include "engine/io/plot.h"

namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

}  // namespace

TEST_CASE("a plot session runs its scripts in order, each as a fresh interpreter would") {
  if (!fs::exists("/usr/bin/python3")) return;  // plots are optional: nothing to test
  const fs::path dir = fs::temp_directory_path() / "kneesim_plot_session_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file((kneesim::io::source_dir() / "tools/plots") / "plot_server.py", dir / "plot_server.py");
  fs::copy_file((kneesim::io::source_dir() / "tools/plots") / "plotio.py", dir / "plotio.py");
  // writes its arguments, whether the previous script's file exists, and a matplotlib setting
  // that the previous script changed
  write(dir / "ok.py",
        "import os, sys\n"
        "import matplotlib\n"
        "out, before = sys.argv[1], sys.argv[2]\n"
        "with open(out + '.tmp', 'w') as f:\n"
        "    f.write(' '.join(sys.argv[1:]) + ' ' + str(os.path.exists(before)) + ' ' +\n"
        "            str(matplotlib.rcParams['lines.linewidth']))\n"
        "os.replace(out + '.tmp', out)\n"
        "matplotlib.rcParams['lines.linewidth'] = 7.0\n");
  write(dir / "fail.py", "import sys\nsys.exit(2)\n");
  // a script that found the disk full (tools/plots/plotio.py DISK_FULL)
  write(dir / "full.py", "import sys\nsys.exit(" + std::to_string(kneesim::io::kPlotDiskFull) + ")\n");
  const char* old = std::getenv("KNEESIM_PLOTS_DIR");
  const std::string saved = old ? old : "";
  setenv("KNEESIM_PLOTS_DIR", dir.c_str(), 1);
  const fs::path a = dir / "a.txt", b = dir / "b.txt", c = dir / "c.txt";
  {
    const kneesim::io::PlotSession session;
    CHECK(kneesim::io::run_plot("ok.py", {a.string(), (dir / "none").string()}));
    CHECK(kneesim::io::run_plot("fail.py", {}));  // queued: its failure is a warning at the end
    CHECK(kneesim::io::run_plot("ok.py", {b.string(), a.string()}));
  }
  // without a session: the caller waits, and a failure is the return value
  CHECK(kneesim::io::run_plot("ok.py", {c.string(), b.string()}));
  CHECK_FALSE(kneesim::io::run_plot("fail.py", {}));
  // a full disk: a warning and false, or an error where the command asks for one
  CHECK_FALSE(kneesim::io::run_plot("full.py", {}));
  CHECK_THROWS_WITH_AS(kneesim::io::run_plot("full.py", {}, /*disk_full_is_error=*/true),
                       doctest::Contains("No space left on device"), std::runtime_error);
  {
    // in a session: wait_for_plots reports the plots queued so far; the session stays usable
    const kneesim::io::PlotSession session;
    CHECK(kneesim::io::run_plot("full.py", {}));
    CHECK_THROWS_WITH_AS(kneesim::io::wait_for_plots(/*disk_full_is_error=*/true),
                         doctest::Contains("cannot write the PNG plots of full.py"),
                         std::runtime_error);
    CHECK_NOTHROW(kneesim::io::wait_for_plots(true));  // nothing queued any more
    CHECK(kneesim::io::run_plot("fail.py", {}));
    CHECK_NOTHROW(kneesim::io::wait_for_plots(true));  // another failure: a warning
  }
  if (old) setenv("KNEESIM_PLOTS_DIR", saved.c_str(), 1); else unsetenv("KNEESIM_PLOTS_DIR");
  const std::string fresh = slurp(c);  // a fresh interpreter's default linewidth
  CHECK(fresh == c.string() + " " + b.string() + " True 1.5");
  CHECK(slurp(a) == a.string() + " " + (dir / "none").string() + " False 1.5");
  // b ran after a (and after the failure) and saw the default setting, not a's 7.0
  CHECK(slurp(b) == b.string() + " " + a.string() + " True 1.5");
  fs::remove_all(dir);
}
