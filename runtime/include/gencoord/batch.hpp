// Batched evaluation: qddot or one integrator step for many states (and parameter sets) at
// once, spread over threads.
//
// A static partition: the batch is cut into `threads` contiguous chunks of nearly equal size,
// one per thread (the calling thread takes the first). Each output element is computed by
// exactly the code the serial path runs, so results equal the serial ones bit for bit
// whatever the thread count. The threads are the shared WorkerPool's (worker_pool.hpp), so a
// batch costs a wake-up, not a thread start; more threads than the machine has are started
// per call.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "gencoord/dynamics.hpp"
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model_traits.hpp"
#include "gencoord/reduced_system.hpp"
#include "gencoord/state.hpp"
#include "gencoord/worker_pool.hpp"

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

template <class P>
void check_batch_sizes(std::size_t num_states, const std::vector<P>& params, int threads) {
  if (params.size() != 1 && params.size() != num_states)
    throw std::invalid_argument("gencoord: batch needs 1 parameter set or one per state (" +
                                std::to_string(num_states) + "), got " +
                                std::to_string(params.size()));
  if (threads < 1)
    throw std::invalid_argument("gencoord: batch thread count must be at least 1, got " +
                                std::to_string(threads));
}

// Calls body(begin, end) on `threads` contiguous chunks of [0, count), concurrently: on the
// shared worker pool when it has enough threads, else on threads started for this call. An
// exception thrown by a chunk is rethrown here after every chunk has finished; with several,
// the one from the lowest chunk, so which error is reported does not depend on timing.
template <class Body>
void parallel_chunks(std::size_t count, int threads, const Body& body) {
  const std::size_t chunks =
      std::min<std::size_t>(static_cast<std::size_t>(threads), std::max<std::size_t>(count, 1));
  std::vector<std::exception_ptr> errors(chunks);
  const std::function<void(std::size_t)> run = [&](std::size_t c) {
    // chunk c is [c * count / chunks, (c + 1) * count / chunks): sizes differ by at most 1
    try {
      body(c * count / chunks, (c + 1) * count / chunks);
    } catch (...) {
      errors[c] = std::current_exception();
    }
  };
  WorkerPool& pool = shared_worker_pool();
  if (chunks == 1) {
    run(0);
  } else if (static_cast<int>(chunks) <= pool.threads()) {
    pool.run(chunks, run);
  } else {
    std::vector<std::thread> workers;
    workers.reserve(chunks - 1);
    for (std::size_t c = 1; c < chunks; ++c) workers.emplace_back(run, c);
    run(0);
    for (auto& worker : workers) worker.join();
  }
  for (const auto& error : errors)
    if (error) std::rethrow_exception(error);
}

}  // namespace detail

/// Generalized accelerations of many states: (*out)[i] = acceleration<M>(params[i], states[i]).
/// \param[in]  states   The states (q, v of dim M::nq, t).
/// \param[in]  params   One parameter set for every state, or one per state.
/// \param[out] out      Resized to states.size() and filled; not null.
/// \param[in]  threads  Threads to use, at least 1 (the caller's thread counts as one).
/// \throws std::invalid_argument on mismatched sizes or threads < 1; DynamicsError as
///         acceleration() (the first failing chunk's), after all threads have finished.
template <class M>
void batch_qddot(const std::vector<State<M>>& states, const std::vector<ParamsOf<M>>& params,
                 std::vector<QVec<M>>* out, int threads = default_batch_threads()) {
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

}  // namespace gencoord
