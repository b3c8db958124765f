// Worker threads for metrics and image writes, so they never sit on the timed path.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace cbr::harness {

class WorkerPool {
public:
    explicit WorkerPool(unsigned threads);
    ~WorkerPool();  // waits for every job
    void submit(std::function<void()> job);
    void wait();    // until the queue is empty and no job runs
    void waitUntilAtMost(size_t jobs);  // until at most `jobs` are queued or running
    size_t pending();

private:
    void loop();
    std::mutex mutex_;
    std::condition_variable wake_, idle_;
    std::deque<std::function<void()>> jobs_;
    std::vector<std::thread> threads_;
    size_t running_ = 0;
    bool stop_ = false;
};

}  // namespace cbr::harness
