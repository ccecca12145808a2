// `vaegail export`: a trained run's weights file, to re-evaluate, render or deploy the model
// without its optimiser state (util/checkpoint_file.h, gail/weights_export.h).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "cli/commands.h"
#include "gail/weights_export.h"
#include "util/checkpoint_file.h"

namespace vaegail::cli {

namespace {

struct ExportFlags {
  std::string run_dir, out, vae;
};

double megabytes(const std::string& path) { return std::filesystem::file_size(path) / 1e6; }

void run_export(const ExportFlags& f) {
  if (!std::filesystem::is_directory(f.run_dir)) throw std::invalid_argument(f.run_dir + ": no such run directory");
  const std::string out = f.out.empty() ? (std::filesystem::path(f.run_dir) / kWeightsFile).string() : f.out;
  const std::string source = model_file(f.run_dir);
  const std::string kind = export_weights(f.run_dir, out, f.vae);
  std::printf("%s: %s weights of %s (%.1f MB) -> %s (%.1f MB)\n", f.run_dir.c_str(), kind.c_str(), source.c_str(),
              megabytes(source), out.c_str(), megabytes(out));
}

}  // namespace

void add_export_command(CLI::App& app) {
  auto f = std::make_shared<ExportFlags>();
  CLI::App* c = app.add_subcommand(
      "export", "a trained run's weights file (weights and config, no optimiser state): every loader takes it");
  c->add_option("--run-dir", f->run_dir, "a vae train, gail train or bc train run directory")->required();
  c->add_option("--out", f->out, "the weights file (default RUN_DIR/weights.pt)");
  c->add_option("--vae", f->vae, "diverse GAIL: the VAE run it was fine-tuned on, for its sizes (default: the "
                                 "run's recorded vae_path)");
  c->callback([f] { run_export(*f); });
}

}  // namespace vaegail::cli
