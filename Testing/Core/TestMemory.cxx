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
    1e6 * (9 * 100 / 2 + 100) * 8.0,
    0.0,
    "Krylov workspace: n (9 k / 2 + 100) 8");
  CheckNear(static_cast<double>(d.Overhead), 16.0 * 1048576.0, 0.0, "the process's own: 16 MiB");
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
    600 * (10 + 9 * 20 / 2 + 100) * 8.0 + 600 * 80 * 12.0,
    0.0,
    "solver terms over the used points");
}

//------------------------------------------------------------------------------
// The plan shrinks automatic bands to the largest that fits, never a band set by hand, and
// refuses below SmallestPlannedBand. Streamed 1M x 1000 (Memory.h's formula): 2 n 64 8 in
// delivery, n 3k 8 for the seams, n (9k/2 + 100) 8 of Krylov, n 80 12 of factor and 16 MiB:
// n (2784 + 60 k) + 16 MiB for even k.
void PlanChoosesBands()
{
  const std::uint64_t n = 1000000;
  const auto streamed = [n](int k)
  { return n * (2784 + 60 * static_cast<std::uint64_t>(k)) + (std::uint64_t(16) << 20); };
  Check(EstimateStreamedMemory(n, n, 1000, 40).Total() == streamed(40),
    "the streamed estimate at bands of 40 is n (2784 + 60 k) + 16 MiB");

  MemoryPlan plan = PlanStreamedMemory(n, n, 1000, 0, false, streamed(100));
  Check(plan.Fits && !plan.Shrunk && plan.BandSize == 0 && plan.UnplannedBandSize == 100,
    "the automatic bands of 100 fit: unchanged");
  plan = PlanStreamedMemory(n, n, 1000, 0, false, 0);
  Check(plan.Fits && !plan.Shrunk && plan.BandSize == 0, "nothing known of the memory: unchanged");

  plan = PlanStreamedMemory(n, n, 1000, 0, false, streamed(40) + 50 * n);
  Check(plan.Fits && plan.Shrunk && plan.BandSize == 40 && plan.Estimate.Total() == streamed(40),
    "between the estimates at 40 and 41: bands of 40 (got " + std::to_string(plan.BandSize) + ")");
  plan = PlanStreamedMemory(n, n, 1000, 0, false, streamed(100) - 1);
  Check(plan.Fits && plan.Shrunk && plan.BandSize == 99, "one byte short of 100: bands of 99");

  plan = PlanStreamedMemory(n, n, 1000, 0, false, streamed(SmallestPlannedBand) - 1);
  Check(!plan.Fits && plan.Estimate.Total() == streamed(SmallestPlannedBand),
    "below the smallest planned band: refused, with the estimate at that band");

  plan = PlanStreamedMemory(n, n, 1000, 60, false, streamed(40));
  Check(!plan.Fits && !plan.Shrunk && plan.BandSize == 60 && plan.Estimate.Total() == streamed(60),
    "a band size set by hand is not shrunk: refused at its own estimate");

  // In memory the basis and the solver's eigenvectors dominate: smaller bands only take the
  // Krylov term down (n 36 bytes a pair of bands, 2 k).
  const std::uint64_t inMemory = EstimateBasisMemory(n, n, 1000, 0, 8).Total();
  plan = PlanBasisMemory(n, n, 1000, 0, 8, true, false, inMemory - 36 * n * 30);
  Check(plan.Fits && plan.BandSize == 70, "in memory, 30 pairs of Krylov short: bands of 70");

  // Few harmonics: one band of m + m/4 + 10 = 22 pairs; 20 is the least it goes down to.
  const std::uint64_t ten = EstimateBasisMemory(n, n, 10, 0, 8).Total();
  plan = PlanBasisMemory(n, n, 10, 0, 8, true, false, ten - 1);
  Check(plan.Fits && plan.BandSize == 21, "10 harmonics, one byte short: a band of 21");
  plan = PlanBasisMemory(n, n, 10, 0, 8, true, false, ten / 2);
  Check(!plan.Fits && plan.Estimate.Total() == EstimateBasisMemory(n, n, 10, 20, 8).Total(),
    "10 harmonics in half the memory: refused at bands of 20");
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
  { "PlanChoosesBands", PlanChoosesBands },
  { "AvailableMemory", AvailableMemory },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
