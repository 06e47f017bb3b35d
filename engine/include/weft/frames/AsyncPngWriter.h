#pragma once
// Encodes and writes PNG frames on background threads while the next frame renders: PNG
// encoding costs more than drawing a frame, and the two overlap well on two cores.

#include <weft/render/Image.h>

#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace weft {

class AsyncPngWriter {
 public:
  // `threads` encoders; write() blocks while `maxQueued` images wait, bounding memory.
  explicit AsyncPngWriter(int threads, int maxQueued = 4);
  ~AsyncPngWriter();  // waits for the encoders; errors not yet collected by finish() are dropped
  AsyncPngWriter(const AsyncPngWriter&) = delete;
  AsyncPngWriter& operator=(const AsyncPngWriter&) = delete;

  // Queues an image; rethrows (once) the first error an encoder met.
  void write(std::string path, render::Image image);
  // Waits until everything queued is written; rethrows the first error.
  void finish();

 private:
  void work();
  void rethrow();
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::pair<std::string, render::Image>> queue_;
  std::vector<std::thread> threads_;
  std::size_t maxQueued_;
  int busy_ = 0;
  bool stopping_ = false;
  std::exception_ptr error_;
};

}  // namespace weft
