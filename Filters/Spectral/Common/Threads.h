// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Threads.h
 * @brief Row ranges of a tall matrix on a few std::threads, for the transforms of Transfer.h.
 *
 * The forward and inverse transforms stream the n by m basis from memory once; splitting its
 * rows over two cores nearly halves their time. They run on plain std::threads rather than on
 * vtkSMPTools because the core does not know VTK, and because ParaView as packaged by Debian
 * selects vtkSMPTools' Sequential backend, which would run them on one thread.
 *
 * Each range is a contiguous block of rows; the work for range p must only write data that
 * belongs to range p (its own rows of an output, or its own partial sum), so the ranges need no
 * locking. Nothing is copied: the work reads the shared inputs in place.
 *
 * Used by Transfer.cxx; tested by Testing/Core/TestTransfer.cxx (ThreadsMatchOneThread).
 */
#ifndef spectral_Threads_h
#define spectral_Threads_h

#include <Eigen/Core>

#include <algorithm>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace spectral
{
/**
 * The number of threads the transforms use when asked for 0 (automatic): 2, or 1 on a machine
 * with one core, and 1 for products of fewer than 2^18 basis entries (n x m), where starting a
 * thread costs more than it saves.
 * \param n Rows of the basis.
 * \param m Columns of the basis.
 * \param requested Threads asked for; >= 1 is returned as is (capped at n, at least 1).
 */
inline int TransformThreads(Eigen::Index n, Eigen::Index m, int requested = 0)
{
  if (requested <= 0)
  {
    const unsigned int cores = std::thread::hardware_concurrency();
    requested = (cores == 1 || n * m < (Eigen::Index(1) << 18)) ? 1 : 2;
  }
  return static_cast<int>(std::max<Eigen::Index>(1, std::min<Eigen::Index>(requested, n)));
}

/**
 * Split the rows [0, n) into `parts` contiguous ranges of nearly equal size and call
 * work(part, first, count) for each, ranges 1, 2, ... on new threads and range 0 on the calling
 * thread; return when all are done.
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
