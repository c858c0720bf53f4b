#include "analysis/report/provenance.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/report/file_hash.h"
#include "engine/io/source_tree.h"

namespace kneesim::report {
namespace {

std::string& stored_command_line() {
  static std::string s;
  return s;
}

std::string shell_quote(const std::string& a) {
  if (!a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                        "0123456789-_./=:,+%@") == std::string::npos) {
    return a;
  }
  std::string q = "'";
  for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

void set_command_line(int argc, const char* const* argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) s += (i ? " " : "") + shell_quote(argv[i]);
  stored_command_line() = s;
}

const std::string& command_line() { return stored_command_line(); }

Provenance make_provenance(const std::string& config_path, const std::vector<std::string>& sets,
                           const models::Config& config,
                           const std::vector<std::pair<std::string, std::string>>& extra) {
  namespace fs = std::filesystem;
  Provenance p;
  p.version = kVersion;
  p.command_line = command_line();
  std::error_code ec;
  p.working_dir = fs::current_path(ec).string();
  p.created_utc = utc_now();
  p.overrides = sets;
  auto add = [&p](const std::string& role, const fs::path& path) {
    if (path.empty()) return;
    const fs::path abs = fs::absolute(path);
    for (const InputFile& f : p.inputs) {
      if (f.path == abs.string()) return;
    }
    p.inputs.push_back({role, abs.string(), sha256_file(abs)});
  };
  if (!config_path.empty()) {
    p.config_path = fs::absolute(config_path).string();
    std::ifstream in(config_path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    p.config_text = s.str();
    add("config", config_path);
  }
  auto resolved = [&config](const std::string& f) {
    return f.empty() ? fs::path() : models::resolve_path(config, f);
  };
  if (config.implant_kind == "mesh") {
    add("femur mesh", resolved(config.femur_mesh));
    add("insert mesh", resolved(config.insert_mesh));
  }
  add("gait waveform", resolved(config.gait_file));  // the shipped one: the caller's `extra`
  add("measured kinematics (rig input)", resolved(config.kinematics_file));
  add("measured kinematics (overlay)", resolved(config.measured_kinematics));
  add("contact law table", resolved(config.contact_law_file));
  add("materials library", io::source_dir() / "models" / "materials.toml");
  for (const auto& [role, path] : extra) add(role, path);
  return p;
}

}  // namespace kneesim::report
