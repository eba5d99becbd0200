// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Threads.h
 * @brief How many threads the core uses (the one rule), and row ranges of a tall matrix on
 *        that many std::threads.
 *
 * Every parallel part of the core (the transforms of Transfer.h, the block products of
 * BlockProducts.h, the factorization and solves of SupernodalLDLT.h) takes a thread count with
 * the same meaning, resolved by ResolveThreads: a count >= 1 is used as is, 0 means every core
 * of the machine, or the limit that a ScopedThreadLimit holds on the calling thread (how the
 * eigensolver passes EigenOptions::Threads to all its parts). Where 0 is asked for, products too
 * small to gain from threads stay on fewer (ThreadsForWork: each thread gets at least a minimum
 * amount of work), never on more than the cores.
 *
 * They run on plain std::threads rather than on vtkSMPTools because the core does not know VTK,
 * and because ParaView as packaged by Debian selects vtkSMPTools' Sequential backend, which
 * would run them on one thread. The threads are kept between calls (RunOnHelpers, Threads.cxx):
 * the 10,000-point torus of the benchmark with 100 harmonics makes about 600 parallel calls,
 * and starting a thread for each took a tenth of its time.
 *
 * Each range of ForEachRowRange is a contiguous block of rows; the work for range p must only
 * write data that belongs to range p (its own rows of an output, or its own partial sum), so the
 * ranges need no locking. Nothing is copied: the work reads the shared inputs in place.
 *
 * Tested by Testing/Core/TestTransfer.cxx (ThreadsMatchOneThread: nested and concurrent calls
 * too).
 */
#ifndef spectral_Threads_h
#define spectral_Threads_h

#include <Eigen/Core>

#include <algorithm>
#include <climits>
#include <exception>
#include <functional>
#include <system_error>
#include <thread>
#include <vector>

namespace spectral
{
/// The limit that ScopedThreadLimit set on the calling thread; 0 for none.
inline int& ThreadLimit()
{
  static thread_local int limit = 0;
  return limit;
}

/**
 * For its lifetime, what a request of 0 threads means on the calling thread: `threads` (>= 1)
 * instead of every core, for everything the computation that holds it runs (e.g. the
 * eigensolver with EigenOptions::Threads). 0 leaves the meaning unchanged. Computations on other
 * threads are not affected.
 */
class ScopedThreadLimit
{
public:
  explicit ScopedThreadLimit(int threads)
    : Previous(ThreadLimit())
  {
    if (threads >= 1)
    {
      ThreadLimit() = threads;
    }
  }
  ~ScopedThreadLimit() { ThreadLimit() = this->Previous; }
  ScopedThreadLimit(const ScopedThreadLimit&) = delete;
  ScopedThreadLimit& operator=(const ScopedThreadLimit&) = delete;

private:
  int Previous;
};

/**
 * The thread count of the core: `requested` if it is >= 1, else (0, automatic) the limit of a
 * ScopedThreadLimit on the calling thread, or the number of cores of the machine
 * (std::thread::hardware_concurrency(), 1 where it is unknown).
 */
inline int ResolveThreads(int requested)
{
  if (requested >= 1)
  {
    return requested;
  }
  if (ThreadLimit() >= 1)
  {
    return ThreadLimit();
  }
  const unsigned int cores = std::thread::hardware_concurrency();
  return cores == 0 ? 1 : static_cast<int>(std::min<unsigned int>(cores, INT_MAX));
}

/**
 * Threads for `work` units of work where a thread pays off only with at least `perThread` of
 * them: `requested` if it is >= 1, else ResolveThreads(0) but no more than work / perThread,
 * at least 1.
 */
inline int ThreadsForWork(Eigen::Index work, Eigen::Index perThread, int requested)
{
  if (requested >= 1)
  {
    return requested;
  }
  const Eigen::Index useful =
    std::max<Eigen::Index>(1, work / std::max<Eigen::Index>(1, perThread));
  return static_cast<int>(std::min<Eigen::Index>(ResolveThreads(0), useful));
}

/**
 * The number of threads of the transforms of an n by m basis: ThreadsForWork with at least 2^17
 * basis entries per thread (below 2^18 entries, starting a thread costs more than it saves),
 * and at most one thread a row.
 * \param n Rows of the basis.
 * \param m Columns of the basis.
 * \param requested Threads asked for, as ResolveThreads.
 */
inline int TransformThreads(Eigen::Index n, Eigen::Index m, int requested = 0)
{
  const int threads = ThreadsForWork(n * m, Eigen::Index(1) << 17, requested);
  return static_cast<int>(std::max<Eigen::Index>(1, std::min<Eigen::Index>(threads, n)));
}

namespace detail
{
/**
 * Call run(1), ..., run(helpers) on the core's helper threads and run(0) on the calling thread;
 * return when all have returned. The helpers wait between calls (starting a thread and joining
 * it costs about 30 microseconds, and a band of the eigensolver makes a dozen parallel calls
 * per block of 8 vectors, some of a few hundred microseconds). One caller uses them at a time.
 * \param run Must not throw.
 * \return false, having run nothing, when the helpers are in use (a call from another thread,
 *         or from within run), cannot be started, or belong to the parent of a forked process.
 */
bool RunOnHelpers(int helpers, const std::function<void(int)>& run);
} // namespace detail

/**
 * Split the rows [0, n) into `parts` contiguous ranges of nearly equal size and call
 * work(part, first, count) for each, ranges 1, 2, ... on other threads (the helpers of
 * RunOnHelpers, or new threads where those are in use) and range 0 on the calling thread;
 * return when all are done.
 * \param n Number of rows, >= 0.
 * \param parts Number of ranges, >= 1 (1 runs work(0, 0, n) on the calling thread only).
 * \param work Callable (int part, Eigen::Index first, Eigen::Index count); it must write only
 *        what belongs to its own part.
 * \throws The first exception that a range threw, after every thread has finished.
 */
template<typename Work>
void ForEachRowRange(Eigen::Index n, int parts, const Work& work)
{
  parts = std::max(1, parts);
  const Eigen::Index chunk = (n + parts - 1) / parts;
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(parts));
  auto run = [&work, &errors, n, chunk](int part)
  {
    const Eigen::Index first = std::min(n, part * chunk);
    try
    {
      work(part, first, std::min(chunk, n - first));
    }
    catch (...)
    {
      errors[static_cast<std::size_t>(part)] = std::current_exception();
    }
  };
  if (parts == 1)
  {
    run(0);
  }
  else if (!detail::RunOnHelpers(parts - 1, std::ref(run))) // a reference: no copy to the heap
  {
    std::vector<std::thread> helpers;
    helpers.reserve(static_cast<std::size_t>(parts - 1));
    for (int part = 1; part < parts; ++part)
    {
      try
      {
        helpers.emplace_back(run, part);
      }
      catch (const std::system_error&)
      {
        run(part); // no thread to be had: this range on the calling thread
      }
    }
    run(0);
    for (std::thread& helper : helpers)
    {
      helper.join();
    }
  }
  for (const std::exception_ptr& error : errors)
  {
    if (error)
    {
      std::rethrow_exception(error);
    }
  }
}
} // namespace spectral

#endif
