// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Basis.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <sstream>

namespace spectral
{
namespace
{
//------------------------------------------------------------------------------
// Number of harmonics to compute: the request, clamped with a warning to the usable points.
int ClampedHarmonics(int requested, int usable, const Monitor& monitor, BasisResult& result)
{
  if (requested < 1)
  {
    throw InvalidInput(
      "the number of harmonics must be at least 1, not " + std::to_string(requested));
  }
  if (requested <= usable)
  {
    return requested;
  }
  const std::string text = "NumberOfHarmonics " + std::to_string(requested) + " clamped to " +
    std::to_string(usable) + ", the number of points triangles use.";
  result.Warnings.push_back(text);
  monitor.Warn(text);
  return usable;
}

//------------------------------------------------------------------------------
// Throws InsufficientMemory when the estimate for this computation exceeds what is available.
void CheckMemory(const TriangleMesh& mesh, Eigen::Index used, int m, const BasisOptions& options)
{
  const MemoryEstimate need = EstimateBasisMemory(static_cast<std::uint64_t>(mesh.Vertices.rows()),
    static_cast<std::uint64_t>(used),
    m,
    options.Solver.BandSize,
    options.BytesPerValue);
  const std::uint64_t available = options.MemoryLimit > 0 ? options.MemoryLimit : AvailableMemory();
  if (available != 0 && need.Total() > available)
  {
    throw InsufficientMemory(need, available, m);
  }
}

//------------------------------------------------------------------------------
// The relative residual eigenpairs can meet in double precision. Round-off in L h is about
// eps lambda_max, measured against the lowest frequencies; lambda_max comes from Gershgorin's
// bound on M^-1 L (lumped mass), the lowest frequency from the size of the surface, (pi / d)^2
// with d the bounding-box diagonal. Sets `ratio` to lambda_max / lambda_low.
double AchievableResidual(const DiscreteLaplacian& ops, double& ratio)
{
  double top = 0.0;
  const SparseMatrix& L = ops.Stiffness;
  for (int j = 0; j < L.outerSize(); ++j)
  {
    const double sum = L.col(j).cwiseAbs().sum();
    top = std::max(top, ops.LumpedMass[j] > 0.0 ? sum / ops.LumpedMass[j] : 0.0);
  }
  const double pi = 3.14159265358979323846;
  ratio = top * ops.Diameter * ops.Diameter / (pi * pi);
  return 10.0 * std::numeric_limits<double>::epsilon() * ratio;
}

//------------------------------------------------------------------------------
// SmallestEigenpairs with the two fallbacks of the file documentation of Basis.h. Beyond a
// residual of 1e-4 the eigenpairs would be meaningless: the failure is passed on with why.
EigenResult SolveWithFallbacks(const DiscreteLaplacian& ops,
  EigenOptions options,
  const Monitor& monitor,
  BasisResult& basis)
{
  const int wanted = options.NumberOfEigenpairs;
  options.NumberOfEigenpairs = (wanted == 1 && ops.Stiffness.rows() > 1) ? 2 : wanted;
  EigenResult result;
  try
  {
    result = SmallestEigenpairs(ops.Stiffness, ops.Mass, options, monitor);
  }
  catch (const SolverFailure& e)
  {
    double ratio = 0.0;
    const double achievable = AchievableResidual(ops, ratio);
    if (!(achievable > options.ResidualTolerance))
    {
      throw;
    }
    std::ostringstream why;
    why << "the operators are badly conditioned (largest / lowest eigenvalue about " << ratio
        << ", from needle, sliver or tiny triangles)";
    if (achievable > 1e-4)
    {
      throw SolverFailure(std::string(e.what()) + "; " + why.str() +
          " beyond what double precision resolves: remove them (merge close points, e.g. with "
          "vtkCleanPolyData and a tolerance) or remesh",
        e.Converged);
    }
    std::ostringstream text;
    text << "Eigenpairs verified to a relative residual of " << achievable << " instead of "
         << options.ResidualTolerance << ": " << why.str()
         << ". Laplacian = Intrinsic Delaunay or remeshing improves this.";
    basis.Warnings.push_back(text.str());
    monitor.Warn(text.str());
    options.ResidualTolerance = achievable;
    result = SmallestEigenpairs(ops.Stiffness, ops.Mass, options, monitor);
  }
  if (result.Eigenvalues.size() > wanted)
  {
    result.Eigenvalues.conservativeResize(wanted);
    result.Eigenvectors.conservativeResize(Eigen::NoChange, wanted);
  }
  return result;
}

//------------------------------------------------------------------------------
// Passes the warnings on to the monitor and keeps them in the result.
void Report(const std::vector<std::string>& warnings, const Monitor& monitor, BasisResult& result)
{
  for (const std::string& text : warnings)
  {
    result.Warnings.push_back(text);
    monitor.Warn(text);
  }
}
} // anonymous namespace

//------------------------------------------------------------------------------
InsufficientMemory::InsufficientMemory(const MemoryEstimate& needed,
  std::uint64_t available,
  int harmonics)
  : std::runtime_error("not enough memory for " + std::to_string(harmonics) + " harmonics: " +
      std::to_string(needed.Total()) + " bytes needed, " + std::to_string(available) + " available")
  , Harmonics(harmonics)
  , Needed(needed)
  , Available(available)
{
}

//------------------------------------------------------------------------------
BasisResult ComputeBasis(const TriangleMesh& mesh,
  const BasisOptions& options,
  const Monitor& monitor)
{
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  BasisResult result;
  monitor.Begin("Assemble");
  const PreparedMesh prepared = PrepareMesh(mesh);
  Report(PreparationWarnings(prepared), monitor, result);
  const Eigen::Index used = prepared.Mesh.Vertices.rows();
  if (used == 0)
  {
    throw InvalidInput("every triangle of the input is degenerate (zero area)");
  }
  const int m =
    ClampedHarmonics(options.NumberOfHarmonics, static_cast<int>(used), monitor, result);
  if (options.CheckMemory)
  {
    CheckMemory(mesh, used, m, options);
  }

  DiscreteLaplacian ops = AssembleLaplacian(prepared, options.Operators, monitor);
  Report(ops.Warnings, monitor, result);
  result.Components = ops.Components;
  if (result.Components > 1)
  {
    Report({ "The surface has " + std::to_string(result.Components) +
             " connected components: the first " + std::to_string(result.Components) +
             " eigenvalues are zero." },
      monitor,
      result);
  }
  result.AssemblySeconds = std::chrono::duration<double>(Clock::now() - start).count();
  monitor.Report(0.1);
  monitor.ThrowIfCancelled();

  monitor.Begin("Eigensolve");
  EigenOptions solver = options.Solver;
  solver.NumberOfEigenpairs = m;
  result.Pairs = SolveWithFallbacks(ops, solver, monitor.Scaled(0.1, 1.0), result);
  result.LumpedMass = std::move(ops.LumpedMass);
  result.InputPointIds = std::move(ops.InputPointIds);
  return result;
}
} // namespace spectral
