// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Monitor.h
 * @brief Progress reporting and cancellation for long computations of the spectral core.
 */
#ifndef spectral_Monitor_h
#define spectral_Monitor_h

#include "Common/Mesh.h"

#include <functional>

namespace spectral
{
/**
 * Two optional callbacks a long computation calls from the thread that started it.
 * Progress receives a fraction in [0, 1]; Cancelled returns true when the caller wants the
 * computation to stop, which then throws spectral::Cancelled.
 */
struct Monitor
{
  std::function<void(double)> Progress;
  std::function<bool()> Cancelled;

  /// Report progress (no-op without a callback).
  void Report(double fraction) const
  {
    if (this->Progress)
    {
      this->Progress(fraction);
    }
  }
  /// Throw spectral::Cancelled if the caller asked to stop.
  void ThrowIfCancelled() const
  {
    if (this->Cancelled && this->Cancelled())
    {
      throw spectral::Cancelled();
    }
  }
};
} // namespace spectral

#endif
