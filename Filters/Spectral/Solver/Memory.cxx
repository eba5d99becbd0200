// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/Memory.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace spectral
{
namespace
{
/// MemAvailable of /proc/meminfo in bytes, 0 if there is no such line (not Linux, old kernel).
std::uint64_t MemAvailableFromProc()
{
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  std::uint64_t kilobytes = 0;
  std::string unit;
  while (meminfo >> key >> kilobytes >> unit)
  {
    if (key == "MemAvailable:")
    {
      return kilobytes * 1024;
    }
  }
  return 0;
}

//------------------------------------------------------------------------------
// The plan of a computation whose estimate at band size k is estimate(k) (a template, not a
// std::function: planning allocates nothing, and the heap a solve starts from stays as it was).
template<typename Estimate>
MemoryPlan PlanMemory(int m, int bandSize, std::uint64_t available, const Estimate& estimate)
{
  MemoryPlan plan;
  plan.BandSize = bandSize;
  plan.UnplannedBandSize = EffectiveBandSize(m, bandSize);
  plan.Estimate = estimate(bandSize);
  if (available == 0 || plan.Estimate.Total() <= available)
  {
    return plan;
  }
  if (bandSize <= 0)
  {
    for (int k = plan.UnplannedBandSize - 1; k >= SmallestPlannedBand; --k)
    {
      const MemoryEstimate smaller = estimate(k);
      if (smaller.Total() <= available)
      {
        plan.BandSize = k;
        plan.Shrunk = true;
        plan.Estimate = smaller;
        return plan;
      }
    }
    if (plan.UnplannedBandSize > SmallestPlannedBand)
    {
      plan.Estimate = estimate(SmallestPlannedBand);
    }
  }
  plan.Fits = false;
  return plan;
}
} // namespace

//------------------------------------------------------------------------------
MemoryEstimate EstimateBasisMemory(std::uint64_t n,
  std::uint64_t nUsed,
  int m,
  int bandSize,
  int bytesPerValue,
  bool keepEigenvectors,
  bool volume)
{
  const std::uint64_t harmonics = static_cast<std::uint64_t>(std::max(m, 0));
  const std::uint64_t band = static_cast<std::uint64_t>(EffectiveBandSize(m, bandSize));
  MemoryEstimate estimate;
  estimate.Basis = n * harmonics * static_cast<std::uint64_t>(bytesPerValue);
  estimate.Eigenvectors =
    nUsed * (keepEigenvectors ? harmonics : std::min(harmonics, 3 * band)) * 8;
  estimate.Krylov = nUsed * (9 * band / 2 + 100) * 8;
  const double perRow =
    volume ? 11.0 * std::cbrt(static_cast<double>(nUsed)) : 80.0; // see Memory.h
  estimate.Factor = static_cast<std::uint64_t>(static_cast<double>(nUsed) * perRow * 12.0);
  estimate.Overhead = std::uint64_t(16) << 20;
  return estimate;
}

//------------------------------------------------------------------------------
MemoryEstimate EstimateStreamedMemory(std::uint64_t n,
  std::uint64_t nUsed,
  int m,
  int bandSize,
  bool volume)
{
  MemoryEstimate estimate = EstimateBasisMemory(n, nUsed, m, bandSize, 0, false, volume);
  const std::uint64_t handed = std::min(
    static_cast<std::uint64_t>(std::max(m, 0)), static_cast<std::uint64_t>(StreamedBlockColumns));
  estimate.Basis = 2 * n * handed * 8;
  return estimate;
}

//------------------------------------------------------------------------------
MemoryPlan PlanBasisMemory(std::uint64_t n,
  std::uint64_t nUsed,
  int m,
  int bandSize,
  int bytesPerValue,
  bool keepEigenvectors,
  bool volume,
  std::uint64_t available)
{
  return PlanMemory(m,
    bandSize,
    available,
    [=](int k)
    { return EstimateBasisMemory(n, nUsed, m, k, bytesPerValue, keepEigenvectors, volume); });
}

//------------------------------------------------------------------------------
MemoryPlan PlanStreamedMemory(std::uint64_t n,
  std::uint64_t nUsed,
  int m,
  int bandSize,
  bool volume,
  std::uint64_t available)
{
  return PlanMemory(
    m, bandSize, available, [=](int k) { return EstimateStreamedMemory(n, nUsed, m, k, volume); });
}

//------------------------------------------------------------------------------
std::uint64_t MemoryShare(std::uint64_t available, std::uint64_t reserved)
{
  return available == 0 ? 0 : (available > reserved ? available - reserved : 1);
}

//------------------------------------------------------------------------------
std::uint64_t AvailableMemory()
{
  const std::uint64_t fromProc = MemAvailableFromProc();
  if (fromProc > 0)
  {
    return fromProc;
  }
#if defined(_SC_AVPHYS_PAGES) && defined(_SC_PAGESIZE)
  const long pages = sysconf(_SC_AVPHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGESIZE);
  if (pages > 0 && pageSize > 0)
  {
    return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(pageSize);
  }
#endif
  return 0;
}
} // namespace spectral
