// `vaegail export`: the weights file (util/checkpoint_file.h) of a trained run, whichever trainer
// wrote it: what evaluating, rendering or deploying the model needs, without the optimiser state
// and the discriminator that only resuming its training does.
#pragma once

#include <string>

namespace vaegail {

// The kind of the run in `run_dir`, from its config.json: "gail" (it names a mode), "vae" (a
// latent size) or "bc" (hidden sizes). Throws one line naming the file otherwise.
std::string run_kind(const std::string& run_dir);

// Writes the weights file of the run in `run_dir` (its newest state, util/checkpoint_file.h's
// model_file) to `out`, atomically, and returns its kind. A diverse-GAIL trainer checkpoint does
// not record its VAE's sizes: they come from `vae` (a VAE run, checkpoint or weights file), or
// when that is empty from the run's recorded vae_path. Throws one line naming the file at fault.
std::string export_weights(const std::string& run_dir, const std::string& out, const std::string& vae = "");

}  // namespace vaegail
