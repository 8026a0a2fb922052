#include "mocapdb/core/parallel_tasks.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace mocapdb {

std::size_t worker_count(std::size_t tasks) {
    const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
    return std::max<std::size_t>(1, std::min(tasks, cores));
}

void run_parallel_tasks(std::size_t tasks, const std::function<void(std::size_t)>& task) {
    const std::size_t workers = worker_count(tasks);
    if (workers < 2) {
        for (std::size_t i = 0; i < tasks; ++i) task(i);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr first;
    std::mutex first_mutex;
    const auto work = [&]() {
        for (std::size_t i = next++; i < tasks && !failed; i = next++) {
            try {
                task(i);
            } catch (...) {
                const std::lock_guard<std::mutex> lock(first_mutex);
                if (!first) first = std::current_exception();
                failed = true;
            }
        }
    };
    std::vector<std::thread> others;
    others.reserve(workers - 1);
    for (std::size_t w = 1; w < workers; ++w) others.emplace_back(work);
    work();
    for (std::thread& t : others) t.join();
    if (first) std::rethrow_exception(first);
}

}  // namespace mocapdb
