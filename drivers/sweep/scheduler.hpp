// SPDX-License-Identifier: BSD-3-Clause
// Chunks handed out dynamically over MPI. Rank 0 coordinates: it gives the next pending chunk
// to whichever rank asks (a worker's result is its request for more), runs chunks itself on
// a compute thread, and writes the results as they arrive, so ranks that finish early take
// more; results that arrive together are written together, with one sync to disk. Only rank 0's
// main thread calls MPI (MPI_THREAD_FUNNELED). Waits test a request with short sleeps, because Open
// MPI's blocking calls poll a core flat out, which a rank that mostly waits would take from the
// ranks that compute.
#pragma once

#include <mpi.h>

#include <atomic>
#include <chrono>
#include <climits>
#include <cstring>
#include <exception>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "sweep/progress.hpp"
#include "sweep/results.hpp"
#include "sweep/table.hpp"

namespace gencoord::sweep {

enum Tag : int {
  kRequest = 1,  // worker -> 0: give me a chunk (no data)
  kResult = 2,   // worker -> 0: a chunk's packed results, and give me another
  kAssign = 3,   // 0 -> worker: a chunk's index and its samples' rows, or -1: no more
};

/// The results of chunk `chunk`, whose samples' values are `rows` (row by row).
using ComputeChunk = std::function<ChunkResults(long long chunk, const double* rows)>;
using WriteChunks = std::function<void(const std::vector<ChunkResults>&)>;

inline void pause_briefly() { std::this_thread::sleep_for(std::chrono::microseconds(200)); }

inline void wait_gently(MPI_Request* request) {
  for (int done = 0;;) {
    MPI_Test(request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    pause_briefly();
  }
}

// The next message with `tag` from rank 0, waited for with short sleeps.
inline std::vector<char> receive_gently(MPI_Comm comm, int tag) {
  MPI_Status status;
  for (int arrived = 0; !arrived;) {
    MPI_Iprobe(0, tag, comm, &arrived, &status);
    if (!arrived) pause_briefly();
  }
  int bytes = 0;
  MPI_Get_count(&status, MPI_BYTE, &bytes);
  std::vector<char> buffer(static_cast<std::size_t>(bytes));
  MPI_Recv(buffer.data(), bytes, MPI_BYTE, 0, tag, comm, MPI_STATUS_IGNORE);
  return buffer;
}

/// A worker rank: asks rank 0 for chunks, computes each (its rows come with it) and sends
/// its results, until told that none are left.
inline void work(MPI_Comm comm, const Table& table, const ComputeChunk& compute) {
  MPI_Send(nullptr, 0, MPI_BYTE, 0, kRequest, comm);
  for (;;) {
    const std::vector<char> message = receive_gently(comm, kAssign);
    long long chunk = -1;
    if (message.size() < sizeof chunk) throw std::runtime_error("sweep: a short assignment");
    std::memcpy(&chunk, message.data(), sizeof chunk);
    if (chunk < 0) return;
    if (chunk >= table.chunks()) throw std::runtime_error("sweep: an assignment of no chunk");
    std::vector<double> rows(static_cast<std::size_t>(table.chunk_size(chunk)) *
                             table.columns.size());
    if (message.size() != sizeof chunk + rows.size() * sizeof(double))
      throw std::runtime_error("sweep: an assignment of the wrong size");
    std::memcpy(rows.data(), message.data() + sizeof chunk, rows.size() * sizeof(double));
    const std::vector<char> bytes = pack(compute(chunk, rows.data()));
    if (bytes.size() > static_cast<std::size_t>(INT_MAX))
      throw std::runtime_error("a chunk's results exceed 2 GB; give the sweep a smaller chunk");
    MPI_Request sent;
    MPI_Isend(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, 0, kResult, comm, &sent);
    wait_gently(&sent);
  }
}

/// Rank 0: runs the `pending` chunks of `table` (in that order of hand-out) on every rank,
/// sending each chunk's rows with it, and on its own compute thread, and writes the results with
/// `write` as they arrive: every result that has arrived at once, in one call (one sync to disk for
/// all of them), after each worker that sent one has its next chunk. Returns when every chunk is
/// written and every worker has been told to stop. \throws what `write` or `compute` throw, after
/// its compute thread has finished its chunk.
inline void coordinate(MPI_Comm comm, const Table& table, const std::vector<long long>& pending,
                       const Layout& layout, const ComputeChunk& compute, const WriteChunks& write,
                       Progress* progress) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::mutex mutex;  // guards next, local_results and local_error
  std::size_t next = 0;
  std::vector<ChunkResults> local_results;
  std::exception_ptr local_error;
  std::atomic<bool> local_done{false};
  auto take = [&] {
    const std::lock_guard<std::mutex> lock(mutex);
    return next < pending.size() ? pending[next++] : -1LL;
  };
  std::thread local([&] {
    try {
      for (long long c = take(); c >= 0; c = take()) {
        ChunkResults r = compute(c, table.row(table.chunk_begin(c)));
        const std::lock_guard<std::mutex> lock(mutex);
        local_results.push_back(std::move(r));
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(mutex);
      local_error = std::current_exception();
    }
    local_done = true;
  });
  int workers = size - 1;        // not yet told to stop
  auto assign = [&](int rank) {  // the next chunk's index and rows, or -1
    const long long chunk = take();
    std::vector<char> message(sizeof chunk);
    std::memcpy(message.data(), &chunk, sizeof chunk);
    if (chunk >= 0) {
      const auto* rows = reinterpret_cast<const char*>(table.row(table.chunk_begin(chunk)));
      message.insert(message.end(), rows,
                     rows + table.chunk_size(chunk) *
                                static_cast<long long>(table.columns.size() * sizeof(double)));
    }
    MPI_Send(message.data(), static_cast<int>(message.size()), MPI_BYTE, rank, kAssign, comm);
    if (chunk < 0) --workers;
  };
  try {
    for (bool computing = true; computing || workers > 0;) {
      std::vector<ChunkResults> batch;
      // every message that has arrived; its sender gets its next chunk before the writes
      for (int arrived = 1; arrived;) {
        MPI_Status status;
        MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm, &arrived, &status);
        if (!arrived) break;
        int bytes = 0;
        MPI_Get_count(&status, MPI_BYTE, &bytes);
        std::vector<char> buffer(static_cast<std::size_t>(bytes));
        MPI_Recv(buffer.data(), bytes, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, comm,
                 MPI_STATUS_IGNORE);
        assign(status.MPI_SOURCE);
        if (status.MPI_TAG == kResult) batch.push_back(unpack(buffer, layout, table.chunk));
      }
      const bool finished = computing && local_done.load();  // before draining: none after
      {
        const std::lock_guard<std::mutex> lock(mutex);
        for (ChunkResults& r : local_results) batch.push_back(std::move(r));
        local_results.clear();
      }
      if (!batch.empty()) {
        write(batch);
        for (const ChunkResults& r : batch) progress->add(r.count);
      }
      if (finished) {
        local.join();
        computing = false;
        if (local_error) std::rethrow_exception(local_error);
      }
      progress->show();
      if (batch.empty()) pause_briefly();
    }
  } catch (...) {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      next = pending.size();  // hand out nothing more
    }
    if (local.joinable()) local.join();
    throw;
  }
}

}  // namespace gencoord::sweep
