// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Basis.h"
#include "Problem.h"

#include "Solver/Acceptance.h"
#include "Solver/Verification.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace spectral
{
namespace
{
//------------------------------------------------------------------------------
// AchievableResidual (Verification.h) of L h = lambda M h: Gershgorin's bound on D^-1 L (D the
// row sums of M, the lumped mass) and the mesh's diameter. Sets `ratio`.
double OperatorsAchievableResidual(const SparseMatrix& L,
  const SparseMatrix& M,
  double diameter,
  double& ratio)
{
  const Vector lumped = M * Vector::Ones(M.cols());
  double top = 0.0;
  for (int j = 0; j < L.outerSize(); ++j)
  {
    const double sum = L.col(j).cwiseAbs().sum();
    top = std::max(top, lumped[j] > 0.0 ? sum / lumped[j] : 0.0);
  }
  return AchievableResidual(top, diameter, ratio);
}

/// The settings and the state that SolveWithFallbacks shares across components.
struct Fallbacks
{
  EigenOptions Options;
  /// Diameter of the mesh: the scale of its lowest frequencies.
  double Diameter = 0.0;
  /// Whether each component's null space is its constants (EigenOptions::ConstantNullSpace).
  bool ConstantHarmonics = true;
  const Monitor* Warnings = nullptr;
  BasisResult* Basis = nullptr;
  /// Whether the relaxed tolerance was announced (once, whatever the number of components).
  bool Relaxed = false;
};

//------------------------------------------------------------------------------
// SmallestEigenpairs with the two fallbacks of the file documentation of Basis.h. Beyond
// MeaningfulResidual the eigenpairs would be meaningless: the failure is passed on with why.
EigenResult SolveWithFallbacks(const SparseMatrix& L,
  const SparseMatrix& M,
  const PairRequest& request,
  const Monitor& monitor,
  Fallbacks& state)
{
  EigenOptions options = state.Options;
  const int wanted = request.Count;
  options.NumberOfEigenpairs =
    (wanted == 1 && request.StartIndex == 0 && L.rows() > 1) ? 2 : wanted;
  options.StartIndex = request.StartIndex;
  options.StartValue = request.StartValue;
  // Every solve is of one connected component: with natural conditions its constant harmonic
  // is known, and deflated.
  options.ConstantNullSpace = state.ConstantHarmonics;
  EigenResult result;
  try
  {
    result = SmallestEigenpairs(L, M, options, monitor);
  }
  catch (const SolverFailure& e)
  {
    double ratio = 0.0;
    const double achievable = OperatorsAchievableResidual(L, M, state.Diameter, ratio);
    const Decision relaxed = Relaxation(options.ResidualTolerance, achievable, ratio);
    if (relaxed.Outcome == Verdict::Fail && relaxed.Error.empty())
    {
      throw;
    }
    if (relaxed.Outcome == Verdict::Fail)
    {
      throw SolverFailure(std::string(e.what()) + "; " + relaxed.Error, e.Converged);
    }
    if (!state.Relaxed)
    {
      Report({ relaxed.Warning }, *state.Warnings, *state.Basis);
      state.Relaxed = true;
    }
    options.ResidualTolerance = relaxed.ResidualTolerance;
    result = SmallestEigenpairs(L, M, options, monitor);
  }
  if (result.Eigenvalues.size() > wanted)
  {
    result.Eigenvalues.conservativeResize(wanted);
    if (result.Eigenvectors.cols() > wanted)
    {
      result.Eigenvectors.conservativeResize(Eigen::NoChange, wanted);
    }
  }
  return result;
}

//------------------------------------------------------------------------------
// Leaves out the rows of the points that no harmonic represents (components beyond the m
// smallest eigenpairs: every component's constant harmonic comes first, so a component is
// represented by all of its rows or by none), with a warning: they get zero harmonics and mass,
// as points no triangle uses, so that no filter downstream moves them.
void LeaveOutUnrepresented(BasisResult& result, const Monitor& monitor)
{
  DenseMatrix& H = result.Pairs.Eigenvectors;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < H.rows(); ++i)
  {
    if ((H.row(i).array() != 0.0).any())
    {
      keep.push_back(i);
    }
  }
  const Eigen::Index left = H.rows() - static_cast<Eigen::Index>(keep.size());
  if (left == 0)
  {
    return;
  }
  H = DenseMatrix(H(keep, Eigen::all));
  result.LumpedMass = Vector(result.LumpedMass(keep));
  std::vector<int> ids;
  for (Eigen::Index i : keep)
  {
    ids.push_back(result.InputPointIds[static_cast<std::size_t>(i)]);
  }
  result.InputPointIds = std::move(ids);
  Report(
    { std::to_string(left) + " points of components that none of the " + std::to_string(H.cols()) +
      " harmonics represents are left out: their harmonics and mass are 0, and the "
      "filters pass them through unchanged." },
    monitor,
    result);
}

//------------------------------------------------------------------------------
// The eigensolve stage of ComputeBasis: each connected component with the fallbacks, the m
// smallest pairs or those of the frequency window.
EigenResult SolveProblem(const TriangleMesh& mesh,
  const Problem& problem,
  const BasisOptions& options,
  const Monitor& monitor,
  BasisResult& result)
{
  const DiscreteLaplacian& ops = problem.Operators;
  Fallbacks state;
  state.Options = options.Solver;
  state.Options.KeepEigenvectors = !options.EigenvaluesOnly;
  state.Diameter = ops.Diameter;
  state.ConstantHarmonics = ops.ConstantHarmonics;
  state.Warnings = &monitor;
  state.Basis = &result;
  const PairSolver solve =
    [&state](
      const SparseMatrix& L, const SparseMatrix& M, const PairRequest& request, const Monitor& part)
  { return SolveWithFallbacks(L, M, request, part, state); };
  if (!problem.Window)
  {
    return SmallestEigenpairsByComponent(ops.Stiffness,
      ops.Mass,
      ops.LumpedMass,
      ops.Components.Label,
      ops.Components.Count,
      problem.Harmonics,
      solve,
      monitor.Scaled(0.1, 1.0),
      ops.ConstantHarmonics);
  }
  // Each component from the lower end of the window up: the bands start there. Its pairs are
  // counted first (the inertia of L - omega^2 M at both ends, per component).
  const auto counted = [&](int below, int inWindow)
  {
    if (inWindow <= 0)
    {
      throw InvalidInput(EmptyWindow(options.LowerFrequency, options.UpperFrequency, below));
    }
    if (options.CheckMemory)
    {
      CheckMemory(mesh, ops.Stiffness.rows(), inWindow, options);
    }
    ReportComponentsOf(problem, inWindow, monitor, result);
  };
  return EigenpairsInWindowByComponent(ops.Stiffness,
    ops.Mass,
    ops.Components.Label,
    ops.Components.Count,
    problem.WindowEigenvalues.first,
    problem.WindowEigenvalues.second,
    solve,
    counted,
    result.FirstIndex,
    monitor.Scaled(0.1, 1.0));
}

//------------------------------------------------------------------------------
} // anonymous namespace

