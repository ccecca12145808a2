// Seeded corruptions of a file this program wrote, each read in a forked child (a segfault
// inside libhdf5 cannot be caught in-process) under an alarm: the reader must never crash,
// abort or hang; it loads the file or rejects it with one line naming it. With the file's
// checksums, no corruption may load as changed data.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>

#include "data/demos.h"
#include "data/demos_test_support.h"
#include "util/rng.h"
#include "util/test_child.h"

namespace vaegail {
namespace {

constexpr int kCasesPerMutation = 200;
constexpr unsigned kTimeoutSeconds = 10;  // a clean read takes milliseconds
constexpr std::uint64_t kSeed = 39;

enum class Mutation { kOverwrittenBytes, kTruncation, kZeroedBlock };
const char* const kMutationNames[] = {"overwritten bytes", "truncation", "zeroed block"};

// A corrupted copy of `bytes`; the stream is seeded per case, so each case is reproducible alone.
std::string mutate(std::string bytes, Mutation mutation, Rng& rng) {
  const auto below = [&](size_t n) { return static_cast<size_t>(rng.next() % n); };
  switch (mutation) {
    case Mutation::kOverwrittenBytes:
      for (size_t i = 0, n = 1 + below(8); i < n; ++i) bytes[below(bytes.size())] = static_cast<char>(rng.next());
      break;
    case Mutation::kTruncation:
      bytes.resize(below(bytes.size()));
      break;
    case Mutation::kZeroedBlock: {
      const size_t start = below(bytes.size()), length = 16 + below(497);
      for (size_t i = start; i < std::min(bytes.size(), start + length); ++i) bytes[i] = '\0';
      break;
    }
  }
  return bytes;
}

enum class Verdict { kRejected, kLoadedUnchanged, kLoadedChanged };

// In the child: the verdict as the exit status, the rejection's message (or the changed field)
// as the report.
int read_in_child(const std::string& path, std::string& report) {
  try {
    report = toy_contents_difference(read_demos(path));
    return static_cast<int>(report.empty() ? Verdict::kLoadedUnchanged : Verdict::kLoadedChanged);
  } catch (const std::exception& e) {
    report = e.what();
    return static_cast<int>(Verdict::kRejected);
  }
}

TEST(DemosFuzz, CorruptedFilesAreLoadedOrRejectedInOneLineNeverCrashOrHang) {
  const std::string clean = write_toy_file("fuzz_clean"), path = temp_demo_path("fuzz_case");
  std::ifstream in(clean, std::ios::binary);
  const std::string bytes(std::istreambuf_iterator<char>(in), {});
  ASSERT_FALSE(bytes.empty());
  std::map<Verdict, int> verdicts;
  int crashes = 0, hangs = 0, cases = 0;
  for (int m = 0; m < 3; ++m) {
    std::map<Verdict, int> of_mutation;
    for (int c = 0; c < kCasesPerMutation; ++c, ++cases) {
      Rng rng(derive_seed(kSeed, static_cast<std::uint64_t>(cases)));
      std::ofstream(path, std::ios::binary | std::ios::trunc) << mutate(bytes, Mutation(m), rng);
      const ChildOutcome outcome = run_in_child([&](std::string& report) { return read_in_child(path, report); },
                                                kTimeoutSeconds);
      const std::string where = std::string(kMutationNames[m]) + ", case " + std::to_string(cases);
      if (outcome.end == ChildOutcome::End::kTimedOut) {
        ++hangs;
        ADD_FAILURE() << where << ": no answer in " << kTimeoutSeconds << " s";
        continue;
      }
      if (outcome.end == ChildOutcome::End::kCrashed || outcome.code > int(Verdict::kLoadedChanged)) {
        ++crashes;
        ADD_FAILURE() << where << ": ended by signal or status " << outcome.code;
        continue;
      }
      const auto verdict = Verdict(outcome.code);
      ++of_mutation[verdict];
      ++verdicts[verdict];
      if (verdict == Verdict::kRejected) {
        EXPECT_EQ(outcome.report.find('\n'), std::string::npos) << where << ": " << outcome.report;
        EXPECT_EQ(outcome.report.rfind(path, 0), 0u) << where << ": does not name the file: " << outcome.report;
      }
      EXPECT_NE(verdict, Verdict::kLoadedChanged) << where << ": loaded with a changed " << outcome.report;
    }
    std::printf("%-18s %3d cases: %3d rejected, %3d loaded unchanged, %3d loaded changed\n", kMutationNames[m],
                kCasesPerMutation, of_mutation[Verdict::kRejected], of_mutation[Verdict::kLoadedUnchanged],
                of_mutation[Verdict::kLoadedChanged]);
  }
  std::printf("%d corruptions of a %zu-byte file: %.1f%% rejected, %.1f%% loaded unchanged, %.1f%% loaded "
              "changed; %d crashes, %d hangs\n",
              cases, bytes.size(), 100.0 * verdicts[Verdict::kRejected] / cases,
              100.0 * verdicts[Verdict::kLoadedUnchanged] / cases, 100.0 * verdicts[Verdict::kLoadedChanged] / cases,
              crashes, hangs);
  EXPECT_EQ(crashes, 0);
  EXPECT_EQ(hangs, 0);
  std::remove(clean.c_str());
  std::remove(path.c_str());
}

}  // namespace
}  // namespace vaegail
