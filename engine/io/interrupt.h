// What a command leaves behind when it does not finish: on SIGINT, SIGTERM or an error exit,
// every table registered as "being written" is renamed to its partial name (wear.csv ->
// wear.partial.csv), every temporary file of an atomic write in progress is removed, the
// plotting interpreters are stopped and the output-folder locks are released, so no folder
// holds a partial result under a final name or a stale lock. A signal then ends the process
// with 128 + the signal's number (130 for SIGINT, 143 for SIGTERM).
//
// The registries are fixed arrays of slots written before they are published with an atomic
// flag, because the signal handler may only read memory and call async-signal-safe functions
// (rename, unlink, kill, _exit); a slot is claimed and released from ordinary code, from any
// thread. What is registered beyond the slots is not cleaned up (a warning is printed once).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <utility>
#include <vector>

namespace kneesim::io {

// SIGINT and SIGTERM handlers: clean up as above, print one line, _exit(128 + signal).
// main() calls it once before any work.
void install_interrupt_handlers();

// renames every registered table to its partial name, removes registered temporary files
// and releases the folder locks; for error exits (main's catch blocks), idempotent
void abandon_outputs();

// `final` is being written and is not a complete result until unregister_partial(id):
// abandoned, it is renamed to `partial`. Returns the slot id (-1 when none is free).
int register_partial(const std::filesystem::path& final, const std::filesystem::path& partial);
void unregister_partial(int id);

// the tables of a result that is not complete until its summary is written: each is
// registered as partial while this object lives; leaving the scope without commit() (an
// exception) renames every one that exists to its partial name, as a signal or an error exit
// would; commit() (after the summary) unregisters them, keeping the final names
class PartialOutputs {
 public:
  PartialOutputs() = default;
  ~PartialOutputs();
  PartialOutputs(const PartialOutputs&) = delete;
  PartialOutputs& operator=(const PartialOutputs&) = delete;
  // `final` (e.g. DIR/trials.csv) is kept as `partial` (DIR/trials.partial.csv) if abandoned
  void add(const std::filesystem::path& final, const std::filesystem::path& partial);
  void commit();

 private:
  struct Entry {
    int slot;
    std::filesystem::path final, partial;
  };
  std::vector<Entry> entries_;
};

// a temporary file that an abandoned command removes
int register_temp(const std::filesystem::path& file);
void unregister_temp(int id);

// a child process (the plotting interpreter) that an abandoned command stops with SIGTERM
int register_child(pid_t pid);
void unregister_child(int id);

// a lock file that an abandoned command removes (engine/io/output_folder.h)
int register_lock(const std::filesystem::path& file);
void unregister_lock(int id);

}  // namespace kneesim::io
