// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Diagnostics.h
 * @brief What the eigensolver reports besides its pairs: the seconds of each stage
 *        (EigenTimings) and the numbers quoted in its failure messages.
 *
 * Used by the eigensolver's source files in Solver/. No test reads the messages or the
 * seconds; bench/ManifoldHarmonicsBench prints the seconds.
 */
#ifndef spectral_Diagnostics_h
#define spectral_Diagnostics_h

#include <chrono>
#include <cstdio>
#include <string>

namespace spectral
{
namespace detail
{
/// The clock of EigenTimings.
using Clock = std::chrono::steady_clock;

/// Seconds from `start` to now.
inline double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// A number in a failure message: nine significant digits.
inline std::string Str(double value)
{
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.9g", value);
  return buffer;
}
} // namespace detail
} // namespace spectral

#endif
