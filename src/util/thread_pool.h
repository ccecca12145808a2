// A fixed pool of worker threads for data-parallel loops (environment steps, rollouts).
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace vaegail {

class ThreadPool {
 public:
  // num_threads <= 1 runs everything on the calling thread.
  explicit ThreadPool(int num_threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return num_threads_; }

  // Calls fn(i) for i in [0, count), splitting the range into contiguous blocks, one per
  // thread (the calling thread takes the first). Returns when all calls are done; the first
  // exception thrown by fn is rethrown here.
  void parallel_for(int count, const std::function<void(int)>& fn);

 private:
  void worker_loop(int worker);
  void run_block(int block);

  int num_threads_;
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, finished_;
  const std::function<void(int)>* job_ = nullptr;
  int job_count_ = 0;
  long generation_ = 0;
  int pending_ = 0;
  bool stopping_ = false;
  std::exception_ptr error_;
};

}  // namespace vaegail
