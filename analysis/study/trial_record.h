// One finished trial of a study and its journal line.
//
// Finished trials are appended to a journal (DIR/trials.journal.<rank>) as they complete, one
// line each, written with one write(2) and fsync'ed (io::append_line_durable), every number as
// a hexadecimal float so a resumed study restores the exact bits. A line carries its own
// FNV-1a checksum: a torn or corrupted line is dropped and its trial simply runs again, so
// `--resume` neither loses nor repeats a finished trial. The journal's first line names the
// study's identity (a hash of everything that defines it); a journal of another study is
// refused. trials.csv, sorted by index, is written from the records at the end.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace kneesim::study {

struct TrialRecord {
  long index = 0;
  uint64_t seed = 0;                      // the trial's sampling seed (0 for AMV points)
  std::string point;                      // AMV design point ("mean", "grad:<label>",
                                          // "mpp:<measure>:p01"); "" for MC and LHS
  std::vector<double> inputs;             // one per variable [key's unit]
  std::vector<double> scalars;            // one per scalar measure (NaN when failed)
  std::vector<std::vector<double>> curves;  // one per curve, its samples (empty when failed)
  bool ok = true;
  std::string failure;                    // why the trial stopped (numerical trouble), or
                                          // an ok trial's remark
};

std::string journal_header(uint64_t identity);
std::string to_journal_line(const TrialRecord& r);
// false for a torn, corrupted or foreign-format line
bool from_journal_line(const std::string& line, TrialRecord& r);

// every intact record of the journals in `dir` (any rank count), by index; throws
// InputError when a journal belongs to another study (identity differs)
std::map<long, TrialRecord> read_journals(const std::filesystem::path& dir, uint64_t identity);
std::filesystem::path journal_path(const std::filesystem::path& dir, int rank);
void remove_journals(const std::filesystem::path& dir);

}  // namespace kneesim::study
