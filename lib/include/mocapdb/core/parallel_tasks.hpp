#pragma once
// Running independent tasks on worker threads (the compress rank search, packing, GP fits). Plain
// std::thread workers that take the next task index in order; no pool lives between
// calls. An exception in any worker is carried to the caller: the one of the lowest task index that
// threw, which is the one a single thread would have thrown (tasks are handed out in index order, so
// every task before it was started and ran to its end).
#include <cstddef>
#include <functional>

namespace mocapdb {

/// Worker threads for `tasks` tasks: min(tasks, std::thread::hardware_concurrency()), at least 1.
std::size_t worker_count(std::size_t tasks);

/// Calls task(i, w) once for every i in [0, tasks), from min(workers, tasks) threads (w in [0,
/// workers) names the calling worker, for per-worker state; the calling thread is worker 0); returns
/// when every call has returned. Tasks start in increasing i; they must be safe to run concurrently.
/// After a task throws, no further task starts; the exception of the lowest i that threw is rethrown
/// here once every worker has stopped. A thread that cannot be started leaves its share to the others.
void run_on_workers(std::size_t workers, std::size_t tasks, const std::function<void(std::size_t, std::size_t)>& task);

/// run_on_workers(worker_count(tasks), tasks, ...) for tasks that need no per-worker state.
void run_parallel_tasks(std::size_t tasks, const std::function<void(std::size_t)>& task);

}  // namespace mocapdb
