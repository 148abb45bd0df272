// SPDX-License-Identifier: BSD-3-Clause
// sweep: runs the samples of a sweep of one generated model under MPI and records them in
// one HDF5 file.
//
//   mpirun -np N sweep --table FILE.table --output FILE.h5 [--resume] [--threads T]
//   sweep --check --table FILE.table --output FILE.h5
//
// `gencoord sweep SWEEP.toml` writes the table (samples and settings) and runs this program;
// docs/sweep.md describes both. Rank 0 creates the results file (or, with --resume, opens
// it and skips the chunks it holds), hands out chunks, runs some itself, writes every result
// and prints the progress and a summary; every rank runs its chunks' samples on its threads.
// --check, without MPI, says how much of the results file is complete, or why it cannot be
// resumed, before a run is launched.
#include <mpi.h>

#include <sys/stat.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "command_line.hpp"
#include "driver_model.hpp"
#include "gencoord/gencoord.hpp"
#include "sweep/h5_file.hpp"
#include "sweep/progress.hpp"
#include "sweep/sample_run.hpp"
#include "sweep/scheduler.hpp"
#include "sweep/table.hpp"

namespace {

using M = gencoord::drivers::Model;
namespace sw = gencoord::sweep;

struct Options {
  std::string table, output;
  bool resume = false, check = false;
  int threads = 0;  // 0: the node's cores shared among its ranks
};

bool mpi_started = false;

[[noreturn]] void usage(int rank, int status) {
  if (rank == 0)
    std::cerr << "usage: mpirun -np N sweep --table FILE.table --output FILE.h5 [--resume]\n"
                 "                          [--threads T]\n"
                 "       sweep --check --table FILE.table --output FILE.h5\n"
                 "  model: "
              << M::name << " (nq = " << M::nq << ", nv = " << gencoord::nv_of_v<M>
              << ")\n"
                 "  gencoord sweep SWEEP.toml writes the table and runs this (docs/sweep.md)\n";
  if (mpi_started) MPI_Finalize();
  std::exit(status);
}

Options parse(int argc, char** argv, int rank) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&] { return gencoord::drivers::option_value("sweep", argc, argv, i); };
    if (arg == "-h" || arg == "--help") usage(rank, 0);
    else if (arg == "--table") o.table = value();
    else if (arg == "--output") o.output = value();
    else if (arg == "--resume") o.resume = true;
    else if (arg == "--check") o.check = true;
    else if (arg == "--threads") {
      const double threads = gencoord::drivers::parse_number("sweep", value(), arg);
      if (threads != std::floor(threads) || threads < 0 || threads > 4096) {
        if (rank == 0) std::cerr << "sweep: error: --threads expects a whole number 0 ... 4096\n";
        usage(rank, 2);
      }
      o.threads = static_cast<int>(threads);
    } else {
      if (rank == 0) std::cerr << "sweep: error: unknown argument " << arg << "\n";
      usage(rank, 2);
    }
  }
  if (o.table.empty() || o.output.empty() || o.threads < 0) usage(rank, 2);
  return o;
}

