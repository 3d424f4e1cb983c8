// The threads kintsugi may use, as the user asked: the environment's KINTSUGI_THREADS.
#pragma once

#include <exception>
#include <functional>
#include <thread>
#include <utility>

namespace kintsugi {

// KINTSUGI_THREADS when it is a whole number from 1 to 64, else the machine's hardware
// threads (at most 8; at least 1). Read on each call: cheap next to the work it sizes.
int threads_from_environment();

// Runs `work` on a thread of its own when `apart`, else at once on this one; join() waits
// for it and passes on what it threw. Joined on destruction too, so that an exception on
// this thread never leaves the other running on freed state. For two independent halves
// of one job (what the other thread writes, this one must not touch before join()).
class OtherThread {
 public:
  OtherThread(const std::function<void()>& work, bool apart) {
    if (!apart) {
      work();
      return;
    }
    thread_ = std::thread([this, work] {
      try {
        work();
      } catch (...) {
        thrown_ = std::current_exception();
      }
    });
  }
  OtherThread(const OtherThread&) = delete;
  OtherThread& operator=(const OtherThread&) = delete;
  ~OtherThread() {
    if (thread_.joinable()) thread_.join();
  }
  void join() {
    if (thread_.joinable()) thread_.join();
    if (thrown_) std::rethrow_exception(std::exchange(thrown_, nullptr));
  }

 private:
  std::thread thread_;
  std::exception_ptr thrown_;
};

}  // namespace kintsugi
