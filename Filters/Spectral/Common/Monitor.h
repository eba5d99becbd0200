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
#include <string>

namespace spectral
{
/**
 * Optional callbacks a long computation calls from the thread that started it.
 * Progress receives a fraction in [0, 1]; Cancelled returns true when the caller wants the
 * computation to stop, which then throws spectral::Cancelled; Stage names the step that begins
 * ("Assemble", "Eigensolve"); Warning receives a sentence for the user as soon as it is known
 * (what was left out, repaired or relaxed), before a long step that follows.
 */
struct Monitor
{
  std::function<void(double)> Progress;
  std::function<bool()> Cancelled;
  std::function<void(const char*)> Stage;
  std::function<void(const std::string&)> Warning;

  /// Report progress (no-op without a callback).
  void Report(double fraction) const
  {
    if (this->Progress)
    {
      this->Progress(fraction);
    }
  }
  /// Announce a step (no-op without a callback).
  void Begin(const char* stage) const
  {
    if (this->Stage)
    {
      this->Stage(stage);
    }
  }
  /// Pass a warning on (no-op without a callback).
  void Warn(const std::string& text) const
  {
    if (this->Warning)
    {
      this->Warning(text);
    }
  }
  /**
   * The same monitor with progress mapped from [0, 1] to [from, to]: for one step of a longer
   * computation.
   */
  Monitor Scaled(double from, double to) const
  {
    Monitor scaled = *this;
    if (this->Progress)
    {
      const std::function<void(double)> progress = this->Progress;
      scaled.Progress = [progress, from, to](double f) { progress(from + (to - from) * f); };
    }
    return scaled;
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