// Whether every rank succeeded; rank 0's failure is printed, else each failing rank's.
bool all_succeeded(bool ok, const std::string& error, int rank) {
  int mine = ok ? 1 : 0, all = 0, root = mine;
  MPI_Allreduce(&mine, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  MPI_Bcast(&root, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (!ok && (rank == 0 || root == 1))
    std::cerr << "sweep: error" << (rank == 0 ? "" : " (rank " + std::to_string(rank) + ")") << ": "
              << error << "\n";
  return all == 1;
}

// Rank 0's `text`, on every rank.
void broadcast(std::string* text) {
  unsigned long long size = text->size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  text->resize(size);
  MPI_Bcast(text->data(), static_cast<int>(size), MPI_CHAR, 0, MPI_COMM_WORLD);
}

// The threads of this rank: the given number, else the node's cores over its ranks.
int threads_of(const Options& o) {
  if (o.threads > 0) return o.threads;
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks_here = 1;
  MPI_Comm_size(node, &ranks_here);
  MPI_Comm_free(&node);
  return std::max(1, gencoord::default_batch_threads() / ranks_here);
}

bool exists(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

// Rank 0: the results file to write into, created or (--resume) reopened, and the chunks it
// still lacks.
sw::ResultsFile open_results(const Options& o, const sw::Table& table, const sw::Layout& layout,
                             std::vector<long long>* pending) {
  if (exists(o.output) && !o.resume)
    throw sw::ResultsError(o.output +
                           " exists: --resume continues that run; remove it to "
                           "start again");
  if (!exists(o.output)) {
    const std::vector<std::string> coordinates(M::coordinate_names.begin(),
                                               M::coordinate_names.end());
    sw::ResultsFile::create(o.output, table, layout, coordinates, sw::detail::speed_names<M>());
  }
  sw::ResultsFile file(o.output, table, layout);
  const std::vector<std::uint8_t> done = file.chunk_done();
  for (long long c = 0; c < table.chunks(); ++c)
    if (!done[static_cast<std::size_t>(c)]) pending->push_back(c);
  return file;
}

// "1 chunk", "2 chunks"; "2 batches"
std::string count(long long n, const std::string& thing, const std::string& things = "") {
  return std::to_string(n) + " " + (n == 1 ? thing : things.empty() ? thing + "s" : things);
}

// How this run went, for the summary.
struct RunFigures {
  int ranks = 1, threads = 1;
  long long chunks_run = 0;
  long long batches = 0;       // rank 0's writes: each the rows of some chunks and two syncs
  double write_seconds = 0.0;  // spent in them
};

void print_summary(const sw::Table& table, const Options& o, sw::ResultsFile& file,
                   const sw::Progress& progress, const RunFigures& run_figures) {
  const long long chunks_run = run_figures.chunks_run;
  const int ranks = run_figures.ranks, threads = run_figures.threads;
  const double seconds = progress.seconds();
  const long long run = progress.samples_this_run();
  std::printf("sweep       %s of %s in %s of %lld; %s x %s\n",
              count(table.samples, "sample").c_str(), table.model.c_str(),
              count(table.chunks(), "chunk").c_str(), table.chunk, count(ranks, "rank").c_str(),
              count(threads, "thread").c_str());
  std::printf("integrator  %s, dt = %g s, %lld steps to t = %g s\n", table.integrator.c_str(),
              table.dt, table.steps, table.t_end);
  if (table.has_event)
    std::printf("event       %s%s\n", table.event_text.c_str(),
                table.event_stop ? " (ends the sample)" : "");
  if (chunks_run == 0) {
    std::printf("this run    nothing to do: every chunk was complete\n");
  } else {
    std::printf("this run    %s, %s in %.3f s (%.4g samples/s); %s complete before\n",
                count(chunks_run, "chunk").c_str(), count(run, "sample").c_str(), seconds,
                static_cast<double>(run) / seconds,
                (count(table.chunks() - chunks_run, "chunk") +
                 (table.chunks() - chunks_run == 1 ? " was" : " were"))
                    .c_str());
    std::printf("writes      %s by rank 0, %.3f ms each (rows and two syncs to disk)\n",
                count(run_figures.batches, "batch", "batches").c_str(),
                1e3 * run_figures.write_seconds / static_cast<double>(run_figures.batches));
  }
  std::map<int, long long> counts;
  for (const std::int8_t s : file.statuses()) ++counts[s];
  std::string failures;
  long long failed = 0;
  for (const auto& [status, samples] : counts) {
    if (status <= static_cast<int>(sw::Status::kOk)) continue;
    failed += samples;
    failures += (failures.empty() ? "" : ", ") + std::to_string(samples) + " " +
                sw::kStatusNames[static_cast<std::size_t>(status)];
  }
  std::printf("status      %lld ok, %lld failed%s%s%s\n", counts[1], failed,
              failures.empty() ? "" : " (", failures.c_str(), failures.empty() ? "" : ")");
  if (table.record_event_time) {
    long long events = 0;
    double first = INFINITY, last = -INFINITY;
    for (const double t : file.event_times()) {
      if (std::isnan(t)) continue;
      ++events;
      first = std::min(first, t);
      last = std::max(last, t);
    }
    if (events > 0)
      std::printf("events      %lld samples, at t = %g s to %g s\n", events, first, last);
    else std::printf("events      none\n");
  }
  std::printf("results     %s\n", o.output.c_str());
}

// --check: whether the results file can be resumed, and how much of it is complete
int check(const Options& o) {
  try {
    const sw::Table table = sw::parse_table(sw::read_text(o.table), o.table, false);
    const sw::Plan<M> plan = sw::make_plan<M>(table);
    const sw::ResultsFile file(o.output, table, plan.layout, sw::ResultsFile::Access::kReadOnly);
    long long chunks = 0, samples = 0;
    const std::vector<std::uint8_t> done = file.chunk_done();
    for (long long c = 0; c < table.chunks(); ++c) {
      if (!done[static_cast<std::size_t>(c)]) continue;
      ++chunks;
      samples += table.chunk_size(c);
    }
    std::printf("resume      %s holds %lld of %lld chunks (%lld of %lld samples)\n",
                o.output.c_str(), chunks, table.chunks(), samples, table.samples);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "sweep: error: " << e.what() << "\n";
    return 1;
  }
}

int run(const Options& o, int rank, int ranks) {
  sw::Table table;
  sw::Plan<M> plan;
  std::string error, header;
  if (rank == 0) {  // the others get the settings from it, and their chunks' rows later
    try {
      const std::string text = sw::read_text(o.table);
      table = sw::parse_table(text, o.table, true);
      header = sw::header_of(text);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  broadcast(&header);
  try {
    if (rank != 0) {
      if (header.empty()) throw sw::TableError("rank 0 could not read the table");
      table = sw::parse_table(header, o.table, false);
    }
    if (!error.empty()) throw sw::TableError(error);
    if (table.model != M::name)
      throw sw::TableError(o.table + ": a table for model " + table.model + ", not " + M::name);
    plan = sw::make_plan<M>(table);
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (!all_succeeded(error.empty(), error, rank)) return 1;
  const int threads = threads_of(o);
  const auto width = static_cast<long long>(table.columns.size());
  auto compute = [&](long long chunk, const double* rows) {
    sw::ChunkResults r;
    r.reset(plan.layout, chunk, table.chunk_begin(chunk), table.chunk_size(chunk));
    gencoord::batch_for_each(static_cast<std::size_t>(r.count), threads, [&](std::size_t i) {
      const auto k = static_cast<long long>(i);
      sw::run_sample(plan, rows + k * width, k, &r);
    });
    return r;
  };
  if (rank != 0) {
    if (!all_succeeded(true, "", rank)) return 1;  // rank 0's results file is ready
    sw::work(MPI_COMM_WORLD, table, compute);
    return 0;
  }
  std::vector<long long> pending;
  std::unique_ptr<sw::ResultsFile> file;
  try {
    file = std::make_unique<sw::ResultsFile>(open_results(o, table, plan.layout, &pending));
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (!all_succeeded(error.empty(), error, rank)) return 1;
  long long done_before = table.samples;
  for (const long long c : pending) done_before -= table.chunk_size(c);
  sw::Progress progress(table.samples, done_before);
  progress.show(true);
  RunFigures figures{ranks, threads, static_cast<long long>(pending.size())};
  const sw::WriteChunks write = [&](const std::vector<sw::ChunkResults>& batch) {
    const auto start = std::chrono::steady_clock::now();
    file->write(batch);
    figures.write_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++figures.batches;
  };
  sw::coordinate(MPI_COMM_WORLD, table, pending, plan.layout, compute, write, &progress);
  progress.finish();
  print_summary(table, o, *file, progress, figures);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--check") return check(parse(argc, argv, 0));
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  mpi_started = true;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (provided < MPI_THREAD_FUNNELED) {  // rank 0 computes on a thread beside its MPI calls
    if (rank == 0) std::cerr << "sweep: error: this MPI library does not support threads\n";
    MPI_Finalize();
    return 1;
  }
  const Options options = parse(argc, argv, rank);
  int status = 1;
  try {
    status = run(options, rank, ranks);
  } catch (const std::exception& error) {
    // a failure while the ranks work together (a write that fails, say): stop them all
    std::cerr << "sweep: error" << (rank == 0 ? "" : " (rank " + std::to_string(rank) + ")") << ": "
              << error.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Finalize();
  return status;
}
