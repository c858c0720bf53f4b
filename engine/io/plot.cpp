#include "engine/io/plot.h"

#include <pthread.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "engine/io/interrupt.h"
#include "engine/io/source_tree.h"

namespace kneesim::io {
namespace {

const char* const kPython = "/usr/bin/python3";

void warn_failed(const std::string& script, bool disk_full) {
  if (disk_full) {
    std::fprintf(stderr, "warning: plot script %s could not write its PNG: No space left on "
                 "device; the CSV and JSON results are complete\n", script.c_str());
    return;
  }
  std::fprintf(stderr, "warning: plot script %s failed; the CSV and JSON results are complete\n",
               script.c_str());
}

// starts python3 with the arguments, MPLBACKEND=Agg added to the environment; when socket_fd
// >= 0 it becomes the child's stdin and fd 3. Everything the child needs is prepared before
// fork(): a multi-threaded parent's child may only call async-signal-safe functions.
pid_t spawn_python(const std::vector<std::string>& args, int socket_fd) {
  std::vector<std::string> env_text = {"MPLBACKEND=Agg"};
  for (char** e = environ; *e != nullptr; ++e) {
    if (std::string(*e).rfind("MPLBACKEND=", 0) != 0) env_text.emplace_back(*e);
  }
  std::vector<char*> envp, argv;
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);
  argv.push_back(const_cast<char*>(kPython));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  // SIGINT and SIGTERM are blocked across fork, so kneesim's handler (engine/io/interrupt.h)
  // never runs in the child; the parent receives a pending one when it unblocks
  sigset_t block, old;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  ::pthread_sigmask(SIG_BLOCK, &block, &old);
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (socket_fd >= 0 && (::dup2(socket_fd, 0) < 0 || ::dup2(socket_fd, 3) < 0)) ::_exit(127);
    // a Ctrl-C reaches the whole process group: Python started with SIGINT ignored installs
    // no KeyboardInterrupt handler (no traceback); kneesim's own handler stops it with SIGTERM
    struct sigaction ignore {}, deflt {};
    ignore.sa_handler = SIG_IGN;
    deflt.sa_handler = SIG_DFL;
    ::sigaction(SIGINT, &ignore, nullptr);
    ::sigaction(SIGTERM, &deflt, nullptr);
    ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
    ::execve(kPython, argv.data(), envp.data());
    ::_exit(127);
  }
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return pid;
}

// the child's exit code, -1 when it was killed or cannot be waited for
int wait_exit(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool wait_ok(pid_t pid) { return wait_exit(pid) == 0; }

// the open session, if any: the interpreter, its socket and the scripts queued, in order
struct Session {
  pid_t pid = -1;
  int fd = -1;
  std::vector<std::string> queued;
  int child_slot = -1;  // engine/io/interrupt.h
};
std::mutex g_mutex;
Session* g_session = nullptr;

bool send_all(int fd, const std::string& text) {
  for (size_t done = 0; done < text.size();) {
    const ssize_t n = ::send(fd, text.data() + done, text.size() - done, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

}  // namespace

bool run_plot(const std::string& script, const std::vector<std::string>& args,
              bool disk_full_is_error) {
  const std::string path = (plots_dir() / script).string();
  if (!std::filesystem::exists(kPython)) {
    std::fprintf(stderr, "warning: %s not found, skipped plot %s\n", kPython, script.c_str());
    return false;
  }
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    if (g_session != nullptr) {
      const nlohmann::json request = {{"script", path}, {"args", args}};
      if (send_all(g_session->fd, request.dump() + "\n")) {
        g_session->queued.push_back(script);
        return true;
      }
      // the interpreter is gone: this plot runs on its own below
    }
  }
  std::vector<std::string> argv = {path};
  argv.insert(argv.end(), args.begin(), args.end());
  const pid_t pid = spawn_python(argv, -1);
  const int child = pid > 0 ? register_child(pid) : -1;
  const int code = pid > 0 ? wait_exit(pid) : -1;
  unregister_child(child);
  if (code == kPlotDiskFull && disk_full_is_error) {
    throw std::runtime_error("cannot write the PNG plots of " + script + ": No space left on "
                             "device (the tables in progress are kept as *.partial.*)");
  }
  if (code != 0) {
    warn_failed(script, code == kPlotDiskFull);
    return false;
  }
  return true;
}

void wait_for_plots(bool disk_full_is_error) {
  std::vector<std::string> scripts, replies;
  {
    // held while reading: no plot is queued meanwhile, so the replies read are these plots'
    std::lock_guard<std::mutex> lock(g_mutex);
    if (g_session == nullptr || g_session->queued.empty()) return;
    std::string text;
    char c;
    while (replies.size() < g_session->queued.size()) {
      const ssize_t n = ::read(g_session->fd, &c, 1);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;  // the interpreter is gone: the rest failed
      if (c == '\n') {
        replies.push_back(text);
        text.clear();
      } else {
        text += c;
      }
    }
    scripts.swap(g_session->queued);
  }
  replies.resize(scripts.size());
  bool disk_full = false;
  std::string full_script;
  for (size_t i = 0; i < scripts.size(); ++i) {
    if (replies[i] == "ok") continue;
    if (replies[i] == "disk full" && disk_full_is_error) {
      if (!disk_full) full_script = scripts[i];
      disk_full = true;
      continue;
    }
    warn_failed(scripts[i], replies[i] == "disk full");
  }
  if (disk_full) {
    throw std::runtime_error("cannot write the PNG plots of " + full_script + ": No space left "
                             "on device (the tables in progress are kept as *.partial.*)");
  }
}

PlotSession::PlotSession() {
  if (!std::filesystem::exists(kPython)) return;  // run_plot warns per plot
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) return;
  const pid_t pid = spawn_python({(plots_dir() / "plot_server.py").string()}, sv[1]);
  ::close(sv[1]);
  if (pid < 0) {
    ::close(sv[0]);
    return;
  }
  std::lock_guard<std::mutex> lock(g_mutex);
  if (g_session != nullptr) {  // one session at a time: this one stays unused
    ::close(sv[0]);
    ::kill(pid, SIGTERM);
    wait_ok(pid);
    return;
  }
  g_session = new Session{pid, sv[0], {}, register_child(pid)};
}

PlotSession::~PlotSession() {
  Session* s = nullptr;
  {
    std::lock_guard<std::mutex> lock(g_mutex);
    std::swap(s, g_session);
  }
  if (s == nullptr) return;
  if (s->queued.empty()) {
    // nothing to plot (an error ended the command, or it had no plot): not worth waiting for
    ::kill(s->pid, SIGTERM);
  }
  ::shutdown(s->fd, SHUT_WR);  // end of requests: the interpreter exits after the last
  // one reply line per queued plot, in order; a missing line is a failed plot
  std::string replies;
  char buf[256];
  for (;;) {
    const ssize_t n = ::read(s->fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    replies.append(buf, static_cast<size_t>(n));
  }
  ::close(s->fd);
  wait_ok(s->pid);
  unregister_child(s->child_slot);
  size_t pos = 0;
  for (const std::string& script : s->queued) {
    const size_t end = replies.find('\n', pos);
    const std::string reply =
        end == std::string::npos ? std::string() : replies.substr(pos, end - pos);
    if (reply != "ok") warn_failed(script, reply == "disk full");
    pos = end == std::string::npos ? replies.size() : end + 1;
  }
  delete s;
}

}  // namespace kneesim::io
