// The integrity check LibTorch skips: its checkpoints are zip archives whose entries each have
// a CRC-32 in the zip directory, but LibTorch is built with miniz's CRC check
// off, so a flipped byte among a checkpoint's tensors loads unnoticed. This walks the archive's
// central directory and checks every entry's bytes against its CRC-32; the same walk reads
// the entries of an archive.
#pragma once

#include <map>
#include <string>

namespace vaegail {

// Whether `bytes` begins like a zip archive (what LibTorch writes).
bool looks_like_zip(const std::string& bytes);

// "" when the archive is whole and every entry matches its CRC-32; else what is wrong, e.g.
// "entry archive/data/0 fails its CRC-32" or "truncated: no zip directory at the end".
// Zip64 directories (archives or entries past 4 GiB) are read; entries are stored (LibTorch's
// tensors) or deflated (some of its code entries, inflated piece by piece to check them).
std::string zip_damage(const std::string& bytes);

// Every entry of a whole archive by name, inflated (numpy's .npz files are such archives);
// throws std::runtime_error saying what zip_damage says when the archive is damaged.
std::map<std::string, std::string> zip_entries(const std::string& bytes);

}  // namespace vaegail
