// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Problem.h"

#include "Common/BasisFile.h" // ByteCount
#include "Solver/Diagnostics.h"

#include <cmath>

namespace spectral
{
//------------------------------------------------------------------------------
std::string NoMoreHarmonicsThanComponents(int m, int components)
{
  const std::string count = std::to_string(components);
  return "NumberOfHarmonics " + std::to_string(m) + " does not exceed the " + count +
    " connected components: every harmonic is constant on one component (eigenvalue 0), so a "
    "spectral filter cannot smooth or enhance a component: it scales each component's centroid by "
    "the gain at frequency 0 and the offsets from it by one gain (with the default low pass the "
    "points of each component with a harmonic move to its centroid). Ask for more than " +
    count + " harmonics, or leave out small components with MinimumComponentSize.";
}

namespace
{
//------------------------------------------------------------------------------
// ClampHarmonics with its warning reported.
int Clamped(int requested,
  long long usable,
  const std::string& what,
  const Monitor& monitor,
  BasisResult& result)
{
  std::string warning;
  const int m = ClampHarmonics(requested, usable, what, warning);
  if (!warning.empty())
  {
    Report({ warning }, monitor, result);
  }
  return m;
}

//------------------------------------------------------------------------------
// Warnings about the components, before the solve: how many zero eigenvalues they give, how to
// weld unwelded seams, and a request for no more harmonics than components.
void ReportComponents(const Problem& problem, int m, const Monitor& monitor, BasisResult& result)
{
  const int components = problem.Operators.Components.Count;
  if (components <= 1)
  {
    return;
  }
  const std::string count = std::to_string(components);
  const std::string kind = problem.Prepared.Mesh.Vertices.rows() == 0
    ? "point cloud"
    : (problem.Dimension == 3 ? "volume" : "surface");
  Report({ "The " + kind + " has " + count + " connected components: the first " + count +
           " eigenvalues are zero, one for each. If they are pieces of one " + kind +
           " whose seams are not welded, weld them: WeldSeams on, with a SeamTolerance above "
           "the gap between the copies of a seam point (or Clean, Clean to Grid in ParaView, "
           "vtkCleanPolyData, with a tolerance); leave out small debris with "
           "MinimumComponentSize." },
    monitor,
    result);
  if (m <= components)
  {
    Report({ NoMoreHarmonicsThanComponents(m, components) }, monitor, result);
  }
}

//------------------------------------------------------------------------------
// A point cloud: the operators of PointCloudLaplacian, in the same units as a mesh's.
void CloudProblem(const TriangleMesh& mesh,
  const BasisOptions& options,
  const Monitor& monitor,
  BasisResult& result,
  Problem& problem)
{
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
  problem.Scale = UnitScale(BoundingBoxDiagonal(mesh.Vertices));
  PointCloudOptions cloudOptions;
  cloudOptions.NumberOfNeighbors = options.NumberOfNeighbors;
  cloudOptions.Mass = options.Operators.Mass;
  problem.Operators = PointCloudLaplacian(
    Points(mesh.Vertices / problem.Scale), cloudOptions, monitor.Scaled(0.0, 0.1));
  Report(problem.Operators.Warnings, monitor, result);
  const Eigen::Index used = problem.Operators.Stiffness.rows();
  if (!problem.Window)
  {
    problem.Harmonics =
      Clamped(options.NumberOfHarmonics, used, "the point cloud triangulates", monitor, result);
    if (options.CheckMemory)
    {
      problem.BandSize = CheckMemory(mesh, used, problem.Harmonics, options, monitor, result);
    }
  }
}

//------------------------------------------------------------------------------
// A surface or a volume: its usable cells, then its operators in units of its size (lambda
// scales as 1 / s^2, the mass, an area or a volume, as s^d, the M-normalized harmonics as
// s^(-d/2)).
void MeshProblem(const TriangleMesh& mesh,
  const BasisOptions& options,
  const Monitor& monitor,
  BasisResult& result,
  Problem& problem)
{
  problem.Prepared = LeaveOutSmallComponents(PrepareMesh(mesh), options.MinimumComponentSize);
  PreparedMesh& prepared = problem.Prepared;
  Report(PreparationWarnings(prepared), monitor, result);
  const Eigen::Index used = prepared.Mesh.Vertices.rows();
  if (used == 0)
  {
    throw InvalidInput(prepared.SmallComponents > 0
        ? "every connected component is smaller than MinimumComponentSize"
        : prepared.Volume ? "every tetrahedron of the input is degenerate (zero volume)"
                          : "every triangle of the input is degenerate (zero area)");
  }
  problem.Dimension = prepared.Volume ? 3 : 2;
  if (!problem.Window)
  {
    problem.Harmonics = Clamped(options.NumberOfHarmonics,
      used,
      prepared.Volume ? "tetrahedra use" : "triangles use",
      monitor,
      result);
    if (options.CheckMemory)
    {
      problem.BandSize = CheckMemory(mesh, used, problem.Harmonics, options, monitor, result);
    }
  }
  problem.Scale = UnitScale(BoundingBoxDiagonal(prepared.Mesh.Vertices));
  prepared.Mesh.Vertices /= problem.Scale;
  problem.Operators = AssembleLaplacian(prepared, options.Operators, monitor);
  Report(problem.Operators.Warnings, monitor, result);
}

} // anonymous namespace

//------------------------------------------------------------------------------
std::pair<double, double> WindowEigenvalues(double lower, double upper, double scale)
{
  const double low = lower * scale;
  const double high = upper * scale;
  if (!(lower >= 0.0) || !(high > low) || !std::isfinite(high))
  {
    throw InvalidInput("the frequency window [" + detail::Str(lower) + ", " +
      detail::Str(upper) + ") must have 0 <= lower < upper < infinity");
  }
  return { low * low, high * high };
}

//------------------------------------------------------------------------------
std::string EmptyWindow(double lower, double upper, int below)
{
  return "no eigenvalue lies in the frequency window [" + detail::Str(lower) + ", " +
    detail::Str(upper) + "): " + std::to_string(below) + " lie below it";
}

//------------------------------------------------------------------------------
void Report(const std::vector<std::string>& warnings, const Monitor& monitor, BasisResult& result)
{
  for (const std::string& text : warnings)
  {
    result.Warnings.push_back(text);
    monitor.Warn(text);
  }
}

//------------------------------------------------------------------------------
int ClampHarmonics(int requested, long long usable, const std::string& what, std::string& warning)
{
  warning.clear();
  if (requested < 1)
  {
    throw InvalidInput(
      "the number of harmonics must be at least 1, not " + std::to_string(requested));
  }
  if (requested <= usable)
  {
    return requested;
  }
  warning = "NumberOfHarmonics " + std::to_string(requested) + " clamped to " +
    std::to_string(usable) + ", the number of points " + what + ".";
  return static_cast<int>(usable);
}

//------------------------------------------------------------------------------
int CheckMemory(const TriangleMesh& mesh,
  Eigen::Index used,
  int m,
  const BasisOptions& options,
  const Monitor& monitor,
  BasisResult& result)
{
  const std::uint64_t n = static_cast<std::uint64_t>(mesh.Vertices.rows());
  const std::uint64_t nUsed = static_cast<std::uint64_t>(used);
  const std::uint64_t available = options.MemoryLimit > 0 ? options.MemoryLimit : AvailableMemory();
  const int bandSize = options.Solver.BandSize;
  const MemoryPlan plan = options.Sink.Harmonics
    ? PlanStreamedMemory(n, nUsed, m, bandSize, mesh.IsVolume(), available)
    : PlanBasisMemory(n,
        nUsed,
        m,
        bandSize,
        options.EigenvaluesOnly ? 0 : options.BytesPerValue,
        !options.EigenvaluesOnly,
        mesh.IsVolume(),
        available);
  if (!plan.Fits)
  {
    throw InsufficientMemory(
      plan.Estimate, available, m, static_cast<bool>(options.Sink.Harmonics));
  }
  if (plan.Shrunk)
  {
    Report({ "Bands of " + std::to_string(plan.BandSize) + " eigenpairs instead of " +
             std::to_string(plan.UnplannedBandSize) + ", so that the solve fits the " +
             ByteCount(available) + " available to it (" +
             (options.MemoryLimit > 0 ? "MemoryLimit" : "reported by the system") + "; about " +
             ByteCount(plan.Estimate.Total()) +
             " needed): more bands take longer. Raise MemoryLimit or free memory for the "
             "automatic bands." },
      monitor,
      result);
  }
  return plan.BandSize;
}

//------------------------------------------------------------------------------
Problem PrepareProblem(const TriangleMesh& mesh,
  const BasisOptions& options,
  const Monitor& monitor,
  BasisResult& result)
{
  Problem problem;
  problem.Window = IsFrequencyWindow(options.LowerFrequency, options.UpperFrequency);
  if (mesh.IsPointCloud())
  {
    CloudProblem(mesh, options, monitor, result, problem);
  }
  else
  {
    MeshProblem(mesh, options, monitor, result, problem);
  }
  const DiscreteLaplacian& ops = problem.Operators;
  result.BoundaryPoints = ops.BoundaryPoints;
  if (!problem.Window && ops.Stiffness.rows() < problem.Harmonics)
  {
    problem.Harmonics =
      Clamped(problem.Harmonics, ops.Stiffness.rows(), "inside the boundary", monitor, result);
  }
  if (problem.Window)
  {
    problem.WindowEigenvalues =
      WindowEigenvalues(options.LowerFrequency, options.UpperFrequency, problem.Scale);
  }
  result.Components = ops.Components.Count;
  result.ConstantHarmonics = ops.ConstantHarmonics;
  if (ops.ConstantHarmonics && !problem.Window)
  {
    ReportComponents(problem, problem.Harmonics, monitor, result);
  }
  return problem;
}

//------------------------------------------------------------------------------
void ReportComponentsOf(const Problem& problem, int m, const Monitor& monitor, BasisResult& result)
{
  if (problem.Operators.ConstantHarmonics)
  {
    ReportComponents(problem, m, monitor, result);
  }
}
} // namespace spectral
