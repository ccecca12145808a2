#include "util/checkpoint_file.h"

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/zip_check.h"

namespace vaegail {

namespace fs = std::filesystem;

namespace {

std::string serialised(const std::string& path, const SaveToStream& save) {
  std::ostringstream out;
  try {
    save(out);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": cannot serialise checkpoint: " + first_line(e.what()));
  }
  if (!out) throw std::runtime_error(path + ": cannot serialise checkpoint");
  return out.str();
}

}  // namespace

std::string model_file(const std::string& run) {
  if (!fs::is_directory(run)) return run;
  for (const auto& candidate : {fs::path(run) / "checkpoints" / "latest.pt", fs::path(run) / kWeightsFile})
    if (fs::exists(candidate)) return candidate.string();
  throw std::runtime_error(run + ": a directory with neither checkpoints/latest.pt nor " + kWeightsFile +
                           " (not a run directory?)");
}

std::string previous_checkpoint_for(const std::string& latest) {
  fs::path previous(latest);
  return previous.replace_filename("previous" + previous.extension().string()).string();
}

void write_checkpoint(const std::string& path, const SaveToStream& save) {
  write_file_atomically(path, serialised(path, save));
}

void rotate_and_write(const std::string& latest, const SaveToStream& save) {
  write_file_atomically(latest, serialised(latest, save), previous_checkpoint_for(latest));
}

void read_checkpoint(const std::string& path, const LoadFromFile& load) {
  if (!fs::exists(path)) throw std::runtime_error(path + ": no such checkpoint");
  const std::string bytes = read_file(path);
  if (looks_like_zip(bytes)) {
    const std::string damage = zip_damage(bytes);
    if (!damage.empty()) throw std::runtime_error(path + ": damaged checkpoint (" + damage + ")");
  }
  try {
    load(path);
  } catch (const std::logic_error&) {
    throw;
  } catch (const std::exception& e) {
    if (names_in_one_line(e.what(), path)) throw;
    throw std::runtime_error(path + ": unreadable checkpoint (" + first_line(e.what()) + ")");
  }
}

std::string ResumedCheckpoint::message() const {
  if (path.empty()) return "";
  return "resumed from " + path + (skipped.empty() ? "" : " (" + skipped + ")");
}

ResumedCheckpoint resume_checkpoint(const std::string& latest, const LoadFromFile& load) {
  const std::string previous = previous_checkpoint_for(latest);
  ResumedCheckpoint resumed;
  if (fs::exists(latest)) {
    try {
      read_checkpoint(latest, load);
      resumed.path = latest;
      return resumed;
    } catch (const std::logic_error&) {
      throw;
    } catch (const std::exception& e) {
      resumed.skipped = e.what();
    }
  } else if (fs::exists(previous)) {
    resumed.skipped = latest + ": missing";  // a run stopped between the two renames of a rotation
  } else {
    return resumed;
  }
  try {
    read_checkpoint(previous, load);
  } catch (const std::logic_error&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(resumed.skipped + "; " + e.what());
  }
  resumed.path = previous;
  if (fs::exists(latest)) {
    const std::string corrupt = latest + ".corrupt";
    if (std::rename(latest.c_str(), corrupt.c_str()) != 0)
      throw std::runtime_error(latest + ": cannot move the unreadable checkpoint aside to " + corrupt);
    resumed.skipped += "; kept as " + corrupt;
  }
  return resumed;
}

}  // namespace vaegail
