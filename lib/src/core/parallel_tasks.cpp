#include "mocapdb/core/parallel_tasks.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <limits>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace mocapdb {

std::size_t worker_count(std::size_t tasks) {
    const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
    return std::max<std::size_t>(1, std::min(tasks, cores));
}

void run_on_workers(std::size_t workers, std::size_t tasks, const std::function<void(std::size_t, std::size_t)>& task) {
    workers = std::max<std::size_t>(1, std::min(workers, tasks));
    if (workers < 2) {
        for (std::size_t i = 0; i < tasks; ++i) task(i, 0);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::size_t failed_task = std::numeric_limits<std::size_t>::max();
    std::exception_ptr failure;
    std::mutex failure_mutex;
    const auto work = [&](std::size_t w) {
        for (std::size_t i; !failed.load() && (i = next++) < tasks;) {
            try {
                task(i, w);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(failure_mutex);
                if (i < failed_task) {
                    failed_task = i;
                    failure = std::current_exception();
                }
                failed = true;
            }
        }
    };
    std::vector<std::thread> others;
    others.reserve(workers - 1);
    for (std::size_t w = 1; w < workers; ++w) {
        try {
            others.emplace_back(work, w);
        } catch (const std::system_error&) {
            break;  // no more threads: the started workers and this one take every task
        }
    }
    work(0);
    for (std::thread& t : others) t.join();
    if (failure) std::rethrow_exception(failure);
}

void run_parallel_tasks(std::size_t tasks, const std::function<void(std::size_t)>& task) {
    run_on_workers(worker_count(tasks), tasks, [&task](std::size_t i, std::size_t) { task(i); });
}

}  // namespace mocapdb
