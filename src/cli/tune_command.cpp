// `vaegail experts tune STYLE.json`: CMA-ES over a humanoid gait style's parameters
// (experts/style_tuner.h), resumable with the same command; the result is written into the file.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "experts/style_tuner.h"

namespace vaegail::cli {
namespace {

struct TuneFlags {
  std::string style;
  std::string run_dir;  // default: runs/tune/SET_STYLE from the file's folder and name
  int jobs = 2;
};

std::string default_run_dir(const std::string& style) {
  const std::filesystem::path p(style);
  return "runs/tune/" + p.parent_path().filename().string() + "_" + p.stem().string();
}

void run_tune(const TuneFlags& f) {
  const std::string run_dir = f.run_dir.empty() ? default_run_dir(f.style) : f.run_dir;
  const std::string command = fmt::format("vaegail experts tune {} --run-dir {} --jobs {}", f.style, run_dir, f.jobs);
  const TuneResult r = tune_style(f.style, run_dir, f.jobs, command);
  if (!r.resumed.empty()) std::printf("%s\n", r.resumed.c_str());
  std::printf("%s", fmt::format("{}: best cost {:.4f} after {} generations; parameters written into {} (search in {})\n",
                                f.style, r.cost, r.generations, f.style, run_dir)
                        .c_str());
}

}  // namespace

void add_experts_tune(CLI::App& experts) {
  auto f = std::make_shared<TuneFlags>();
  CLI::App* tune = experts.add_subcommand(
      "tune", "humanoid: CMA-ES over a gait style's parameters, scored over pushed episodes against the style's targets; resumable, the result written into the style file");
  tune->add_option("style", f->style, "style file (configs/humanoid_styles/*/*.json) with 'targets' and 'tune'")
      ->required()->check(CLI::ExistingFile);
  tune->add_option("--run-dir", f->run_dir, "the search's state and metrics.csv (default runs/tune/SET_STYLE); a rerun resumes it");
  tune->add_option("--jobs", f->jobs, "candidates scored at once (one core each)")->check(CLI::Range(1, 64))->capture_default_str();
  tune->callback([f] { run_tune(*f); });
}

}  // namespace vaegail::cli
