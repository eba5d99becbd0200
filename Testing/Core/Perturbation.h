// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The rounding-level perturbation of generated test meshes (the one home of its rule), used by
// Meshes.h here and by the filters' C++ tests (Filters/Testing/Cxx). Without dependencies.
//
// With MANIFOLDHARMONICS_TEST_PERTURBATION=<seed> (an unsigned integer) in the environment,
// every generated mesh has each coordinate multiplied by 1 + 1e-15 u, u uniform in [-1, 1]
// drawn from that seed (the same sequence for each mesh, so two calls that generate the same
// mesh still agree). Unset or empty: no perturbation. A test whose verdict changes under it
// depends on which side of a threshold a rounding-sized number falls (see
// scripts/check-portability.sh).
#ifndef spectral_Testing_Perturbation_h
#define spectral_Testing_Perturbation_h

#include <cstdlib>
#include <random>

namespace spectral
{
namespace testing
{
/// Relative size of the perturbation of each coordinate.
constexpr double RoundingPerturbationSize = 1e-15;

/// Factors 1 + RoundingPerturbationSize u, one per call, from the seed in the environment.
class RoundingPerturbation
{
public:
  RoundingPerturbation()
  {
    const char* seed = std::getenv("MANIFOLDHARMONICS_TEST_PERTURBATION");
    this->On = seed != nullptr && *seed != '\0';
    if (this->On)
    {
      this->Generator.seed(std::strtoull(seed, nullptr, 10));
    }
  }

  /// Whether the environment asks for a perturbation.
  bool Active() const { return this->On; }

  /// The next factor (1 when inactive).
  double operator()()
  {
    return this->On ? 1.0 + RoundingPerturbationSize * this->Uniform(this->Generator) : 1.0;
  }

private:
  bool On = false;
  std::mt19937_64 Generator;
  std::uniform_real_distribution<double> Uniform{ -1.0, 1.0 };
};
} // namespace testing
} // namespace spectral

#endif
