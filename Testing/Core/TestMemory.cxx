// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The memory estimate of a basis computation and the available memory
// (Filters/Spectral/Solver/Memory.h).
#include "Checks.h"
#include "Solver/Memory.h"

#include <string>

using namespace spectral;
using namespace spectral::testing;

namespace
{
//------------------------------------------------------------------------------
void EstimateFormula()
{
  Check(EffectiveBandSize(10, 0) == 22, "automatic band size for m = 10: one band of 22");
  Check(EffectiveBandSize(100, 0) == 135, "automatic band size for m = 100: one band of 135");
  Check(EffectiveBandSize(120, 0) == 160, "automatic band size for m = 120: one band of 160");
  Check(EffectiveBandSize(121, 0) == 100, "automatic band size for m = 121: bands of 100");
  Check(EffectiveBandSize(1000, 0) == 100, "automatic band size for m = 1000: 100");
  Check(EffectiveBandSize(1000, 30) == 30, "a band size set by hand is kept");

  // 1M points, 1000 harmonics: the 8 GB of a double basis become 4 GB in float.
  const MemoryEstimate d = EstimateBasisMemory(1000000, 1000000, 1000, 0, 8);
  const MemoryEstimate f = EstimateBasisMemory(1000000, 1000000, 1000, 0, 4);
  CheckNear(static_cast<double>(d.Basis), 8e9, 0.0, "double basis: n m 8");
  CheckNear(static_cast<double>(f.Basis), 4e9, 0.0, "float basis: n m 4");
  CheckNear(static_cast<double>(d.Eigenvectors), 8e9, 0.0, "solver eigenvectors: n m 8");
  CheckNear(static_cast<double>(d.Krylov),
    1e6 * (3 * 100 + 100) * 8.0,
    0.0,
    "Krylov workspace: n (3 k + 100) 8");
  CheckNear(static_cast<double>(d.Factor), 1e6 * 80 * 12.0, 0.0, "sparse factor: n 80 12");
  CheckNear(static_cast<double>(d.Total() - f.Total()), 4e9, 0.0, "float saves n m 4");
  // A volume of 1M points: the factor fills 11 n^(1/3) = 1100 entries a row.
  const MemoryEstimate v = EstimateBasisMemory(1000000, 1000000, 1000, 0, 8, true, true);
  CheckNear(static_cast<double>(v.Factor),
    1e6 * 1100 * 12.0,
    1e-6 * 1.32e10,
    "volume factor: n 11 n^(1/3) 12");

  // Unused points count in the output basis only.
  const MemoryEstimate partial = EstimateBasisMemory(1000, 600, 10, 20, 8);
  CheckNear(static_cast<double>(partial.Basis), 1000 * 10 * 8.0, 0.0, "basis over all n points");
  CheckNear(static_cast<double>(partial.Eigenvectors + partial.Krylov + partial.Factor),
    600 * (10 + 3 * 20 + 100) * 8.0 + 600 * 80 * 12.0,
    0.0,
    "solver terms over the used points");
}

//------------------------------------------------------------------------------
void AvailableMemory()
{
  const double bytes = static_cast<double>(spectral::AvailableMemory());
  Check(bytes > 1e6 && bytes < 1e16,
    "available memory is known and plausible: " + std::to_string(bytes / 1e9) + " GB");
}

const Case Cases[] = {
  { "EstimateFormula", EstimateFormula },
  { "AvailableMemory", AvailableMemory },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
