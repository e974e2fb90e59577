// SPDX-License-Identifier: MIT
#pragma once
// Independent host-side jobs 0 .. count-1 (several logs of one identification, Monte Carlo runs) on up to
// `threads` threads, the calling thread among them. Each job writes its result at its own index and each
// job's exception is kept at its index: the caller reports the first failure by index whatever the
// scheduling, so neither results nor errors depend on the thread count. Not for lib/ or the firmware
// (threads and heap).
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace jacobid {

struct ParallelForOptions {
    int threads = 1;               // at most this many threads (fewer when there are fewer jobs)
    bool stop_on_failure = true;   // no job starts after one has failed (the ones running finish)
    // Called after each job, serialized, with the count finished so far; an exception it throws is ignored
    // (it must not end a worker thread).
    std::function<void(std::size_t finished, std::size_t count)> progress;
};

// Runs job(k) for every k in [0, count); returns each job's exception (null where it succeeded or was not
// started after a failure; `started` tells which ran when given).
inline std::vector<std::exception_ptr> parallel_for(std::size_t count, const ParallelForOptions& options,
                                                    const std::function<void(std::size_t)>& job, std::vector<bool>* started = nullptr) {
    std::vector<std::exception_ptr> errors(count);
    std::vector<char> ran(count, 0);
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex progress_mutex;
    std::size_t finished = 0;
    auto worker = [&] {
        for (std::size_t k = next++; k < count && !(options.stop_on_failure && failed); k = next++) {
            ran[k] = 1;
            try {
                job(k);
            } catch (...) {
                errors[k] = std::current_exception();
                failed = true;
            }
            const std::lock_guard<std::mutex> lock(progress_mutex);
            ++finished;
            try {
                if (options.progress) options.progress(finished, count);
            } catch (...) {
            }
        }
    };
    const std::size_t wanted = std::min<std::size_t>(count, static_cast<std::size_t>(std::max(1, options.threads)));
    std::vector<std::thread> pool;
    try {
        for (std::size_t t = 1; t < wanted; ++t) pool.emplace_back(worker);
    } catch (const std::system_error&) {
        // Fewer threads than asked (the system refused one): the started ones and this one do the jobs.
    }
    worker();
    for (auto& t : pool) t.join();
    if (started) started->assign(ran.begin(), ran.end());
    return errors;
}

}  // namespace jacobid
