// Per-pixel work of the accuracy measurement spread over the machine's cores (issue 32: an
// evaluation should cost little beside its trace). Work is cut into fixed chunks whose results
// the caller combines in chunk order, so sums come out bit for bit the same on any core count.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace shadowlab {

// Calls work(chunk, begin, end) for every chunk [begin, end) of [0, count) in pieces of
// `chunkSize` (the last may be shorter), on up to hardware_concurrency threads; returns when all
// are done. Chunks run in any order and at the same time: work must only write what its chunk
// owns. An exception thrown by work is rethrown here after the other threads finished.
template <typename Work>
void forEachChunk(size_t count, size_t chunkSize, Work&& work) {
    chunkSize = std::max<size_t>(chunkSize, 1);
    const size_t chunks = (count + chunkSize - 1) / chunkSize;
    if (chunks == 0) return;
    const size_t threads = std::min<size_t>(chunks, std::clamp<size_t>(std::thread::hardware_concurrency(), 1, 64));
    std::atomic<size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    auto run = [&] {
        for (size_t chunk = next++; chunk < chunks; chunk = next++) {
            try {
                work(chunk, chunk * chunkSize, std::min(count, (chunk + 1) * chunkSize));
            } catch (...) {
                const std::lock_guard<std::mutex> lock(failureMutex);
                if (!failure) failure = std::current_exception();
            }
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(run);
    run();
    for (std::thread& thread : pool) thread.join();
    if (failure) std::rethrow_exception(failure);
}

// The number of chunks forEachChunk cuts `count` into: the size of a per-chunk results array.
inline size_t chunkCount(size_t count, size_t chunkSize) {
    chunkSize = std::max<size_t>(chunkSize, 1);
    return (count + chunkSize - 1) / chunkSize;
}

} // namespace shadowlab
