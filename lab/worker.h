// lab/worker.h — the live lab's render thread: one thread runs every GL job,
// one at a time, on contexts it alone makes current. Jobs arrive in lanes (the page's panels:
// "a", "b", ...); a lane holds at most one waiting job, so a new job in a lane drops the one
// waiting there (latest request wins: while a slider moves, stale frames are never rendered).
#pragma once

#include <condition_variable>
#include <functional>
#include <future>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace sl::lab {

// What became of a job.
struct JobResult {
  enum class Status { kDone, kSuperseded, kBusy, kStopped };
  Status status = Status::kDone;
  int httpStatus = 200;
  std::string contentType;
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;  // extra response headers
};

class Worker {
 public:
  // A job runs on the worker thread and answers with a JobResult.
  using Job = std::function<JobResult()>;

  // `maxLanes`: lanes with a waiting job at once; a job for yet another lane is refused (kBusy).
  explicit Worker(int maxLanes);
  ~Worker();  // stops: waiting jobs answer kStopped, the running one finishes first
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;

  // Queues `job` in `lane`, replacing (and answering kSuperseded) a job waiting there. The
  // future is ready when the job ran, was dropped, refused or the worker stopped.
  std::future<JobResult> submit(const std::string& lane, Job job);

  // Runs `job` on the worker thread ahead of any lane (loading the scenes for /api/scenes)
  // and waits for it.
  JobResult runNow(Job job);

 private:
  struct Pending {
    unsigned long long sequence = 0;
    Job job;
    std::promise<JobResult> promise;
  };
  void loop();

  const int maxLanes_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::map<std::string, Pending> lanes_;  // at most one waiting job per lane
  unsigned long long sequence_ = 0;
  bool stopping_ = false;
  std::thread thread_;
};

}  // namespace sl::lab
