#include "lab/worker.h"

#include <exception>

namespace sl::lab {

namespace {
const std::string kPriorityLane = "\x01start-up";  // not a name the API accepts
JobResult statusOnly(JobResult::Status status, int http, const std::string& text) {
  JobResult r;
  r.status = status;
  r.httpStatus = http;
  r.contentType = "text/plain";
  r.body = text;
  return r;
}
}  // namespace

Worker::Worker(int maxLanes) : maxLanes_(maxLanes), thread_([this] { loop(); }) {}

Worker::~Worker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  thread_.join();
  for (auto& [lane, pending] : lanes_)
    pending.promise.set_value(
        statusOnly(JobResult::Status::kStopped, 503, "the lab is shutting down"));
}

std::future<JobResult> Worker::submit(const std::string& lane, Job job) {
  std::promise<JobResult> promise;
  std::future<JobResult> future = promise.get_future();
  std::lock_guard<std::mutex> lock(mutex_);
  if (stopping_) {
    promise.set_value(statusOnly(JobResult::Status::kStopped, 503, "the lab is shutting down"));
    return future;
  }
  auto it = lanes_.find(lane);
  if (it != lanes_.end()) {
    // Latest request wins: the waiting job of this lane is dropped, not queued.
    it->second.promise.set_value(statusOnly(JobResult::Status::kSuperseded, 409,
                                            "superseded by a newer request in lane " + lane));
    it->second.job = std::move(job);
    it->second.promise = std::move(promise);
    it->second.sequence = ++sequence_;
  } else {
    if (lane != kPriorityLane && int(lanes_.size()) >= maxLanes_) {
      promise.set_value(statusOnly(
          JobResult::Status::kBusy, 503,
          "the lab is busy: " + std::to_string(maxLanes_) + " lanes are waiting already"));
      return future;
    }
    Pending& p = lanes_[lane];
    p.job = std::move(job);
    p.promise = std::move(promise);
    p.sequence = lane == kPriorityLane ? 0 : ++sequence_;
  }
  wake_.notify_all();
  return future;
}

JobResult Worker::runNow(Job job) { return submit(kPriorityLane, std::move(job)).get(); }

void Worker::loop() {
  for (;;) {
    Pending next;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stopping_ || !lanes_.empty(); });
      if (stopping_) return;
      auto oldest = lanes_.begin();
      for (auto it = lanes_.begin(); it != lanes_.end(); ++it)
        if (it->second.sequence < oldest->second.sequence) oldest = it;
      next = std::move(oldest->second);
      lanes_.erase(oldest);
    }
    JobResult result;
    try {
      result = next.job();
    } catch (const std::exception& e) {
      result = statusOnly(JobResult::Status::kDone, 500, e.what());
    }
    next.promise.set_value(std::move(result));
  }
}

}  // namespace sl::lab
