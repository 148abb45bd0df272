// SPDX-License-Identifier: BSD-3-Clause
// Batched evaluation: qddot or one integrator step for many states (and parameter sets) at
// once, or any work per index (batch_for_each()), spread over threads.
//
// A static partition: the batch is cut into `threads` contiguous chunks of nearly equal size,
// one per thread (the calling thread takes the first); batch_for_each() instead hands out
// indices one at a time, for elements of very different cost. Each output element is
// computed by exactly the code the serial path runs, so results equal the serial ones bit for
// bit whatever the thread count. The threads are the shared WorkerPool's (worker_pool.hpp),
// so a batch costs a wake-up, not a thread start; more threads than the machine has are
// started per call.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/parallel/worker_pool.hpp"

namespace gencoord {

/// The default thread count of the batch functions: std::thread::hardware_concurrency(), or 1
/// when the platform cannot tell.
inline int default_batch_threads() {
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

namespace detail {

// parameters of element i: one set shared by the whole batch, or one per state
template <class P>
const P& batch_params(const std::vector<P>& params, std::size_t i) {
  return params.size() == 1 ? params[0] : params[i];
}

inline void check_batch_threads(int threads) {
  if (threads < 1)
    throw std::invalid_argument("gencoord: batch thread count must be at least 1, got " +
                                std::to_string(threads));
}

template <class P>
void check_batch_sizes(std::size_t num_states, const std::vector<P>& params, int threads) {
  if (params.size() != 1 && params.size() != num_states)
    throw std::invalid_argument("gencoord: batch needs 1 parameter set or one per state (" +
                                std::to_string(num_states) + "), got " +
                                std::to_string(params.size()));
  check_batch_threads(threads);
}

// Runs task(0) ... task(tasks - 1) concurrently: on the shared worker pool when it has enough
// threads, else on threads started for this call. An exception thrown by a task is rethrown
// here after every task has finished; with several, the one from the lowest task, so which
// error is reported does not depend on timing.
template <class Task>
void run_tasks(std::size_t tasks, const Task& task) {
  std::vector<std::exception_ptr> errors(tasks);
  const std::function<void(std::size_t)> run = [&](std::size_t c) {
    try {
      task(c);
    } catch (...) {
      errors[c] = std::current_exception();
    }
  };
  WorkerPool& pool = shared_worker_pool();
  if (tasks == 1) {
    run(0);
  } else if (static_cast<int>(tasks) <= pool.threads()) {
    pool.run(tasks, run);
  } else {
    std::vector<std::thread> workers;
    workers.reserve(tasks - 1);
    for (std::size_t c = 1; c < tasks; ++c) workers.emplace_back(run, c);
    run(0);
    for (auto& worker : workers) worker.join();
  }
  for (const auto& error : errors)
    if (error) std::rethrow_exception(error);
}

// Calls body(begin, end) on `threads` contiguous chunks of [0, count), concurrently
// (run_tasks()).
template <class Body>
void parallel_chunks(std::size_t count, int threads, const Body& body) {
  const std::size_t chunks =
      std::min<std::size_t>(static_cast<std::size_t>(threads), std::max<std::size_t>(count, 1));
  // chunk c is [c * count / chunks, (c + 1) * count / chunks): sizes differ by at most 1
  run_tasks(chunks, [&](std::size_t c) { body(c * count / chunks, (c + 1) * count / chunks); });
}

}  // namespace detail

/// Generalized accelerations of many states: (*out)[i] = acceleration<M>(params[i], states[i]).
/// \param[in]  states   The states (t, q of dim M::nq, v of dim nv_of_v<M>).
/// \param[in]  params   One parameter set for every state, or one per state.
/// \param[out] out      Resized to states.size() and filled; not null.
/// \param[in]  threads  Threads to use, at least 1 (the caller's thread counts as one).
/// \throws std::invalid_argument on mismatched sizes or threads < 1; DynamicsError as
///         acceleration() (the first failing chunk's), after all threads have finished.
template <class M>
void batch_qddot(const std::vector<State<M>>& states, const std::vector<ParamsOf<M>>& params,
                 std::vector<VVec<M>>* out, int threads = default_batch_threads()) {
  static_assert(assert_model_v<M>);
  detail::check_batch_sizes(states.size(), params, threads);
  out->resize(states.size());
  detail::parallel_chunks(states.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      (*out)[i] = acceleration<M>(detail::batch_params(params, i), states[i]);
  });
}

/// One step of size dt of `integrator` from each state: (*out)[i] = step(ReducedSystem<M>(p_i),
/// integrator, states[i], dt).
/// \param[in]  integrator  Which integrator (implicit ones use default NewtonOptions).
/// \param[in]  params      One parameter set for every state, or one per state.
/// \param[in]  states      The states at the start of the step.
/// \param[in]  dt          The step size; positive and finite.
/// \param[out] out         Resized to states.size() and filled; may be &states (in place).
/// \param[in]  threads     Threads to use, at least 1.
/// \throws as batch_qddot(), and StepSizeError or NewtonError as step().
template <class M>
void batch_step(Integrator integrator, const std::vector<ParamsOf<M>>& params,
                const std::vector<State<M>>& states, double dt, std::vector<State<M>>* out,
                int threads = default_batch_threads()) {
  static_assert(assert_model_v<M>);
  detail::check_batch_sizes(states.size(), params, threads);
  out->resize(states.size());
  detail::parallel_chunks(states.size(), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      (*out)[i] =
          step(ReducedSystem<M>(detail::batch_params(params, i)), integrator, states[i], dt);
  });
}

/// Calls body(i) for every i in [0, count) on `threads` threads, handing out the indices one
/// at a time to whichever thread is free: elements that take very different times (runs
/// that stop at an event, say) keep every thread busy to the end. Which thread runs body(i)
/// changes nothing when body(i) depends on i alone, so results stored per index equal the
/// serial ones bit for bit whatever the thread count.
/// \param[in] count    The number of elements.
/// \param[in] threads  Threads to use, at least 1 (the caller's thread counts as one).
/// \param[in] body     Callable as body(std::size_t i), concurrently for different i.
/// \throws std::invalid_argument for threads < 1; an exception of body(i) after every index
///         has run; with several, the one of the lowest index.
template <class Body>
void batch_for_each(std::size_t count, int threads, const Body& body) {
  detail::check_batch_threads(threads);
  const std::size_t tasks = std::min<std::size_t>(static_cast<std::size_t>(threads), count);
  if (tasks == 0) return;
  std::atomic<std::size_t> next{0};
  // each task takes increasing indices, so its first failure is its lowest
  std::vector<std::size_t> failed(tasks, count);
  std::vector<std::exception_ptr> errors(tasks);
  detail::run_tasks(tasks, [&](std::size_t task) {
    for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      try {
        body(i);
      } catch (...) {
        if (!errors[task]) {
          failed[task] = i;
          errors[task] = std::current_exception();
        }
      }
    }
  });
  const auto lowest = std::min_element(failed.begin(), failed.end()) - failed.begin();
  if (errors[static_cast<std::size_t>(lowest)])
    std::rethrow_exception(errors[static_cast<std::size_t>(lowest)]);
}

}  // namespace gencoord
