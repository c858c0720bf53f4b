#include "analysis/study/trial_record.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "engine/errors.h"
#include "engine/io/atomic_file.h"
#include "engine/io/journal_file.h"
#include "wear/checkpoint.h"

namespace kneesim::study {
namespace {

constexpr const char* kHeader = "# kneesim study journal v1 identity=";

// FNV-1a of a string through the checkpoint's hash (wear/checkpoint.h)
uint64_t fnv1a(const std::string& s) { return wear::fnv1a(s.data(), s.size()); }

void put(std::string& out, double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, " %a", v);
  out += buf;
}

// text without spaces, tabs or newlines (failure messages and labels)
std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) out += (c == ' ' || c == '\t' || c == '\n' || c == '\r') ? '_' : c;
  return out.empty() ? "-" : out;
}

}  // namespace

std::string journal_header(uint64_t identity) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s%016" PRIx64 "\n", kHeader, identity);
  return buf;
}

std::string to_journal_line(const TrialRecord& r) {
  std::string body = "T " + std::to_string(r.index) + " " + std::to_string(r.seed) + " " +
                     escape(r.point) + " " + (r.ok ? "ok" : "failed") + " " + escape(r.failure);
  body += " " + std::to_string(r.inputs.size());
  for (double v : r.inputs) put(body, v);
  body += " " + std::to_string(r.scalars.size());
  for (double v : r.scalars) put(body, v);
  body += " " + std::to_string(r.curves.size());
  for (const auto& c : r.curves) {
    body += " " + std::to_string(c.size());
    for (double v : c) put(body, v);
  }
  char sum[24];
  std::snprintf(sum, sizeof sum, " %016" PRIx64 "\n", fnv1a(body));
  return body + sum;
}

bool from_journal_line(const std::string& line, TrialRecord& r) {
  const auto last = line.rfind(' ');
  if (line.rfind("T ", 0) != 0 || last == std::string::npos) return false;
  const std::string body = line.substr(0, last);
  char* end = nullptr;
  const uint64_t sum = std::strtoull(line.c_str() + last + 1, &end, 16);
  if (end == line.c_str() + last + 1 || sum != fnv1a(body)) return false;
  std::istringstream in(body.substr(2));
  std::string ok, failure, point;
  size_t n = 0;
  r = TrialRecord{};
  if (!(in >> r.index >> r.seed >> point >> ok >> failure)) return false;
  r.point = point == "-" ? "" : point;
  r.ok = ok == "ok";
  r.failure = failure == "-" ? "" : failure;
  auto read_doubles = [&](std::vector<double>& v) {
    if (!(in >> n) || n > 1000000) return false;
    v.resize(n);
    std::string tok;
    for (size_t i = 0; i < n; ++i) {
      if (!(in >> tok)) return false;
      v[i] = std::strtod(tok.c_str(), nullptr);
    }
    return true;
  };
  if (!read_doubles(r.inputs) || !read_doubles(r.scalars)) return false;
  size_t curves = 0;
  if (!(in >> curves) || curves > 1000) return false;
  r.curves.resize(curves);
  for (auto& c : r.curves)
    if (!read_doubles(c)) return false;
  return true;
}

std::filesystem::path journal_path(const std::filesystem::path& dir, int rank) {
  return dir / ("trials.journal." + std::to_string(rank));
}

std::map<long, TrialRecord> read_journals(const std::filesystem::path& dir, uint64_t identity) {
  namespace fs = std::filesystem;
  std::map<long, TrialRecord> out;
  if (!fs::exists(dir)) return out;
  const std::string header = journal_header(identity);
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename().string().rfind("trials.journal.", 0) == 0) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    const std::string text = io::read_file(f);
    if (text.empty()) continue;
    if (text.rfind(header, 0) != 0) {
      throw InputError(f.string() + " belongs to a different study (another config, method, "
                       "trial count, seed or variables); resume it with its own options or "
                       "choose another --out");
    }
    size_t pos = header.size();
    while (pos < text.size()) {
      const size_t nl = text.find('\n', pos);
      if (nl == std::string::npos) break;  // a torn last line: its trial runs again
      TrialRecord r;
      if (from_journal_line(text.substr(pos, nl + 1 - pos - 1), r)) out[r.index] = std::move(r);
      pos = nl + 1;
    }
  }
  return out;
}

void remove_journals(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  if (!fs::exists(dir)) return;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().filename().string().rfind("trials.journal.", 0) == 0) fs::remove(e.path());
  }
}

}  // namespace kneesim::study
