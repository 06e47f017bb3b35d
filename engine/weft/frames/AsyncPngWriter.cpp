#include <weft/frames/AsyncPngWriter.h>

#include <algorithm>

namespace weft {

AsyncPngWriter::AsyncPngWriter(int threads, int maxQueued)
    : maxQueued_(std::size_t(std::max(1, maxQueued))) {
  for (int i = 0; i < std::max(1, threads); ++i) threads_.emplace_back([this] { work(); });
}

AsyncPngWriter::~AsyncPngWriter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  for (std::thread& t : threads_) t.join();
}

void AsyncPngWriter::rethrow() {
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    queue_.clear();
    std::rethrow_exception(e);
  }
}

void AsyncPngWriter::write(std::string path, render::Image image) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < maxQueued_ || error_; });
  rethrow();
  queue_.emplace_back(std::move(path), std::move(image));
  lock.unlock();
  changed_.notify_all();
}

void AsyncPngWriter::finish() {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return (queue_.empty() && busy_ == 0) || error_; });
  changed_.wait(lock, [&] { return busy_ == 0; });  // no encoder still holds a file open
  rethrow();
}

void AsyncPngWriter::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return !queue_.empty() || stopping_; });
    if (queue_.empty()) return;  // stopping with nothing left
    auto job = std::move(queue_.front());
    queue_.pop_front();
    ++busy_;
    lock.unlock();
    changed_.notify_all();  // room in the queue
    std::exception_ptr failure;
    try {
      render::writePng(job.first, job.second);
    } catch (...) {
      failure = std::current_exception();
    }
    lock.lock();
    --busy_;
    if (failure && !error_) error_ = failure;
    changed_.notify_all();
  }
}

}  // namespace weft
