#include "util/thread_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

namespace vaegail {
namespace {

TEST(ThreadPool, VisitsEveryIndexOnceForAnyThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    ThreadPool pool(threads);
    for (int count : {0, 1, 5, 64}) {
      std::vector<std::atomic<int>> hits(count);
      pool.parallel_for(count, [&](int i) { ++hits[i]; });
      for (int i = 0; i < count; ++i) EXPECT_EQ(hits[i].load(), 1) << threads << " threads, count " << count;
    }
  }
}

TEST(ThreadPool, RethrowsAnExceptionFromAWorker) {
  ThreadPool pool(3);
  EXPECT_THROW(pool.parallel_for(9, [](int i) { if (i == 7) throw std::runtime_error("boom"); }),
               std::runtime_error);
  int sum = 0;  // the pool stays usable afterwards
  pool.parallel_for(1, [&](int) { sum = 1; });
  EXPECT_EQ(sum, 1);
}

}  // namespace
}  // namespace vaegail
