#include "MpiDistributor.h"

#include <weft/core/Error.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <mutex>
#include <thread>

namespace weft {
namespace {

constexpr int kReportTag = 1;  // worker -> rank 0: the finished item's result (or none), a request
constexpr int kAssignTag = 2;  // rank 0 -> worker: the next item, or -1 for none

// Waits for `request` without MPI's busy polling: a few quick tests, then sleeps growing to 1 ms
// (an item takes seconds to hours; a millisecond of latency per hand-out is the price).
void waitPolitely(MPI_Request& request, MPI_Status* status = MPI_STATUS_IGNORE) {
  int done = 0;
  auto pause = std::chrono::microseconds(20);
  for (int tests = 0;; ++tests) {
    MPI_Test(&request, &done, status);
    if (done) return;
    if (tests > 50) {
      std::this_thread::sleep_for(pause);
      pause = std::min(pause * 2, std::chrono::microseconds(1000));
    }
  }
}

void append(std::string& out, const void* bytes, std::size_t n) {
  out.append(static_cast<const char*>(bytes), n);
}
void appendString(std::string& out, const std::string& s) {
  const std::uint64_t n = s.size();
  append(out, &n, sizeof n);
  out += s;
}

// Item index, then the result: ok, exit code, rank, data, message.
std::string encode(std::int64_t item, const WorkItemResult& r) {
  std::string out;
  append(out, &item, sizeof item);
  const std::uint8_t ok = r.ok ? 1 : 0;
  const std::int32_t code = r.exitCode, rank = r.rank;
  append(out, &ok, 1);
  append(out, &code, sizeof code);
  append(out, &rank, sizeof rank);
  appendString(out, r.data);
  appendString(out, r.message);
  appendString(out, r.detail);
  return out;
}

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  T read() {
    T v;
    need(sizeof v);
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  std::string readString() {
    const auto n = static_cast<std::size_t>(read<std::uint64_t>());
    need(n);
    std::string s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - at_ < n) throw std::runtime_error("MPI: truncated work item message");
  }
  const std::string& bytes_;
  std::size_t at_ = 0;
};

std::int64_t decode(Reader& in, WorkItemResult& r) {
  const auto item = in.read<std::int64_t>();
  r.ok = in.read<std::uint8_t>() != 0;
  r.exitCode = in.read<std::int32_t>();
  r.rank = in.read<std::int32_t>();
  r.data = in.readString();
  r.message = in.readString();
  r.detail = in.readString();
  return item;
}

}  // namespace

MpiDistributor::MpiDistributor() {
  MPI_Comm_dup(MPI_COMM_WORLD, &comm_);
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

MpiDistributor::~MpiDistributor() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && comm_ != MPI_COMM_NULL) MPI_Comm_free(&comm_);
}

std::string MpiDistributor::description() const {
  return "MPI, " + std::to_string(size_) + (size_ == 1 ? " rank" : " ranks");
}

std::vector<WorkItemResult> MpiDistributor::map(std::size_t count, const Work& work) {
  std::vector<WorkItemResult> results;
  if (rank_ == 0)
    results = mapOnRoot(count, work);
  else
    mapOnWorker(work);
  shareResults(results, count);
  return results;
}

