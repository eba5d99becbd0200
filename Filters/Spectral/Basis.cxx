// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Basis.h"
#include "Problem.h"

#include "Common/Constants.h"
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
// The options of one solve of `request` on one connected component (L has its rows).
EigenOptions RequestOptions(const Fallbacks& state, const PairRequest& request, Eigen::Index rows)
{
  EigenOptions options = state.Options;
  const int wanted = request.Count;
  options.NumberOfEigenpairs = (wanted == 1 && request.StartIndex == 0 && rows > 1) ? 2 : wanted;
  options.StartIndex = request.StartIndex;
  options.StartValue = request.StartValue;
  // Every solve is of one connected component: with natural conditions its constant harmonic
  // is known, and deflated.
  options.ConstantNullSpace = state.ConstantHarmonics;
  return options;
}

//------------------------------------------------------------------------------
// After the failure `e` of a solve verified to `tolerance`: the relaxed tolerance to solve again
// with (its warning reported once), or the failure passed on, with why beyond
// MeaningfulResidual (the eigenpairs would be meaningless).
double RelaxedTolerance(const SparseMatrix& L,
  const SparseMatrix& M,
  double tolerance,
  const SolverFailure& e,
  Fallbacks& state)
{
  double ratio = 0.0;
  const double achievable = OperatorsAchievableResidual(L, M, state.Diameter, ratio);
  const Decision relaxed = Relaxation(tolerance, achievable, ratio);
  if (relaxed.Outcome == Verdict::Fail && relaxed.Error.empty())
  {
    throw e;
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
  return relaxed.ResidualTolerance;
}

//------------------------------------------------------------------------------
// SmallestEigenpairs with the two fallbacks of the file documentation of Basis.h.
EigenResult SolveWithFallbacks(const SparseMatrix& L,
  const SparseMatrix& M,
  const PairRequest& request,
  const Monitor& monitor,
  Fallbacks& state)
{
  EigenOptions options = RequestOptions(state, request, L.rows());
  const int wanted = request.Count;
  EigenResult result;
  try
  {
    result = SmallestEigenpairs(L, M, options, monitor);
  }
  catch (const SolverFailure& e)
  {
    options.ResidualTolerance = RelaxedTolerance(L, M, options.ResidualTolerance, e, state);
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
// Keeps the rows `keep` (ascending) of the result's harmonics (if any), mass and ids, with the
// warning about the points of the m harmonics' unrepresented components it leaves out.
void KeepRows(BasisResult& result,
  const std::vector<Eigen::Index>& keep,
  const Monitor& monitor,
  int m)
{
  const Eigen::Index left = result.LumpedMass.size() - static_cast<Eigen::Index>(keep.size());
  if (left == 0)
  {
    return;
  }
  DenseMatrix& H = result.Pairs.Eigenvectors;
  if (H.size() > 0)
  {
    H = DenseMatrix(H(keep, Eigen::all));
  }
  result.LumpedMass = Vector(result.LumpedMass(keep));
  std::vector<int> ids;
  for (Eigen::Index i : keep)
  {
    ids.push_back(result.InputPointIds[static_cast<std::size_t>(i)]);
  }
  result.InputPointIds = std::move(ids);
  Report({ std::to_string(left) + " points of components that none of the " + std::to_string(m) +
           " harmonics represents are left out: their harmonics and mass are 0, and the "
           "filters pass them through unchanged." },
    monitor,
    result);
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
  KeepRows(result, keep, monitor, static_cast<int>(H.cols()));
}

//------------------------------------------------------------------------------
// The eigensolver's settings of a problem: the caller's, in bands of the size the memory plan
// chose (CheckMemory; with a frequency window, once its pairs are counted).
EigenOptions PlannedSolverOptions(const Problem& problem, const BasisOptions& options)
{
  EigenOptions solver = options.Solver;
  solver.BandSize = problem.BandSize > 0 ? problem.BandSize : solver.BandSize;
  return solver;
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
  state.Options = PlannedSolverOptions(problem, options);
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
      state.Options.BandSize =
        CheckMemory(mesh, ops.Stiffness.rows(), inWindow, options, monitor, result);
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
// Thrown inside a streamed pass when a component's solve failed after delivering pairs: the
// pass starts over (BasisSink::Restart) with the component's relaxed tolerance.
struct StreamRestart
{
};

//------------------------------------------------------------------------------
// The number of eigenvalues below sigma (CountEigenvaluesBelow); a shift that is an eigenvalue
// (the factorization fails) moves up by a relative 1e-9 and counts again.
int CountBelow(const SparseMatrix& L, const SparseMatrix& M, double& sigma)
{
  for (int attempt = 0;; ++attempt)
  {
    try
    {
      return CountEigenvaluesBelow(L, M, sigma);
    }
    catch (const SolverFailure&)
    {
      if (attempt == 3)
      {
        throw;
      }
      sigma += 1e-9 * std::max(std::abs(sigma), 1e-300);
    }
  }
}

//------------------------------------------------------------------------------
// How far below lambda_{m-1} HighestOfSmallest's shift may count (its solve computes the pairs
// from there on): a twentieth of m, at least 20 pairs.
int HighestWindow(int m)
{
  return std::max(20, m / 20);
}

//------------------------------------------------------------------------------
// lambda_{m-1} of a connected component's L h = lambda M h, without the pairs far below it.
// Inertia counts (CountBelow) look for a shift sigma with c eigenvalues below it,
// m - 1 - HighestWindow(m) <= c <= m - 1; the solve of the m - c pairs from sigma on
// (PairRequest::StartIndex c) then ends at lambda_{m-1}, proven as every band is. The first
// shift comes from Weyl's law, N(lambda) ~ C lambda^(d/2) with C = |M| / (4 pi) on a surface
// (d = 2) and |M| / (6 pi^2) in a volume (d = 3), |M| = 1^T M 1 its area or volume; each next
// one from the last count by the same law, kept inside the bracket of the counts so far. After
// HighestCounts counts without such a shift, the best one below lambda_{m-1} serves (a longer
// solve; from 0, the whole spectrum). `statistics` receives the solve's, and the counts'
// factorizations. Progress: each count a share of HighestCounts in the first half, the solve
// the rest.
constexpr int HighestCounts = 12;
double HighestOfSmallest(const SparseMatrix& L,
  const SparseMatrix& M,
  int m,
  int dimension,
  const PairSolver& solve,
  const Monitor& monitor,
  EigenResult& statistics)
{
  const int window = HighestWindow(m);
  const double target = std::max(0.5, m - 1 - 0.5 * window);
  const double exponent = 2.0 / dimension;
  const double measure = M.sum();
  const double weyl = measure / (dimension == 3 ? 6.0 * Pi * Pi : 4.0 * Pi);
  double sigma = std::pow(target / weyl, exponent);
  double low = 0.0; // the best shift below lambda_{m-1} so far, and its count
  int lowCount = 0;
  double high = std::numeric_limits<double>::infinity();
  int counts = 0;
  while (counts < HighestCounts && std::isfinite(sigma) && sigma > 0.0)
  {
    monitor.ThrowIfCancelled();
    const int count = CountBelow(L, M, sigma);
    ++counts;
    monitor.Report(0.5 * counts / HighestCounts);
    if (count <= m - 1)
    {
      if (count >= lowCount)
      {
        low = sigma;
        lowCount = count;
      }
      if (count >= m - 1 - window)
      {
        break;
      }
    }
    else
    {
      high = std::min(high, sigma);
    }
    double next = sigma * std::pow(target / std::max(count, 1), exponent);
    if (!(next > low && next < high))
    {
      next = std::isfinite(high) ? 0.5 * (low + high) : 2.0 * sigma;
    }
    sigma = next;
  }
  statistics = solve(L,
    M,
    PairRequest{ m - lowCount, lowCount, low },
    monitor.Scaled(0.5 * counts / HighestCounts, 1.0));
  statistics.Factorizations += counts;
  const Vector& values = statistics.Eigenvalues;
  if (values.size() != m - lowCount)
  {
    throw SolverFailure("the solve below the highest eigenvalue returned " +
        std::to_string(values.size()) + " of " + std::to_string(m - lowCount) + " pairs",
      static_cast<int>(values.size()));
  }
  return values[values.size() - 1];
}

/// A streamed basis (BasisSink): which pairs of which component go where, and what came.
class Stream
{
public:
  Stream(const Problem& problem,
    const BasisOptions& options,
    const Monitor& monitor,
    BasisResult& result)
    : Ops(problem.Operators)
    , Options(options)
    , Sink(options.Sink)
    , Watch(monitor)
    , Result(result)
    , ValueScale(problem.Scale * problem.Scale)
    , VectorScale(std::pow(problem.Scale, 0.5 * problem.Dimension))
    , Harmonics(problem.Harmonics)
    , Dimension(problem.Dimension)
  {
    this->State.Options = PlannedSolverOptions(problem, options);
    this->State.Options.KeepEigenvectors = false;
    this->State.Diameter = this->Ops.Diameter;
    this->State.ConstantHarmonics = this->Ops.ConstantHarmonics;
    this->State.Warnings = &monitor;
    this->State.Basis = &result;
  }

  /// The whole stream: the plan (a spectrum first where needed), Begin, then the harmonics.
  void Run(double massScale);

private:
  void Decide();
  void Plan(const Monitor& monitor);
  ComponentChoice WantedPass(int& expected) const;
  void KeepRepresented(double massScale);
  void SolveComponent(int component,
    const std::vector<int>& rows,
    const SparseMatrix& L,
    const SparseMatrix& M,
    const PairRequest& request,
    const Monitor& monitor);
  void Deliver(int component,
    const std::vector<int>& rows,
    int first,
    const Vector& values,
    const DenseMatrix& vectors);

  const DiscreteLaplacian& Ops;
  const BasisOptions& Options;
  const BasisSink& Sink;
  const Monitor& Watch;
  BasisResult& Result;
  /// Eigenvalues are divided by ValueScale, harmonics by VectorScale (as ComputeBasis does).
  const double ValueScale;
  const double VectorScale;
  const int Harmonics;
  const int Dimension;
  /// Whether the plan found lambda_{m-1} alone (one component, BasisSink::HighestFirst), or
  /// the whole spectrum (SpectrumFirst, or several components).
  bool HighestOnly = false;
  bool Planned = false;
  Fallbacks State;
  ComponentChoice Choice;
  /// For each component, the basis index of each of its pairs (-1: not in the basis).
  std::vector<std::vector<int>> Index;
  /// For each row of the operators, its row in the delivered harmonics (-1: left out).
  std::vector<Eigen::Index> Position;
  Eigen::Index Rows = 0;
  /// Whether each index was delivered (in this pass), and how many were.
  std::vector<bool> Delivered;
  int DeliveredCount = 0;
  /// Pairs delivered by the current component's solve.
  int FromComponent = 0;
  /// For each component, the pairs its solve in the streamed pass is asked for (WantedPass).
  std::vector<int> PassAsked;
};

//------------------------------------------------------------------------------
// What the plan solves first: lambda_{m-1} alone where the sink needs no more (HighestFirst) and
// that is cheaper than the spectrum (one component, past the dense solver's sizes, more pairs
// than two windows of HighestOfSmallest); the whole spectrum where the sink asks for it or
// several components must share the m pairs; nothing otherwise.
void Stream::Decide()
{
  const int count = this->Ops.Components.Count;
  this->HighestOnly = this->Sink.HighestFirst && !this->Sink.SpectrumFirst && count <= 1 &&
    this->Ops.Stiffness.rows() > this->State.Options.DenseThreshold &&
    this->Harmonics > 2 * HighestWindow(this->Harmonics);
  this->Planned =
    !this->HighestOnly && (this->Sink.SpectrumFirst || this->Sink.HighestFirst || count > 1);
}

//------------------------------------------------------------------------------
// Which component's pairs go where: from a spectrum alone with several components (or when the
// sink asks for it first), otherwise the one component's m pairs in order.
void Stream::Plan(const Monitor& monitor)
{
  const int count = this->Ops.Components.Count;
  const PairSolver solveOne =
    [this](
      const SparseMatrix& L, const SparseMatrix& M, const PairRequest& request, const Monitor& part)
  { return SolveWithFallbacks(L, M, request, part, this->State); };
  if (this->HighestOnly)
  {
    EigenResult statistics;
    const double highest = HighestOfSmallest(this->Ops.Stiffness,
      this->Ops.Mass,
      this->Harmonics,
      this->Dimension,
      solveOne,
      monitor,
      statistics);
    statistics.Eigenvalues =
      Vector::Constant(this->Harmonics, std::numeric_limits<double>::quiet_NaN());
    statistics.Eigenvalues[this->Harmonics - 1] = highest / this->ValueScale;
    this->Result.Pairs = std::move(statistics);
  }
  if (this->Planned)
  {
    EigenResult spectrum = SmallestEigenpairsByComponent(this->Ops.Stiffness,
      this->Ops.Mass,
      this->Ops.LumpedMass,
      this->Ops.Components.Label,
      count,
      this->Harmonics,
      solveOne,
      monitor,
      this->Ops.ConstantHarmonics,
      &this->Choice);
    this->Result.Pairs = std::move(spectrum);
    this->Result.Pairs.Eigenvalues /= this->ValueScale;
  }
  else
  {
    this->Choice.Asked = { this->Harmonics };
    this->Choice.Tolerance = { this->State.Options.ResidualTolerance };
    for (int k = 0; k < this->Harmonics; ++k)
    {
      this->Choice.Pairs.emplace_back(0, k);
    }
  }
  this->Index.assign(static_cast<std::size_t>(std::max(count, 1)), std::vector<int>());
  for (std::size_t j = 0; j < this->Choice.Pairs.size(); ++j)
  {
    const auto [component, k] = this->Choice.Pairs[j];
    std::vector<int>& index = this->Index[static_cast<std::size_t>(component)];
    if (static_cast<int>(index.size()) <= k)
    {
      index.resize(static_cast<std::size_t>(k) + 1, -1);
    }
    index[static_cast<std::size_t>(k)] = static_cast<int>(j);
  }
}

//------------------------------------------------------------------------------
// The solves of the streamed pass: the plan's, each component asked only up to its last pair at
// or below the sink's BasisSink::WantedUpTo and the pairs of the same eigenvalue after it
// (StreamedClusterGap); a component with no wanted pair is not solved. With the highest
// eigenvalue alone known (HighestOnly), an inertia count gives how many pairs lie there.
// `expected` is set to the number of basis pairs the pass delivers.
ComponentChoice Stream::WantedPass(int& expected) const
{
  ComponentChoice pass = this->Choice;
  expected = static_cast<int>(this->Choice.Pairs.size());
  const Vector& lambda = this->Result.Pairs.Eigenvalues;
  if (!this->Sink.WantedUpTo || lambda.size() != expected)
  {
    return pass;
  }
  const double bound = this->Sink.WantedUpTo();
  if (!(bound < lambda[expected - 1]))
  {
    return pass;
  }
  const double reach = bound + StreamedClusterGap * std::abs(bound);
  if (this->HighestOnly)
  {
    double shift = reach * this->ValueScale;
    // At least two pairs: the first non-constant harmonic, whose eigenvalue the filter's
    // warnings name, comes with the constant one.
    const int count = bound < 0.0 ? 0 : CountBelow(this->Ops.Stiffness, this->Ops.Mass, shift);
    expected = std::min(std::max(count, 2), expected);
    pass.Asked = { expected };
    pass.Pairs.resize(static_cast<std::size_t>(expected));
    return pass;
  }
  // Each component's pairs are a prefix of its spectrum, in ascending order.
  std::vector<int> upTo(pass.Asked.size(), 0);
  pass.Pairs.clear();
  for (int j = 0; j < expected; ++j)
  {
    const auto [component, k] = this->Choice.Pairs[static_cast<std::size_t>(j)];
    if (lambda[j] <= reach)
    {
      pass.Pairs.emplace_back(component, k);
      int& count = upTo[static_cast<std::size_t>(component)];
      count = std::max(count, k + 1);
    }
  }
  for (std::size_t c = 0; c < upTo.size(); ++c)
  {
    pass.Asked[c] = std::min(pass.Asked[c], upTo[c]);
  }
  expected = static_cast<int>(pass.Pairs.size());
  return pass;
}

//------------------------------------------------------------------------------
// The rows of the components that a pair represents, as LeaveOutUnrepresented keeps them.
void Stream::KeepRepresented(double massScale)
{
  const std::vector<int>& label = this->Ops.Components.Label;
  const Eigen::Index n = this->Ops.Stiffness.rows();
  std::vector<Eigen::Index> keep;
  this->Position.assign(static_cast<std::size_t>(n), -1);
  for (Eigen::Index i = 0; i < n; ++i)
  {
    const std::size_t c = this->Ops.Components.Count > 1
      ? static_cast<std::size_t>(label[static_cast<std::size_t>(i)])
      : 0;
    if (!this->Index[c].empty())
    {
      this->Position[static_cast<std::size_t>(i)] = static_cast<Eigen::Index>(keep.size());
      keep.push_back(i);
    }
  }
  this->Rows = static_cast<Eigen::Index>(keep.size());
  this->Result.LumpedMass = this->Ops.LumpedMass * massScale;
  this->Result.InputPointIds = this->Ops.InputPointIds;
  KeepRows(this->Result, keep, this->Watch, static_cast<int>(this->Choice.Pairs.size()));
}

//------------------------------------------------------------------------------
// The pairs first, first + 1, ... of a component's solve: in runs of consecutive basis indices,
// on the delivered rows, in the mesh's units.
void Stream::Deliver(int component,
  const std::vector<int>& rows,
  int first,
  const Vector& values,
  const DenseMatrix& vectors)
{
  const std::vector<int>& index = this->Index[static_cast<std::size_t>(component)];
  const int count = static_cast<int>(values.size());
  for (int k = 0; k < count;)
  {
    const int local = first + k;
    // Pairs beyond the pass's request (a solve asked for 1 pair computes 2) are not delivered.
    const int passed = std::min(
      static_cast<int>(index.size()), this->PassAsked[static_cast<std::size_t>(component)]);
    if (local >= passed || index[static_cast<std::size_t>(local)] < 0)
    {
      ++k;
      continue;
    }
    const int start = index[static_cast<std::size_t>(local)];
    int run = 1;
    while (run < StreamedBlockColumns && k + run < count && local + run < passed &&
      index[static_cast<std::size_t>(local + run)] == start + run)
    {
      ++run;
    }
    DenseMatrix harmonics = DenseMatrix::Zero(this->Rows, run);
    for (std::size_t r = 0; r < rows.size(); ++r)
    {
      const Eigen::Index row = this->Position[static_cast<std::size_t>(rows[r])];
      harmonics.row(row) = vectors.row(static_cast<Eigen::Index>(r)).segment(k, run);
    }
    harmonics /= this->VectorScale;
    const Vector lambda = values.segment(k, run) / this->ValueScale;
    for (int j = 0; j < run; ++j)
    {
      if (this->Delivered[static_cast<std::size_t>(start + j)])
      {
        throw SolverFailure(
          "the streamed basis delivered pair " + std::to_string(start + j) + " twice", 0);
      }
      this->Delivered[static_cast<std::size_t>(start + j)] = true;
      this->Result.Pairs.Eigenvalues[start + j] = lambda[j];
    }
    this->DeliveredCount += run;
    this->FromComponent += run;
    this->Sink.Harmonics(start, lambda, harmonics);
    k += run;
  }
}

//------------------------------------------------------------------------------
// One component's solve with the request the plan recorded, streaming its pairs; a failure
// after some were delivered restarts the pass with the relaxed tolerance.
void Stream::SolveComponent(int component,
  const std::vector<int>& rows,
  const SparseMatrix& L,
  const SparseMatrix& M,
  const PairRequest& request,
  const Monitor& monitor)
{
  double& tolerance = this->Choice.Tolerance[static_cast<std::size_t>(component)];
  EigenOptions options = RequestOptions(this->State, request, L.rows());
  options.ResidualTolerance = tolerance;
  options.Deliver = [this, component, &rows](
                      int first, const Vector& values, const DenseMatrix& vectors)
  { this->Deliver(component, rows, first, values, vectors); };
  this->FromComponent = 0;
  EigenResult solved;
  try
  {
    solved = SmallestEigenpairs(L, M, options, monitor);
  }
  catch (const SolverFailure& e)
  {
    tolerance = RelaxedTolerance(L, M, tolerance, e, this->State);
    if (this->FromComponent > 0)
    {
      throw StreamRestart();
    }
    options.ResidualTolerance = tolerance;
    solved = SmallestEigenpairs(L, M, options, monitor);
  }
  AddStatistics(this->Result.Pairs, solved);
}

//------------------------------------------------------------------------------
void Stream::Run(double massScale)
{
  this->Decide();
  // The share of the progress of what the plan solves first (Decide).
  const double planned = this->Planned ? 0.55 : (this->HighestOnly ? 0.2 : 0.1);
  this->Plan(this->Watch.Scaled(0.1, planned));
  this->KeepRepresented(massScale);
  const int m = static_cast<int>(this->Choice.Pairs.size());
  if (!this->Planned && !this->HighestOnly)
  {
    this->Result.Pairs = EigenResult();
  }
  if (this->Sink.Begin)
  {
    this->Sink.Begin(this->Result);
  }
  int expected = m;
  const ComponentChoice pass =
    this->Planned || this->HighestOnly ? this->WantedPass(expected) : this->Choice;
  this->PassAsked = pass.Asked;
  this->Result.Pairs.Eigenvalues.conservativeResize(m);
  const Monitor streamPart = this->Watch.Scaled(planned, 1.0);
  const ComponentSolver solve = [this](int component,
                                  const std::vector<int>& rows,
                                  const SparseMatrix& L,
                                  const SparseMatrix& M,
                                  const PairRequest& request,
                                  const Monitor& part)
  { this->SolveComponent(component, rows, L, M, request, part); };
  while (true)
  {
    this->Delivered.assign(static_cast<std::size_t>(m), false);
    this->DeliveredCount = 0;
    try
    {
      ForEachChosenComponent(this->Ops.Stiffness,
        this->Ops.Mass,
        this->Ops.Components.Label,
        this->Ops.Components.Count,
        pass,
        solve,
        streamPart);
      break;
    }
    catch (const StreamRestart&)
    {
      if (!this->Sink.Restart)
      {
        throw SolverFailure("a streamed solve failed its residual test after delivering pairs, "
                            "and the sink cannot start over (BasisSink::Restart)",
          0);
      }
      this->Sink.Restart();
    }
  }
  if (this->DeliveredCount != expected)
  {
    throw SolverFailure("the streamed basis delivered " + std::to_string(this->DeliveredCount) +
        " of its " + std::to_string(expected) + " pairs",
      this->DeliveredCount);
  }
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
  int harmonics,
  bool streamed)
  : std::runtime_error("not enough memory for " + std::to_string(harmonics) +
      (streamed ? " streamed" : "") + " harmonics: " + std::to_string(needed.Total()) +
      " bytes needed, " + std::to_string(available) + " available")
  , Harmonics(harmonics)
  , Streamed(streamed)
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
  const bool streamed = static_cast<bool>(options.Sink.Harmonics);
  if (streamed && IsFrequencyWindow(options.LowerFrequency, options.UpperFrequency))
  {
    throw InvalidInput("a frequency window is not streamed: compute its basis in memory");
  }
  monitor.Begin("Assemble");
  Problem problem = PrepareProblem(mesh, options, monitor, result);
  result.AssemblySeconds = std::chrono::duration<double>(Clock::now() - start).count();
  monitor.Report(0.1);
  monitor.ThrowIfCancelled();

  monitor.Begin("Eigensolve");
  if (streamed)
  {
    Stream(problem, options, monitor, result).Run(std::pow(problem.Scale, problem.Dimension));
    monitor.Report(1.0);
    return result;
  }
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
