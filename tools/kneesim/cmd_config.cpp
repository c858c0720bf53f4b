// `kneesim config`: what a config can say. `--reference` prints every key of the config
// registry with its type, default, allowed range and meaning (docs/config-reference.md is its
// output); `--check CONFIG` loads a config as every command would and reports the first error.
#include <cstdio>
#include <string>
#include <vector>

#include "analysis/run/gait_run.h"
#include "models/config_reference.h"
#include "models/config_template.h"
#include "tools/kneesim/commands.h"

namespace kneesim::cli {

void add_config_command(CLI::App& app) {
  struct Args {
    bool reference = false;
    bool template_ = false;
    std::string femur, insert;
    std::string check;
    std::vector<std::string> sets;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "config", "Print the configuration reference or a template for your own implant, or "
      "check a config file.");
  cmd->add_flag("--reference", args->reference,
                "print every config key (type, default, allowed range, meaning) as Markdown");
  cmd->add_flag("--template", args->template_,
                "print a commented config for your own implant meshes (then: kneesim implant "
                "check CONFIG)");
  cmd->add_option("--femur", args->femur, "--template: the femoral component's mesh file");
  cmd->add_option("--insert", args->insert, "--template: the tibial insert's mesh file");
  cmd->add_option("--check", args->check,
                  "load CONFIG (with any --set) as every command does and report its first "
                  "error (exit 2) or 'ok'");
  cmd->add_option("--set", args->sets, "key=value override (TOML value syntax), repeatable");
  cmd->callback([args] {
    if (int(args->reference) + int(args->template_) + int(!args->check.empty()) != 1) {
      throw CLI::ValidationError("kneesim config",
                                 "give exactly one of --reference, --template, --check");
    }
    if (!args->template_ && (!args->femur.empty() || !args->insert.empty())) {
      throw CLI::ValidationError("kneesim config", "--femur and --insert go with --template");
    }
    if (args->template_) {
      std::fputs(models::config_template(args->femur, args->insert).c_str(), stdout);
      return;
    }
    if (args->reference) {
      std::fputs(models::config_reference_markdown().c_str(), stdout);
      return;
    }
    run::load_run_config(args->check, args->sets);
    std::printf("%s: ok\n", args->check.c_str());
  });
}

}  // namespace kneesim::cli
