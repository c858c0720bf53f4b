#include "loads/iso14243/waveform.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "engine/errors.h"
#include "loads/iso14243/text_table.h"

namespace kneesim::loads {
namespace {

constexpr double kCycle = 100.0;  // [%] period

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// checks one gait_pct value against the range and its predecessor
void check_pct(const TextTable& t, std::size_t row, std::size_t col, double pct, double prev,
               bool has_prev, const std::string& what) {
  const std::string where = display_path(t.file) + ": line " + std::to_string(t.line[row]) +
                            ", column '" + t.header[col] + "'";
  if (pct < 0.0 || pct > kCycle) {
    throw InputError(where + ": " + fmt(pct) + " is outside the allowed range 0..100 %.");
  }
  if (has_prev && pct <= prev) {
    throw InputError(where + ": " + fmt(pct) + " does not increase over the previous " + what +
                     " value " + fmt(prev) + " (gait_pct must be strictly increasing).");
  }
}

Waveform load_table(const TextTable& t) {
  if (t.header.empty() || t.header[0] != "gait_pct") {
    throw InputError(display_path(t.file) + ": the first column must be 'gait_pct', found '" +
                     (t.header.empty() ? std::string() : t.header[0]) + "'.");
  }
  if (t.header.size() < 2) {
    throw InputError(display_path(t.file) + ": the table has no channel column after gait_pct.");
  }
  std::vector<double> pct;
  std::vector<std::vector<double>> cols(t.header.size() - 1);
  for (std::size_t r = 0; r < t.cells.size(); ++r) {
    double p = t.number(r, 0);
    check_pct(t, r, 0, p, pct.empty() ? 0.0 : pct.back(), !pct.empty(), "row's");
    pct.push_back(p);
    for (std::size_t c = 1; c < t.header.size(); ++c) cols[c - 1].push_back(t.number(r, c));
  }
  std::vector<std::string> names(t.header.begin() + 1, t.header.end());
  return Waveform::from_table(names, pct, cols, display_path(t.file));
}

Waveform load_keypoints(const TextTable& t) {
  if (t.header != std::vector<std::string>{"channel", "gait_pct", "value"}) {
    throw InputError(display_path(t.file) +
                     ": a keypoints file needs the header 'channel,gait_pct,value'.");
  }
  // group rows by channel in order of first appearance
  std::vector<Waveform::KeyPoints> chans;
  for (std::size_t r = 0; r < t.cells.size(); ++r) {
    const std::string& name = t.cells[r][0];
    if (name.empty()) {
      throw InputError(display_path(t.file) + ": line " + std::to_string(t.line[r]) +
                       ", column 'channel': the channel name is empty.");
    }
    auto it = std::find_if(chans.begin(), chans.end(), [&](auto& k) { return k.name == name; });
    if (it == chans.end()) {
      chans.push_back({name, {}, {}});
      it = chans.end() - 1;
    }
    double p = t.number(r, 1);
    check_pct(t, r, 1, p, it->pct.empty() ? 0.0 : it->pct.back(), !it->pct.empty(),
              "'" + name + "' key point's");
    it->pct.push_back(p);
    it->value.push_back(t.number(r, 2));
  }
  return Waveform::from_keypoints(chans, display_path(t.file));
}

}  // namespace

Waveform load_waveform(const std::filesystem::path& file) {
  TextTable t = read_text_table(file, TextFormat::csv);
  // the form is declared, or recognised from the key-point header
  std::string form = "table";
  if (auto it = t.directives.find("form"); it != t.directives.end()) {
    form = it->second;
  } else if (t.header == std::vector<std::string>{"channel", "gait_pct", "value"}) {
    form = "keypoints";
  }
  if (form == "keypoints") return load_keypoints(t);
  if (form == "table") return load_table(t);
  throw InputError(display_path(file) + ": '# form: " + form +
                   "' is not a known form; allowed forms are 'table' and 'keypoints'.");
}

}  // namespace kneesim::loads
