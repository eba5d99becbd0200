// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/Bands.h"

namespace spectral
{
//------------------------------------------------------------------------------
int SingleBandSize(int m)
{
  return m + m / 4 + 10;
}

//------------------------------------------------------------------------------
int EffectiveBandSize(int m, int bandSize)
{
  if (bandSize > 0)
  {
    return bandSize;
  }
  // Up to 160 pairs one band beats two bands of 100: on the benchmark tori, m = 100 took 0.38 s
  // instead of 0.54 s (10K points) and 4.0 s instead of 5.5 s (100K); m = 150 in one band of 197
  // was slower than in two (0.66 s against 0.54 s).
  const int single = SingleBandSize(m);
  return single <= 160 ? single : 100;
}
} // namespace spectral
