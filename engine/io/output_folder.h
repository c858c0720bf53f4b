// The output folder of a command, checked before any work: a run that cannot write its results
// must not find out after hours of simulation, and a folder error must read as one sentence
// naming the flag, not as a raw std::filesystem message. The folder is created (with its
// parents) and a probe file written and removed, which also catches read-only file systems,
// immutable folders and full disks that permission bits do not show.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace kneesim::io {

// creates `dir` if needed and checks that a file can be written in it; throws InputError
// ("--out 'x' is an existing file, not a folder; ...") naming `flag` and the folder.
// Then claims it for this process until it exits: DIR/.kneesim.lock (pid, command, start;
// an flock, so the lock of a killed process is taken over silently) refuses a second kneesim process
// naming the first; DIR/.kneesim-command names the command whose results the folder holds,
// and a different command is refused while the folder holds any (non-hidden) file; files a
// killed run left in the middle of an atomic write (NAME.tmp.PID) are removed. MPI ranks other
// than 0 share rank 0's claim.
// A folder the call created is removed again when the process ends and nothing but the
// command marker was written in it (a command refused after the check leaves no empty folder).
void check_output_folder(const std::filesystem::path& dir, const std::string& flag = "--out");

// bytes free for an unprivileged writer on the file system holding `dir` (an existing folder);
// UINTMAX_MAX when unknown
std::uintmax_t free_bytes(const std::filesystem::path& dir);

// "1.2 GB", "350 MB", "12 kB": a byte count for a message
std::string format_bytes(double bytes);

}  // namespace kneesim::io