//------------------------------------------------------------------------------
double UnitScale(double diameter)
{
  if (!(diameter > 0.0) || !std::isfinite(diameter))
  {
    return 1.0;
  }
  return std::ldexp(1.0, std::ilogb(diameter));
}

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
  Problem problem = PrepareProblem(mesh, options, monitor, result);
  result.AssemblySeconds = std::chrono::duration<double>(Clock::now() - start).count();
  monitor.Report(0.1);
  monitor.ThrowIfCancelled();

  monitor.Begin("Eigensolve");
  result.Pairs = SolveProblem(mesh, problem, options, monitor, result);
  // The mass is an area (a volume) and scales as s^d, d = 2 (3); M-normalized harmonics as
  // s^(-d/2).
  const double s = problem.Scale;
  const double d = problem.Dimension;
  result.Pairs.Eigenvalues /= s * s;
  result.Pairs.Eigenvectors /= std::pow(s, 0.5 * d);
  result.LumpedMass = problem.Operators.LumpedMass * std::pow(s, d);
  result.InputPointIds = std::move(problem.Operators.InputPointIds);
  LeaveOutUnrepresented(result, monitor);
  if (options.EigenvaluesOnly)
  {
    result.Pairs.Eigenvectors.resize(0, 0);
  }
  return result;
}
} // namespace spectral
