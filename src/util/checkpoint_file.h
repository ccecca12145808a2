// Checkpoints on a failing disk and from a damaged file. A checkpoint is serialised in memory,
// then written atomically (util/atomic_file.h): LibTorch's OutputArchive::save_to(filename)
// aborts the process when a write fails (its writer throws again from its destructor), while
// save_to(std::ostream&) into memory cannot fail on a disk. A trainer's checkpoint keeps the one
// before it (latest.pt and previous.pt), and resuming falls back to previous.pt when latest.pt
// is missing or unreadable. Every failure is one line naming the file. LibTorch-free: callers
// pass what serialises and what loads.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace vaegail {

// Serialises a checkpoint: [&](std::ostream& out) { archive.save_to(out); }.
using SaveToStream = std::function<void(std::ostream&)>;
// Loads one: [&](const std::string& path) { archive.load_from(path, device); ... }.
using LoadFromFile = std::function<void(const std::string&)>;

// A weights-only file (`vaegail export`): what rebuilds and runs a trained model, without the
// optimiser state and counters that a trainer's checkpoint keeps for resuming. A LibTorch
// archive: "kind" names the model ("vae", "gail" or "bc"), "config" is its options as JSON (what
// sizes it), and the module lies under the name its trainer's checkpoint gives it ("model" for
// the VAE, "agent" for a policy); a diverse-GAIL policy adds "vae_config", its frozen VAE's.
// Written into the run directory by default, under this name.
inline constexpr const char* kWeightsFile = "weights.pt";

// The file a loader reads for `run`: a file as it is (a trainer's checkpoint or a weights file);
// for a run directory its checkpoints/latest.pt (the newest state), else its weights file (a run
// directory that ships only the export). A directory with neither throws one line naming it.
std::string model_file(const std::string& run);

// "previous" with latest's extension, in latest's folder: checkpoints/previous.pt.
std::string previous_checkpoint_for(const std::string& latest);

// Writes `path` from `save`; on failure `path` is as it was and no temporary file is left.
void write_checkpoint(const std::string& path, const SaveToStream& save);

// The same, keeping the file it replaces as previous_checkpoint_for(latest).
void rotate_and_write(const std::string& latest, const SaveToStream& save);

// Calls load(path). A missing file throws "PATH: no such checkpoint"; a zip archive (what
// LibTorch writes) with an entry that fails its CRC-32 or a directory cut short "PATH: damaged
// checkpoint (WHAT)" (util/zip_check.h), before LibTorch reads it; a failed load (LibTorch's
// c10::Error and its stack trace) "PATH: unreadable checkpoint (FIRST LINE)". A
// std::logic_error passes through as thrown: it means a whole checkpoint of another run
// (another config or seed), which falling back would not mend.
void read_checkpoint(const std::string& path, const LoadFromFile& load);

struct ResumedCheckpoint {
  std::string path;     // the file loaded; empty when there was none (a fresh run)
  std::string skipped;  // why latest was passed over, when `path` is the previous checkpoint
  // "" for a fresh run, else "resumed from PATH", and why latest was skipped.
  std::string message() const;
};

// For a trainer resuming: reads latest, or when that is missing or unreadable the previous
// checkpoint. An unreadable latest is then renamed to LATEST.corrupt, so that the next
// rotate_and_write keeps the good previous checkpoint rather than the damaged one. Throws one
// line naming both files when neither loads.
ResumedCheckpoint resume_checkpoint(const std::string& latest, const LoadFromFile& load);

}  // namespace vaegail