std::vector<WorkItemResult> MpiDistributor::mapOnRoot(std::size_t count, const Work& work) {
  std::vector<WorkItemResult> results(count);
  std::atomic<std::size_t> next{0};
  std::mutex resultsMutex;
  std::exception_ptr dispatchFailure;
  // The dispatcher: the only thread of rank 0 calling MPI while items run (MPI_THREAD_SERIALIZED).
  std::thread dispatcher([&] {
    try {
      int finished = 0;  // workers told there is nothing left
      auto pause = std::chrono::microseconds(20);
      while (finished < size_ - 1) {
        int flag = 0;
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, kReportTag, comm_, &flag, &status);
        if (!flag) {
          std::this_thread::sleep_for(pause);
          pause = std::min(pause * 2, std::chrono::microseconds(1000));
          continue;
        }
        pause = std::chrono::microseconds(20);
        int bytes = 0;
        MPI_Get_count(&status, MPI_BYTE, &bytes);
        std::string message(static_cast<std::size_t>(bytes), '\0');
        MPI_Recv(message.data(), bytes, MPI_BYTE, status.MPI_SOURCE, kReportTag, comm_,
                 MPI_STATUS_IGNORE);
        Reader in(message);
        WorkItemResult r;
        const std::int64_t item = decode(in, r);
        if (item >= 0) {
          const std::lock_guard<std::mutex> lock(resultsMutex);
          results[static_cast<std::size_t>(item)] = std::move(r);
        }
        const std::size_t take = next++;
        const std::int64_t assign = take < count ? static_cast<std::int64_t>(take) : -1;
        if (assign < 0) ++finished;
        MPI_Send(&assign, 1, MPI_INT64_T, status.MPI_SOURCE, kAssignTag, comm_);
      }
    } catch (...) {
      dispatchFailure = std::current_exception();
    }
  });
  for (std::size_t i = next++; i < count; i = next++) {
    WorkItemResult r = runWorkItem(work, i, 0);
    const std::lock_guard<std::mutex> lock(resultsMutex);
    results[i] = std::move(r);
  }
  dispatcher.join();
  if (dispatchFailure) std::rethrow_exception(dispatchFailure);
  return results;
}

void MpiDistributor::mapOnWorker(const Work& work) {
  std::int64_t done = -1;
  WorkItemResult result;
  for (;;) {
    const std::string report = encode(done, result);
    MPI_Send(report.data(), static_cast<int>(report.size()), MPI_BYTE, 0, kReportTag, comm_);
    std::int64_t item = -1;
    MPI_Request request;
    MPI_Irecv(&item, 1, MPI_INT64_T, 0, kAssignTag, comm_, &request);
    waitPolitely(request);
    if (item < 0) return;
    result = runWorkItem(work, static_cast<std::size_t>(item), rank_);
    done = item;
  }
}

void MpiDistributor::shareResults(std::vector<WorkItemResult>& results, std::size_t count) {
  std::string blob;
  if (rank_ == 0)
    for (std::size_t i = 0; i < count; ++i)
      blob += encode(static_cast<std::int64_t>(i), results[i]);
  std::uint64_t size = blob.size();
  MPI_Request request;
  MPI_Ibcast(&size, 1, MPI_UINT64_T, 0, comm_, &request);
  waitPolitely(request);
  blob.resize(size);
  // MPI counts are ints: the blob goes in chunks below 2 GiB.
  constexpr std::uint64_t kChunk = 1u << 30;
  for (std::uint64_t at = 0; at < size; at += kChunk) {
    MPI_Ibcast(blob.data() + at, static_cast<int>(std::min(kChunk, size - at)), MPI_BYTE, 0, comm_,
               &request);
    waitPolitely(request);
  }
  if (rank_ == 0) return;
  results.assign(count, WorkItemResult{});
  Reader in(blob);
  for (std::size_t i = 0; i < count; ++i) {
    WorkItemResult r;
    const std::int64_t item = decode(in, r);
    results[static_cast<std::size_t>(item)] = std::move(r);
  }
}

void MpiDistributor::rootFirst(const std::function<void()>& step) {
  std::int32_t code = 0;
  std::exception_ptr failure;
  if (rank_ == 0) {
    const WorkItemResult r = runWorkItem(
        [&](std::size_t) {
          try {
            step();
          } catch (...) {
            failure = std::current_exception();
            throw;
          }
          return std::string();
        },
        0, 0);
    code = r.ok ? 0 : r.exitCode;
  }
  MPI_Request request;
  MPI_Ibcast(&code, 1, MPI_INT32_T, 0, comm_, &request);
  waitPolitely(request);
  if (failure) std::rethrow_exception(failure);
  if (code != 0) throw QuietExit{code};
  if (rank_ != 0) step();
  // Nobody goes on until every rank has run the step (rank 0 would otherwise change what the
  // others are still reading).
  MPI_Ibarrier(comm_, &request);
  waitPolitely(request);
}

}  // namespace weft
