// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Basis.h"

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
// Passes the warnings on to the monitor and keeps them in the result.
void Report(const std::vector<std::string>& warnings, const Monitor& monitor, BasisResult& result)
{
  for (const std::string& text : warnings)
  {
    result.Warnings.push_back(text);
    monitor.Warn(text);
  }
}
//------------------------------------------------------------------------------
// Number of harmonics to compute: the request, clamped with a warning to the usable points.
int ClampedHarmonics(int requested,
  int usable,
  const std::string& what,
  const Monitor& monitor,
  BasisResult& result)
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
  Report({ "NumberOfHarmonics " + std::to_string(requested) + " clamped to " +
           std::to_string(usable) + ", the number of points " + what + "." },
    monitor,
    result);
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
    options.EigenvaluesOnly ? 0 : options.BytesPerValue,
    !options.EigenvaluesOnly,
    mesh.IsVolume());
  const std::uint64_t available = options.MemoryLimit > 0 ? options.MemoryLimit : AvailableMemory();
  if (available != 0 && need.Total() > available)
  {
    throw InsufficientMemory(need, available, m);
  }
}

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
    if (!(achievable > options.ResidualTolerance))
    {
      throw;
    }
    if (achievable > MeaningfulResidual)
    {
      throw SolverFailure(std::string(e.what()) + "; " + UnresolvableResidual(ratio), e.Converged);
    }
    if (!state.Relaxed)
    {
      Report({ RelaxedResidualWarning(achievable, options.ResidualTolerance, ratio) },
        *state.Warnings,
        *state.Basis);
      state.Relaxed = true;
    }
    options.ResidualTolerance = achievable;
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
// Warnings about the components, before the solve: how many zero eigenvalues they give, how to
// weld unwelded seams, and a request for no more harmonics than components.
void ReportComponents(int components, int m, const Monitor& monitor, BasisResult& result)
{
  if (components <= 1)
  {
    return;
  }
  const std::string count = std::to_string(components);
  Report({ "The surface has " + count + " connected components: the first " + count +
           " eigenvalues are zero, one for each. If they are pieces of one surface whose "
           "seams are not welded, weld them: WeldSeams on, with a SeamTolerance above the gap "
           "between the copies of a seam point (or vtkCleanPolyData, Clean in ParaView, with a "
           "tolerance); leave out small debris with MinimumComponentSize." },
    monitor,
    result);
  if (m <= components)
  {
    Report({ "NumberOfHarmonics " + std::to_string(m) + " does not exceed the " + count +
             " connected components: every harmonic is constant on one component (eigenvalue "
             "0), so filtering can only move whole components. Ask for more than " +
             count + " harmonics, or leave out small components with MinimumComponentSize." },
      monitor,
      result);
  }
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
// The frequency window in the units of the operators (frequencies times s), checked.
std::pair<double, double> Window(const BasisOptions& options, double s)
{
  const double low = options.LowerFrequency * s;
  const double high = options.UpperFrequency * s;
  if (!(options.LowerFrequency >= 0.0) || !(high > low) || !std::isfinite(high))
  {
    throw InvalidInput("the frequency window [" + std::to_string(options.LowerFrequency) + ", " +
      std::to_string(options.UpperFrequency) + ") must have 0 <= lower < upper < infinity");
  }
  return { low, high };
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
  const bool window = options.UpperFrequency > 0.0;
  const bool cloud = mesh.IsPointCloud();
  PreparedMesh prepared;
  DiscreteLaplacian ops;
  int m = 0;
  double s = 1.0;
  if (cloud)
  {
    // A point cloud: the operators of PointCloudLaplacian, in the same units as a mesh's.
    if (options.Operators.Laplacian != LaplacianKind::Cotangent ||
      options.Operators.Boundary != BoundaryCondition::Neumann || options.MinimumComponentSize > 0)
    {
      Report({ "A point cloud has its own Laplacian (Sharp and Crane's, on the local Delaunay "
               "triangulations of its neighbourhoods) with natural conditions: the Laplacian, "
               "BoundaryCondition and MinimumComponentSize settings do not apply to it." },
        monitor,
        result);
    }
    // Every point of a cloud is a candidate, and the unit comes from all of them: a coordinate
    // beyond MaxCoordinate (even of a point left out later) would make the others vanish in it.
    for (Eigen::Index i = 0; i < mesh.Vertices.rows(); ++i)
    {
      CheckCoordinates(mesh.Vertices, i);
    }
    s = UnitScale(BoundingBoxDiagonal(mesh.Vertices));
    PointCloudOptions cloudOptions;
    cloudOptions.NumberOfNeighbors = options.NumberOfNeighbors;
    cloudOptions.Mass = options.Operators.Mass;
    ops = PointCloudLaplacian(Points(mesh.Vertices / s), cloudOptions, monitor.Scaled(0.0, 0.1));
    Report(ops.Warnings, monitor, result);
    const Eigen::Index used = ops.Stiffness.rows();
    if (!window)
    {
      m = ClampedHarmonics(options.NumberOfHarmonics,
        static_cast<int>(used),
        "the point cloud triangulates",
        monitor,
        result);
      if (options.CheckMemory)
      {
        CheckMemory(mesh, used, m, options);
      }
    }
  }
  else
  {
    prepared = LeaveOutSmallComponents(PrepareMesh(mesh), options.MinimumComponentSize);
    Report(PreparationWarnings(prepared), monitor, result);
    const Eigen::Index used = prepared.Mesh.Vertices.rows();
    if (used == 0)
    {
      throw InvalidInput(prepared.SmallComponents > 0
          ? "every connected component is smaller than MinimumComponentSize"
          : prepared.Volume ? "every tetrahedron of the input is degenerate (zero volume)"
                            : "every triangle of the input is degenerate (zero area)");
    }
    m = window ? 0
               : ClampedHarmonics(options.NumberOfHarmonics,
                   static_cast<int>(used),
                   prepared.Volume ? "tetrahedra use" : "triangles use",
                   monitor,
                   result);
    if (options.CheckMemory && !window)
    {
      CheckMemory(mesh, used, m, options);
    }

    // The operators of the mesh in units of its size: lambda scales as 1 / s^2, the mass (an
    // area or a volume) as s^d, the M-normalized harmonics as s^(-d/2).
    s = UnitScale(BoundingBoxDiagonal(prepared.Mesh.Vertices));
    prepared.Mesh.Vertices /= s;
    ops = AssembleLaplacian(prepared, options.Operators, monitor);
    Report(ops.Warnings, monitor, result);
  }
  const Eigen::Index used = ops.Stiffness.rows();
  result.BoundaryPoints = ops.BoundaryPoints;
  if (!window && ops.Stiffness.rows() < m)
  {
    m = ClampedHarmonics(
      m, static_cast<int>(ops.Stiffness.rows()), "inside the boundary", monitor, result);
  }
  const std::pair<double, double> range = window ? Window(options, s) : std::make_pair(0.0, 0.0);
  result.Components = ops.Components.Count;
  result.ConstantHarmonics = ops.ConstantHarmonics;
  if (ops.ConstantHarmonics && !window)
  {
    ReportComponents(result.Components, m, monitor, result);
  }
  result.AssemblySeconds = std::chrono::duration<double>(Clock::now() - start).count();
  monitor.Report(0.1);
  monitor.ThrowIfCancelled();

  monitor.Begin("Eigensolve");
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
  if (window)
  {
    // Each component from the lower end of the window up: the bands start there. Its pairs are
    // counted first (the inertia of L - omega^2 M at both ends, per component).
    const auto counted = [&](int below, int inWindow)
    {
      if (inWindow <= 0)
      {
        throw InvalidInput("no eigenvalue lies in the frequency window [" +
          std::to_string(options.LowerFrequency) + ", " + std::to_string(options.UpperFrequency) +
          "): " + std::to_string(below) + " lie below it");
      }
      if (options.CheckMemory)
      {
        CheckMemory(mesh, used, inWindow, options);
      }
      if (ops.ConstantHarmonics)
      {
        ReportComponents(result.Components, inWindow, monitor, result);
      }
    };
    result.Pairs = EigenpairsInWindowByComponent(ops.Stiffness,
      ops.Mass,
      ops.Components.Label,
      ops.Components.Count,
      range.first * range.first,
      range.second * range.second,
      solve,
      counted,
      result.FirstIndex,
      monitor.Scaled(0.1, 1.0));
  }
  else
  {
    result.Pairs = SmallestEigenpairsByComponent(ops.Stiffness,
      ops.Mass,
      ops.LumpedMass,
      ops.Components.Label,
      ops.Components.Count,
      m,
      solve,
      monitor.Scaled(0.1, 1.0),
      ops.ConstantHarmonics);
  }
  // The mass is an area (a volume) and scales as s^d, d = 2 (3); M-normalized harmonics as
  // s^(-d/2).
  const double d = prepared.Volume ? 3.0 : 2.0;
  result.Pairs.Eigenvalues /= s * s;
  result.Pairs.Eigenvectors /= std::pow(s, 0.5 * d);
  result.LumpedMass = ops.LumpedMass * std::pow(s, d);
  result.InputPointIds = std::move(ops.InputPointIds);
  LeaveOutUnrepresented(result, monitor);
  if (options.EigenvaluesOnly)
  {
    result.Pairs.Eigenvectors.resize(0, 0);
  }
  return result;
}
} // namespace spectral
