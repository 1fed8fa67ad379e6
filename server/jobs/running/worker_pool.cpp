#include "server/jobs/running/worker_pool.hpp"

#include <unistd.h>

#include <iostream>

namespace stoss::server::jobs {

namespace {

std::string process_name() {
  char host[256] = "host";
  gethostname(host, sizeof host - 1);
  return std::string(host) + ":" + std::to_string(getpid()) + ":" + JobId::random().str().substr(0, 8);
}

void warn(const std::string& what, const std::exception& e) {
  std::cerr << "stoss: " << what << ": " << e.what() << std::endl;
}

}  // namespace

void WorkerPool::Running::stop(Stop reason) {
  Stop expected = Stop::none;
  why.compare_exchange_strong(expected, reason);
  cancel = true;
}

WorkerPool::WorkerPool(JobStore& store, Executor& executor, WorkerPoolOptions options)
    : store_(store), executor_(executor), options_(options), name_(process_name()) {}

void WorkerPool::start() {
  for (int i = 0; i < options_.workers; ++i) threads_.emplace_back([this, i] { work(i); });
  lease_keeper_ = std::make_unique<Periodic>("lease keeper", std::chrono::milliseconds(options_.renew_every),
                                             [this] { renew_leases(); });
}

void WorkerPool::stop() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    for (auto& [id, running] : running_) running->stop(Stop::shutdown);
  }
  wake_.notify_all();
  for (auto& t : threads_)
    if (t.joinable()) t.join();
  threads_.clear();
  if (lease_keeper_) lease_keeper_->stop();
}

void WorkerPool::notify() {
  {
    std::lock_guard lock(mutex_);
    ++wakes_;
  }
  wake_.notify_all();
}

bool WorkerPool::cancel(const JobId& id) {
  std::lock_guard lock(mutex_);
  auto it = running_.find(id);
  if (it == running_.end()) return false;
  it->second->stop(Stop::user);
  return true;
}

int WorkerPool::running() const {
  std::lock_guard lock(mutex_);
  return static_cast<int>(running_.size());
}

std::optional<Job> WorkerPool::claim(const std::string& worker) {
  try {
    return store_.claim(worker, options_.lease, options_.ranks_per_job);
  } catch (const std::exception& e) {
    warn("claim", e);
    return std::nullopt;
  }
}

void WorkerPool::work(int index) {
  const std::string worker = name_ + "/" + std::to_string(index);
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    const std::uint64_t seen = wakes_;
    lock.unlock();
    std::optional<Job> job = claim(worker);
    if (job) run_claimed(*job);
    lock.lock();
    if (!job)
      wake_.wait_for(lock, std::chrono::milliseconds(options_.idle_poll),
                     [&] { return stopping_ || wakes_ != seen; });
  }
}

void WorkerPool::run_claimed(const Job& job) {
  auto running = std::make_shared<Running>(claim_of(job));
  {
    std::lock_guard lock(mutex_);
    running_[job.id] = running;
    if (stopping_) running->stop(Stop::shutdown);
  }
  auto progress = [this, running](const Progress& p) {
    try {
      if (!store_.progress(running->claim, p)) running->stop(Stop::lease_lost);
    } catch (const std::exception& e) {
      warn("progress of job " + running->claim.id.str(), e);
    }
  };
  const Outcome outcome = executor_.run(job, running->cancel, progress);
  report(*running, outcome);
  std::lock_guard lock(mutex_);
  running_.erase(job.id);
}

bool WorkerPool::stopping() const {
  std::lock_guard lock(mutex_);
  return stopping_;
}

void WorkerPool::report(const Running& running, const Outcome& outcome) {
  // A store that is away (a database restart, an outage longer than the lease) gets the report when it is
  // back, unless the lease was taken away meanwhile: then the attempt changes nothing, and the attempt
  // that replaced it adopts a completed run from this attempt's folder (InProcessExecutor).
  const std::string job = running.claim.id.str();
  for (bool warned = false;; std::this_thread::sleep_for(std::chrono::milliseconds(200))) {
    try {
      const Stop why = running.why.load();
      if (why == Stop::lease_lost) return;  // another attempt owns the job now
      if (why == Stop::shutdown && outcome.status == Status::canceled) {
        store_.release(running.claim);
        return;
      }
      store_.finish(running.claim, outcome);
      return;
    } catch (const StoreUnavailable& e) {
      if (stopping()) return warn("reporting job " + job + " (left for the next claim to adopt)", e);
      if (!warned) warn("reporting job " + job + " (retrying until the store is back)", e);
      warned = true;
    } catch (const std::exception& e) {
      return warn("reporting job " + job, e);  // the lease expires and the rescuer requeues it
    }
  }
}

void WorkerPool::renew_leases() {
  std::vector<std::shared_ptr<Running>> snapshot;
  {
    std::lock_guard lock(mutex_);
    for (auto& [id, running] : running_) snapshot.push_back(running);
  }
  for (auto& running : snapshot) {
    try {
      const Lease lease = store_.renew(running->claim, options_.lease);
      if (lease == Lease::lost) running->stop(Stop::lease_lost);
      if (lease == Lease::cancel_requested) running->stop(Stop::user);
    } catch (const std::exception& e) {
      warn("renewing the lease of job " + running->claim.id.str(), e);
    }
  }
}

}  // namespace stoss::server::jobs
