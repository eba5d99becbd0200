// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The core's one entry point (Filters/Spectral/Basis.h): it computes what its parts compute
// when called one by one, maps rows back to input points, clamps, warns, checks memory and
// honours cancellation.
#include "Basis.h"
#include "BasisChecks.h"
#include "Checks.h"
#include "Common/Eigenvalues.h"
#include "Meshes.h"
#include "Solver/Bands.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cstdio>

#include <string>
#include <utility>
#include <vector>

using namespace spectral;
using namespace spectral::testing;

namespace
{
//------------------------------------------------------------------------------
// The largest |a_k - b_k| / max(|b_k|, 1).
double EigenvalueDifference(const Vector& a, const Vector& b)
{
  return ((a - b).array().abs() / b.array().abs().max(1.0)).maxCoeff();
}

//------------------------------------------------------------------------------
// A sphere with what PrepareMesh leaves out: a point no triangle uses (with NaN coordinates,
// which are allowed on unused points) and a zero-area triangle. Point 0 is the unused one.
TriangleMesh SphereWithDefects()
{
  const TriangleMesh sphere = Icosphere(2);
  TriangleMesh mesh;
  const Eigen::Index n = sphere.Vertices.rows();
  mesh.Vertices.resize(n + 1, 3);
  mesh.Vertices.row(0).setConstant(std::nan(""));
  mesh.Vertices.bottomRows(n) = sphere.Vertices;
  mesh.Faces.resize(sphere.Faces.rows() + 1, 3);
  mesh.Faces.topRows(sphere.Faces.rows()) = sphere.Faces.array() + 1;
  mesh.Faces.bottomRows(1) << 1, 1, 2;
  return mesh;
}

//------------------------------------------------------------------------------
void SameAsParts()
{
  // Both Laplacians, both masses: the entry point equals the parts called one by one.
  const TriangleMesh mesh = SphereWithDefects();
  for (int variant = 0; variant < 4; ++variant)
  {
    BasisOptions options;
    options.NumberOfHarmonics = 12;
    options.Operators.Laplacian =
      (variant & 1) ? LaplacianKind::IntrinsicDelaunay : LaplacianKind::Cotangent;
    options.Operators.Mass = (variant & 2) ? MassKind::Consistent : MassKind::Lumped;
    const BasisResult basis = ComputeBasis(mesh, options);

    const PreparedMesh prepared = PrepareMesh(mesh);
    const DiscreteLaplacian ops = AssembleLaplacian(prepared, options.Operators);
    EigenOptions solver = options.Solver;
    solver.NumberOfEigenpairs = 12;
    // One component with natural conditions: its constant harmonic is deflated.
    Check(ops.Components.Count == 1, "the sphere with defects is connected");
    solver.ConstantNullSpace = true;
    const EigenResult direct = SmallestEigenpairs(ops.Stiffness, ops.Mass, solver);
    const std::string name = std::string(variant & 1 ? "intrinsic" : "cotangent") + ", " +
      (variant & 2 ? "consistent" : "lumped") + ": ";
    CheckBelow(EigenvalueDifference(basis.Pairs.Eigenvalues, direct.Eigenvalues),
      1e-12,
      name + "eigenvalues equal the solver's on the assembled operators");
    CheckBelow((basis.Pairs.Eigenvectors - direct.Eigenvectors).cwiseAbs().maxCoeff(),
      1e-9,
      name + "harmonics equal the solver's");
    CheckBelow((basis.LumpedMass - ops.LumpedMass).cwiseAbs().maxCoeff(),
      0.0,
      name + "lumped mass is the operators'");
    Check(basis.InputPointIds == prepared.InputPointIds && basis.InputPointIds.front() == 1,
      name + "rows map to the used input points (point 0 is unused)");
    CheckBelow(
      OrthonormalityError(basis.Pairs.Eigenvectors, ops.Mass), 1e-10, name + "M-orthonormal");
  }
}

//------------------------------------------------------------------------------
void WarningsAndClamping()
{
  // Two spheres apart, a zero-area triangle and an unused point; more harmonics than points.
  TriangleMesh mesh = SphereWithDefects();
  const TriangleMesh second = Translated(Icosphere(0), 5.0);
  mesh = Join(mesh, second);
  const int usable = static_cast<int>(mesh.Vertices.rows()) - 1;
  BasisOptions options;
  options.NumberOfHarmonics = usable + 50;
  std::vector<std::string> seen;
  std::vector<std::string> stages;
  Monitor monitor;
  monitor.Warning = [&seen](const std::string& text) { seen.push_back(text); };
  monitor.Stage = [&stages](const char* stage) { stages.emplace_back(stage); };
  const BasisResult basis = ComputeBasis(mesh, options, monitor);

  Check(basis.Warnings == seen, "the result keeps every warning the monitor received, in order");
  const auto has = [&seen](const std::string& part)
  {
    for (const std::string& text : seen)
    {
      if (text.find(part) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  };
  Check(has("Left out 1 degenerate"), "the zero-area triangle is named");
  Check(has("1 point is used by no triangle"), "the unused point is named");
  Check(has("2 connected components"), "the two components are named");
  Check(has("clamped to " + std::to_string(usable)), "the clamp is named");
  Check(basis.Components == 2, "two components");
  Check(basis.Pairs.Eigenvalues.size() == usable, "m clamped to the usable points");
  Check(basis.Pairs.Eigenvalues[0] == 0.0 && basis.Pairs.Eigenvalues[1] == 0.0,
    "two eigenvalues exactly 0 (zero modes by construction)");
  Check(basis.Pairs.Eigenvalues[2] > 1e-3, "the third is not zero");
  Check(stages == std::vector<std::string>({ "Assemble", "Eigensolve" }), "steps announced");
}

//------------------------------------------------------------------------------
void OneHarmonic()
{
  // A single harmonic is the constant one of eigenvalue 0, normalized in the mass.
  BasisOptions options;
  options.NumberOfHarmonics = 1;
  const BasisResult basis = ComputeBasis(Icosphere(2), options);
  Check(basis.Pairs.Eigenvalues.size() == 1 && basis.Pairs.Eigenvectors.cols() == 1,
    "one pair returned");
  Check(basis.Pairs.Eigenvalues[0] == 0.0, "its eigenvalue is exactly 0");
  const double area = basis.LumpedMass.sum();
  const Vector h = basis.Pairs.Eigenvectors.col(0);
  CheckBelow((h.array() - 1.0 / std::sqrt(area)).abs().maxCoeff(),
    1e-9,
    "its harmonic is the constant 1 / sqrt(area)");
}

//------------------------------------------------------------------------------
void MemoryCheck()
{
  const TriangleMesh mesh = SphereWithDefects();
  BasisOptions options;
  options.NumberOfHarmonics = 20;
  options.BytesPerValue = 4;
  options.MemoryLimit = 1;
  const auto run = [&]() { ComputeBasis(mesh, options); };
  CheckThrows<InsufficientMemory>(run, "a limit of one byte refuses the computation");
  try
  {
    run();
  }
  catch (const InsufficientMemory& e)
  {
    // The automatic band (one of 35 pairs) does not fit: the refusal names the estimate at the
    // smallest band the plan goes down to.
    const MemoryEstimate expected =
      EstimateBasisMemory(static_cast<std::uint64_t>(mesh.Vertices.rows()),
        static_cast<std::uint64_t>(mesh.Vertices.rows() - 1),
        20,
        SmallestPlannedBand,
        4);
    Check(e.Needed.Total() == expected.Total() && e.Available == 1 && e.Harmonics == 20,
      "the refusal carries the estimate of Memory.h for n, the used points and m");
  }
  options.MemoryLimit = 1ull << 40;
  CheckThrows<InvalidInput>(
    [&]()
    {
      options.NumberOfHarmonics = 0;
      ComputeBasis(mesh, options);
    },
    "zero harmonics are refused");
}

//------------------------------------------------------------------------------
void BadInput()
{
  TriangleMesh flat;
  flat.Vertices.resize(3, 3);
  flat.Vertices << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  flat.Faces.resize(1, 3);
  flat.Faces << 0, 1, 2;
  CheckThrows<InvalidInput>([&]() { ComputeBasis(flat, BasisOptions()); },
    "a mesh of degenerate triangles only is invalid input");
  TriangleMesh outOfRange = Icosphere(0);
  outOfRange.Faces(0, 0) = 99;
  CheckThrows<InvalidInput>(
    [&]() { ComputeBasis(outOfRange, BasisOptions()); }, "an index out of range is invalid input");
}

//------------------------------------------------------------------------------
void ProgressAndCancellation()
{
  std::vector<double> fractions;
  Monitor monitor;
  monitor.Progress = [&fractions](double f) { fractions.push_back(f); };
  BasisOptions options;
  options.NumberOfHarmonics = 30;
  options.Solver.DenseThreshold = 0; // the iterative solver, which reports and polls
  ComputeBasis(Icosphere(3), options, monitor);
  bool ascending = true;
  for (std::size_t i = 1; i < fractions.size(); ++i)
  {
    ascending = ascending && fractions[i] >= fractions[i - 1] - 1e-12;
  }
  Check(fractions.size() > 2 && ascending && fractions.front() >= 0.0 &&
      fractions.back() <= 1.0 + 1e-12,
    "progress rises within [0, 1] (" + std::to_string(fractions.size()) + " reports)");
  Check(fractions.back() > 0.99, "progress ends at 1");

  int polls = 0;
  Monitor cancel;
  cancel.Cancelled = [&polls]() { return ++polls > 3; };
  CheckThrows<Cancelled>([&]() { ComputeBasis(Icosphere(3), options, cancel); },
    "a cancel during the solve stops the computation");
}

//------------------------------------------------------------------------------
// A sphere of 642 points and `islands` small components beside it: single triangles (3
// points), octahedra-like icospheres of 12 and 42 points and strips of up to 80 points, each
// translated away from the others and scaled down (debris of a scan).
TriangleMesh SphereWithIslands(int islands)
{
  TriangleMesh mesh = Icosphere(3);
  for (int i = 0; i < islands; ++i)
  {
    TriangleMesh island;
    switch (i % 4)
    {
      case 0:
        island.Vertices.resize(3, 3);
        island.Vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0;
        island.Faces.resize(1, 3);
        island.Faces << 0, 1, 2;
        break;
      case 1:
        island = Icosphere(0);
        break;
      case 2:
        island = Icosphere(1);
        break;
      default:
        island = Rectangle(1.0, 0.5, 1 + i % 19, 3); // 2 (nx + 1) .. 80 points
        break;
    }
    island.Vertices *= 0.01 * (1 + i % 7);
    island.Vertices.rowwise() += Eigen::RowVector3d(3.0 + 0.2 * (i % 20), 0.2 * (i / 20), 0.0);
    mesh = Join(mesh, island);
  }
  return mesh;
}

//------------------------------------------------------------------------------
// The generalized eigenvalues of each component of a mesh, dense, merged ascending.
Vector UnionOfComponentSpectra(const TriangleMesh& mesh)
{
  const PreparedMesh prepared = PrepareMesh(mesh);
  const DiscreteLaplacian ops = AssembleLaplacian(prepared, LaplacianOptions());
  const ComponentLabels& labels = ops.Components;
  std::vector<double> all;
  for (int c = 0; c < labels.Count; ++c)
  {
    std::vector<int> rows;
    for (std::size_t i = 0; i < labels.Label.size(); ++i)
    {
      if (labels.Label[i] == c)
      {
        rows.push_back(static_cast<int>(i));
      }
    }
    const Eigen::Index k = static_cast<Eigen::Index>(rows.size());
    DenseMatrix L = DenseMatrix::Zero(k, k);
    DenseMatrix M = DenseMatrix::Zero(k, k);
    for (Eigen::Index a = 0; a < k; ++a)
    {
      for (Eigen::Index b = 0; b < k; ++b)
      {
        L(a, b) = ops.Stiffness.coeff(rows[a], rows[b]);
        M(a, b) = ops.Mass.coeff(rows[a], rows[b]);
      }
    }
    Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> dense(L, M);
    for (Eigen::Index j = 0; j < k; ++j)
    {
      all.push_back(dense.eigenvalues()[j]);
    }
  }
  std::sort(all.begin(), all.end());
  return Eigen::Map<Vector>(all.data(), static_cast<Eigen::Index>(all.size()));
}

//------------------------------------------------------------------------------
void ComponentsOneByOne()
{
  // 201 components: more zero eigenvalues than one band holds (a band asks for 135 pairs at
  // m = 100); each component gets exactly one.
  const TriangleMesh mesh = SphereWithIslands(200);
  BasisOptions options;
  options.NumberOfHarmonics = 260;
  const BasisResult basis = ComputeBasis(mesh, options);
  const Vector& lambda = basis.Pairs.Eigenvalues;
  Check(basis.Components == 201, "201 components");
  int zeros = 0;
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
  {
    zeros += lambda[k] == 0.0 ? 1 : 0;
  }
  Check(zeros == 201, "one eigenvalue exactly 0 per component: " + std::to_string(zeros));
  const Vector reference = UnionOfComponentSpectra(mesh).head(lambda.size());
  double worst = 0.0;
  for (Eigen::Index k = 201; k < lambda.size(); ++k)
  {
    worst = std::max(worst, std::abs(lambda[k] - reference[k]) / reference[k]);
  }
  CheckBelow(worst, 1e-8, "non-zero eigenvalues equal the union of dense component spectra");
  const DiscreteLaplacian ops = AssembleLaplacian(PrepareMesh(mesh), LaplacianOptions());
  CheckBelow(OrthonormalityError(basis.Pairs.Eigenvectors, ops.Mass), 1e-10, "M-orthonormal");
  const Vector residuals =
    RelativeResiduals(ops.Stiffness, ops.Mass, lambda, basis.Pairs.Eigenvectors);
  CheckBelow(residuals.maxCoeff(), 1e-8, "every pair is an eigenpair of the whole operators");

  // The same mesh without its debris: the islands' points get no rows.
  options.MinimumComponentSize = 100;
  std::vector<std::string> seen;
  Monitor monitor;
  monitor.Warning = [&seen](const std::string& text) { seen.push_back(text); };
  const BasisResult cleaned = ComputeBasis(mesh, options, monitor);
  Check(cleaned.Components == 1 && cleaned.InputPointIds.size() == 642,
    "MinimumComponentSize 100 keeps the sphere only");
  Check(!seen.empty() && seen.front().find("Left out 200 connected components") == 0,
    "the debris left out is named: " + (seen.empty() ? std::string() : seen.front()));
  const BasisResult sphere = ComputeBasis(Icosphere(3), options);
  CheckBelow(EigenvalueDifference(cleaned.Pairs.Eigenvalues, sphere.Pairs.Eigenvalues),
    1e-12,
    "its eigenvalues are the sphere's alone");
}

//------------------------------------------------------------------------------
void FewerHarmonicsThanComponents()
{
  std::vector<std::string> seen;
  Monitor monitor;
  monitor.Warning = [&seen](const std::string& text) { seen.push_back(text); };
  bool warnedBeforeSolve = false;
  bool solving = false;
  monitor.Stage = [&](const char* stage)
  {
    solving = std::string(stage) == "Eigensolve";
    if (solving)
    {
      for (const std::string& text : seen)
      {
        warnedBeforeSolve |=
          text.find("does not exceed the 11 connected components") != std::string::npos;
      }
    }
  };
  BasisOptions options;
  options.NumberOfHarmonics = 10;
  const BasisResult basis = ComputeBasis(SphereWithIslands(10), options, monitor);
  Check(warnedBeforeSolve, "10 harmonics for 11 components: said before the solve");
  Check((basis.Pairs.Eigenvalues.array() == 0.0).all(), "all ten eigenvalues are exactly 0");
  // The smallest component (a single triangle; the last of the smallest size) has no
  // harmonic: its points are left out.
  const TriangleMesh mesh = SphereWithIslands(10);
  const PreparedMesh prepared = PrepareMesh(mesh);
  const ComponentLabels labels = LabelComponents(prepared.Mesh);
  std::vector<int> size(static_cast<std::size_t>(labels.Count), 0);
  for (int label : labels.Label)
  {
    ++size[static_cast<std::size_t>(label)];
  }
  int smallest = 0;
  for (int c = 0; c < labels.Count; ++c)
  {
    smallest =
      size[static_cast<std::size_t>(c)] <= size[static_cast<std::size_t>(smallest)] ? c : smallest;
  }
  std::vector<int> represented;
  for (std::size_t i = 0; i < labels.Label.size(); ++i)
  {
    if (labels.Label[i] != smallest)
    {
      represented.push_back(prepared.InputPointIds[i]);
    }
  }
  Check(basis.InputPointIds == represented,
    "the points of the component without a harmonic have no row (" +
      std::to_string(prepared.InputPointIds.size() - represented.size()) + " points)");
  Check(basis.Pairs.Eigenvectors.rows() == static_cast<Eigen::Index>(represented.size()) &&
      basis.LumpedMass.size() == static_cast<Eigen::Index>(represented.size()),
    "harmonics and mass have their rows only");
  Check(seen.back().find("none of the 10 harmonics represents are left out") != std::string::npos,
    "and a warning says so: " + seen.back());
}

//------------------------------------------------------------------------------
void ScaleInvariance()
{
  // lambda s^2 and the M-normalized harmonics times s do not depend on the unit.
  const TriangleMesh unit = NoisyTorus(40, 16, 0.2);
  BasisOptions options;
  options.NumberOfHarmonics = 30;
  options.Solver.DenseThreshold = 0;
  const BasisResult reference = ComputeBasis(unit, options);
  for (double scale : { 1e-20, 1e-7, 3.7e-3, 5e5, 8e6, 1e9, 1e20 })
  {
    TriangleMesh mesh = unit;
    mesh.Vertices *= scale;
    const BasisResult basis = ComputeBasis(mesh, options);
    const Vector lambda = basis.Pairs.Eigenvalues * (scale * scale);
    const double top = reference.Pairs.Eigenvalues.maxCoeff();
    char name[64];
    std::snprintf(name, sizeof(name), "scale %g: ", scale);
    CheckBelow((lambda - reference.Pairs.Eigenvalues).cwiseAbs().maxCoeff() / top,
      1e-12,
      std::string(name) + "lambda s^2 equal");
    CheckBelow(
      (basis.Pairs.Eigenvectors * scale - reference.Pairs.Eigenvectors).cwiseAbs().maxCoeff() /
        reference.Pairs.Eigenvectors.cwiseAbs().maxCoeff(),
      1e-9,
      std::string(name) + "harmonics times s equal");
    CheckBelow(std::abs(basis.LumpedMass.sum() / (scale * scale) - reference.LumpedMass.sum()) /
        reference.LumpedMass.sum(),
      1e-13,
      std::string(name) + "mass / s^2 equal");
  }
}

//------------------------------------------------------------------------------
void DuplicateTriangles()
{
  // Every fifth triangle repeated, alternately in the other orientation: left out, counted.
  const TriangleMesh sphere = Icosphere(2);
  TriangleMesh doubled = sphere;
  const Eigen::Index f = sphere.Faces.rows();
  doubled.Faces.conservativeResize(f + f / 5, 3);
  for (Eigen::Index t = 0; t < f / 5; ++t)
  {
    const Eigen::Index src = 5 * t;
    doubled.Faces.row(f + t) = (t % 2)
      ? sphere.Faces.row(src)
      : Eigen::RowVector3i(sphere.Faces(src, 0), sphere.Faces(src, 2), sphere.Faces(src, 1));
  }
  std::vector<std::string> seen;
  Monitor monitor;
  monitor.Warning = [&seen](const std::string& text) { seen.push_back(text); };
  BasisOptions options;
  options.NumberOfHarmonics = 20;
  const BasisResult basis = ComputeBasis(doubled, options, monitor);
  const BasisResult clean = ComputeBasis(sphere, options);
  Check(!seen.empty() &&
      seen.front() ==
        "Left out " + std::to_string(f / 5) +
          " duplicated triangles (the same three points as another triangle, in either "
          "orientation).",
    "the duplicates are counted: " + (seen.empty() ? std::string() : seen.front()));
  CheckBelow(EigenvalueDifference(basis.Pairs.Eigenvalues, clean.Pairs.Eigenvalues),
    1e-13,
    "the spectrum is the sphere's");
  CheckBelow(
    (basis.LumpedMass - clean.LumpedMass).cwiseAbs().maxCoeff(), 1e-15, "the mass is the sphere's");
}

//------------------------------------------------------------------------------
// A noisy torus of 20,000 points with what real range scans carry: near-coincident points
// (edges of 1e-4 to 1e-8 of their triangle's), needles (cotangents of about 1e4), zero-area
// triangles and 200 islands of 3 to 80 points.
void ScanDefectsGiveABasis()
{
  ScanDefects defects;
  defects.NearCoincident = 40;
  defects.Needles = 40;
  defects.ZeroArea = 30;
  defects.Islands = 200;
  const TriangleMesh torus = NoisyTorusOfSize(20000, 0.02);
  const TriangleMesh mesh = WithScanDefects(torus, defects);
  for (const LaplacianKind laplacian :
    { LaplacianKind::Cotangent, LaplacianKind::IntrinsicDelaunay })
  {
    const std::string name =
      laplacian == LaplacianKind::Cotangent ? "scan [cotan]: " : "scan [intrinsic]: ";
    BasisOptions options;
    options.NumberOfHarmonics = 260;
    options.Operators.Laplacian = laplacian;
    std::vector<std::string> seen;
    Monitor monitor;
    monitor.Warning = [&seen](const std::string& text) { seen.push_back(text); };
    BasisResult basis;
    try
    {
      basis = ComputeBasis(mesh, options, monitor);
    }
    catch (const std::exception& e)
    {
      Check(false, name + "no basis: " + e.what());
      continue;
    }
    for (const std::string& text : seen)
    {
      std::printf("    warning: %s\n", text.c_str());
    }
    const Vector& lambda = basis.Pairs.Eigenvalues;
    CheckZeroModes(basis, 201, name);
    const DiscreteLaplacian ops = AssembleLaplacian(PrepareMesh(mesh), options.Operators);
    CheckBelow(
      OrthonormalityError(basis.Pairs.Eigenvectors, ops.Mass), 1e-10, name + "M-orthonormal");
    CheckBelow(basis.Pairs.MaxBackwardError,
      options.Solver.BackwardErrorTolerance,
      name + "componentwise backward error");
    if (laplacian == LaplacianKind::Cotangent)
    {
      // The defects cost the iteration no extra restarts: the residual estimate of a band, in
      // the D^-1 norm, never passes on the rows of tiny mass, and a band whose pairs had settled
      // waited for a second restart before the check that accepts them by their backward errors
      // (23% to 38% more operator applications than without the defects, over 1 to 8 threads
      // and perturbation seeds 1 to 3; 0% to 7% since).
      const BasisResult clean = ComputeBasis(torus, options);
      CheckBelow(static_cast<double>(basis.Pairs.OperatorApplications) /
          static_cast<double>(clean.Pairs.OperatorApplications),
        1.2,
        name + "operator applications against the same torus without defects (ratio)");
    }
    // An independent solve: CHOLMOD's simplicial factorization and Spectra's Lanczos.
    BasisOptions reference = options;
    reference.Solver.Factorization = FactorizationMethod::Simplicial;
    reference.Solver.Method = LanczosMethod::Spectra;
    const BasisResult other = ComputeBasis(mesh, reference);
    // To 1e-8 where the backward errors allow: a pair exact for a pencil within omega of
    // (L, M) entry by entry has its eigenvalue within omega kappa, kappa = (|h|^T |L| |h| +
    // lambda |h|^T |M| |h|) / lambda (first order, h^T M h = 1).
    const Vector omega = BackwardErrors(ops.Stiffness, ops.Mass, lambda, basis.Pairs.Eigenvectors);
    const Vector omegaOther =
      BackwardErrors(ops.Stiffness, ops.Mass, other.Pairs.Eigenvalues, other.Pairs.Eigenvectors);
    const SparseMatrix absL = ops.Stiffness.cwiseAbs();
    const SparseMatrix absM = ops.Mass.cwiseAbs();
    double worst = 0.0;
    for (Eigen::Index k = 201; k < lambda.size(); ++k)
    {
      const Vector h = basis.Pairs.Eigenvectors.col(k).cwiseAbs();
      const double kappa = (h.dot(absL * h) + lambda[k] * h.dot(absM * h)) / lambda[k];
      const double allowed = std::max(1e-8, 2.0 * (omega[k] + omegaOther[k]) * kappa);
      worst =
        std::max(worst, std::abs(lambda[k] - other.Pairs.Eigenvalues[k]) / lambda[k] / allowed);
    }
    CheckBelow(worst,
      1.0,
      name +
        "non-zero eigenvalues equal an independent solve's, to max(1e-8, the backward "
        "errors' bound) (ratio)");
  }
}

//------------------------------------------------------------------------------
void HeapLayoutDoesNotRound()
{
  // The same solve with the heap laid out differently (a block of another size held during it
  // moves later allocations by 0, 16, 32 or 48 bytes modulo 64): the same bits. A sum or product
  // whose vector instructions start at the first 64-byte boundary of a buffer placed by `new`
  // rounds differently when the buffer moves (SumOfEntries, AlignedBuffer in Common/Mesh.h).
  BasisOptions options;
  options.NumberOfHarmonics = 60;
  options.Solver.BandSize = 25;
  const TriangleMesh mesh = NoisyTorusOfSize(3000, 0.02);
  const BasisResult first = ComputeBasis(mesh, options);
  bool same = true;
  for (std::size_t bytes : { 8, 40, 48, 72, 100, 1000 })
  {
    std::vector<char> held(bytes);
    const BasisResult again = ComputeBasis(mesh, options);
    same = same && again.Pairs.Eigenvalues == first.Pairs.Eigenvalues &&
      again.Pairs.Eigenvectors == first.Pairs.Eigenvectors && again.LumpedMass == first.LumpedMass;
    held[0] = 1;
  }
  Check(same, "eigenvalues, harmonics and mass are bitwise the same whatever the heap's layout");
}

void ThreadsMatchOneThread()
{
  // Several bands on a 20,000-point torus: the factorizations, solves and block products of
  // every band on 1, 2, 4 and 8 threads (oversubscribed on a small machine) give the basis of
  // one thread.
  BasisOptions options;
  options.NumberOfHarmonics = 150;
  options.Solver.BandSize = 60;
  options.Solver.Threads = 1;
  const TriangleMesh mesh = NoisyTorusOfSize(20000, 0.02);
  const BasisResult one = ComputeBasis(mesh, options);
  for (int threads : { 2, 4, 8 })
  {
    options.Solver.Threads = threads;
    const BasisResult many = ComputeBasis(mesh, options);
    const std::string name = std::to_string(threads) + " threads: ";
    CheckBelow(EigenvalueDifference(many.Pairs.Eigenvalues, one.Pairs.Eigenvalues),
      1e-12,
      name + "eigenvalues of one thread");
    // Compare spans, not vectors: a multiple eigenvalue's basis may rotate with round-off.
    const DiscreteLaplacian ops = AssembleLaplacian(PrepareMesh(mesh), options.Operators);
    const DenseMatrix overlap =
      one.Pairs.Eigenvectors.transpose() * (ops.Mass * many.Pairs.Eigenvectors);
    const Eigen::JacobiSVD<DenseMatrix> svd(overlap);
    CheckBelow(1.0 - svd.singularValues().minCoeff(),
      1e-9,
      name + "the harmonics span the same space (smallest principal cosine)");
    Check(
      many.Pairs.Bands == one.Pairs.Bands && many.Pairs.Factorizations == one.Pairs.Factorizations,
      name + "the same bands and factorizations (" + std::to_string(many.Pairs.Bands) + ", " +
        std::to_string(many.Pairs.Factorizations) + ")");
  }
}

//------------------------------------------------------------------------------
void FrequencyWindow()
{
  // The unit sphere: lambda = l (l + 1) with multiplicity 2 l + 1, omega = sqrt(l (l + 1)):
  // 0, 1.41, 2.45, 3.46, ... The window [2, 3.2) holds l = 2 only: 5 harmonics, after 4.
  const TriangleMesh sphere = Icosphere(4);
  BasisOptions options;
  options.LowerFrequency = 2.0;
  options.UpperFrequency = 3.2;
  const BasisResult window = ComputeBasis(sphere, options);
  Check(window.FirstIndex == 4 && window.Pairs.Eigenvalues.size() == 5,
    "window [2, 3.2) on the unit sphere: the 5 harmonics of l = 2, after 4 (" +
      std::to_string(window.FirstIndex) + ", " + std::to_string(window.Pairs.Eigenvalues.size()) +
      ")");
  BasisOptions all;
  all.NumberOfHarmonics = 9;
  const BasisResult smallest = ComputeBasis(sphere, all);
  CheckBelow(EigenvalueDifference(window.Pairs.Eigenvalues, smallest.Pairs.Eigenvalues.tail(5)),
    1e-12,
    "the window's eigenvalues are pairs 4 to 8 of the smallest");
  CheckBelow((window.Pairs.Eigenvalues.array() - 6.0).abs().maxCoeff() / 6.0,
    1e-2,
    "they are l (l + 1) = 6 within the discretization error");
  const DiscreteLaplacian ops = AssembleLaplacian(PrepareMesh(sphere), options.Operators);
  CheckBelow(OrthonormalityError(window.Pairs.Eigenvectors, ops.Mass), 1e-10, "M-orthonormal");

  // Scaled by 10, the same window in the new units (frequencies / 10) gives the same pairs.
  TriangleMesh large = sphere;
  large.Vertices *= 10.0;
  options.LowerFrequency = 0.2;
  options.UpperFrequency = 0.32;
  const BasisResult scaled = ComputeBasis(large, options);
  Check(scaled.FirstIndex == 4 && scaled.Pairs.Eigenvalues.size() == 5,
    "the window is in the units of the mesh");

  // Two spheres, of radius 1 and 2: the window [2, 3) holds l = 2 of the first (omega 2.45)
  // and l = 4, 5 of the second (omega sqrt(l (l + 1)) / 2: 2.24, 2.74), 5 + 9 + 11 = 25
  // harmonics, after the 4 + 16 below omega = 2. Each component starts its bands at the window.
  TriangleMesh big = Icosphere(4);
  big.Vertices *= 2.0;
  const TriangleMesh two = Join(sphere, Translated(big, 5.0));
  options.LowerFrequency = 2.0;
  options.UpperFrequency = 3.0;
  const BasisResult both = ComputeBasis(two, options);
  Check(both.FirstIndex == 20 && both.Pairs.Eigenvalues.size() == 25,
    "two spheres, window [2, 3): 25 harmonics after 20 (" + std::to_string(both.FirstIndex) + ", " +
      std::to_string(both.Pairs.Eigenvalues.size()) + ")");
  all.NumberOfHarmonics = 45;
  const BasisResult bottom = ComputeBasis(two, all);
  CheckBelow(EigenvalueDifference(both.Pairs.Eigenvalues, bottom.Pairs.Eigenvalues.tail(25)),
    1e-9,
    "two spheres: the window's eigenvalues are pairs 20 to 44 of the smallest");
  const DiscreteLaplacian twoOps = AssembleLaplacian(PrepareMesh(two), options.Operators);
  CheckBelow(
    OrthonormalityError(both.Pairs.Eigenvectors, twoOps.Mass), 1e-10, "two spheres: M-orthonormal");

  options.LowerFrequency = 2.5;
  options.UpperFrequency = 2.6;
  CheckThrows<InvalidInput>(
    [&]() { ComputeBasis(sphere, options); }, "a window without an eigenvalue is refused");
  options.LowerFrequency = 3.0;
  options.UpperFrequency = 2.0;
  CheckThrows<InvalidInput>([&]() { ComputeBasis(sphere, options); }, "an empty window is refused");
  // Only [0, 0) is off: an upper end at or below 0, or NaN, is an error, not the m smallest (they
  // were computed as if there were no window).
  for (const std::pair<double, double>& window : std::vector<std::pair<double, double>>{
         { 5.0, 0.0 }, { 5.0, -1.0 }, { 2.0, std::nan("") }, { 0.0, -3.0 } })
  {
    options.LowerFrequency = window.first;
    options.UpperFrequency = window.second;
    CheckThrows<InvalidInput>([&]() { ComputeBasis(sphere, options); },
      "the window [" + std::to_string(window.first) + ", " + std::to_string(window.second) +
        ") is refused");
  }

  // A mesh in micrometres (a sphere of radius 1e6): the message gives the window as asked, not
  // rounded to six decimals (it said [0.000003, 0.000003)).
  TriangleMesh micro = sphere;
  micro.Vertices *= 1e6;
  options.LowerFrequency = 2.5e-6;
  options.UpperFrequency = 2.6e-6;
  std::string message;
  try
  {
    ComputeBasis(micro, options);
  }
  catch (const InvalidInput& error)
  {
    message = error.what();
  }
  Check(message.find("[2.5e-06, 2.6e-06)") != std::string::npos,
    "the error gives the window's frequencies as asked: " + message);
}

//------------------------------------------------------------------------------
void EigenvaluesOnly()
{
  BasisOptions options;
  options.NumberOfHarmonics = 20;
  const BasisResult full = ComputeBasis(Icosphere(3), options);
  options.EigenvaluesOnly = true;
  const BasisResult spectrum = ComputeBasis(Icosphere(3), options);
  Check(spectrum.Pairs.Eigenvectors.size() == 0, "no harmonics returned");
  CheckBelow(EigenvalueDifference(spectrum.Pairs.Eigenvalues, full.Pairs.Eigenvalues),
    0.0,
    "the same verified eigenvalues");
  CheckBelow((spectrum.LumpedMass - full.LumpedMass).cwiseAbs().maxCoeff(), 0.0, "the same mass");
  // Without the output basis in the estimate, a limit between the two estimates passes (a band
  // size set by hand, which the memory plan keeps: smaller bands would fit the basis too).
  const int band = EffectiveBandSize(20, 0);
  options.Solver.BandSize = band;
  const MemoryEstimate with = EstimateBasisMemory(642, 642, 20, band, 8);
  const MemoryEstimate without = EstimateBasisMemory(642, 642, 20, band, 0);
  options.MemoryLimit = (with.Total() + without.Total()) / 2;
  ComputeBasis(Icosphere(3), options);
  Check(true, "fits without the basis");
  options.EigenvaluesOnly = false;
  CheckThrows<InsufficientMemory>(
    [&]() { ComputeBasis(Icosphere(3), options); }, "the same limit refuses the basis");
}

//------------------------------------------------------------------------------
void SpectrumAloneInBands()
{
  // A solve in many bands (10,242 points, 400 pairs): without harmonics the solver keeps only
  // the vectors its seams need, and gives the same verified eigenvalues.
  BasisOptions bands;
  bands.NumberOfHarmonics = 400;
  const TriangleMesh fine = Icosphere(5);
  const BasisResult kept = ComputeBasis(fine, bands);
  bands.EigenvaluesOnly = true;
  const BasisResult alone = ComputeBasis(fine, bands);
  Check(alone.Pairs.Eigenvectors.size() == 0 && alone.Pairs.Bands > 2,
    "400 eigenvalues alone, in " + std::to_string(alone.Pairs.Bands) + " bands");
  CheckBelow(EigenvalueDifference(alone.Pairs.Eigenvalues, kept.Pairs.Eigenvalues),
    1e-12,
    "the same eigenvalues as with the harmonics");
  std::printf("    worst relative residual %.3e, backward error %.3e (with harmonics %.3e, %.3e)\n",
    alone.Pairs.MaxResidual,
    alone.Pairs.MaxBackwardError,
    kept.Pairs.MaxResidual,
    kept.Pairs.MaxBackwardError);
  Check(alone.Pairs.MaxBackwardError > 0.0 &&
      std::abs(alone.Pairs.MaxBackwardError - kept.Pairs.MaxBackwardError) <=
        1e-3 * kept.Pairs.MaxBackwardError &&
      std::abs(alone.Pairs.MaxResidual - kept.Pairs.MaxResidual) <= 1e-3 * kept.Pairs.MaxResidual,
    "verified as the harmonics are (the same worst figures)");
  // The memory estimate of a solve that lets its vectors go counts three bands of them.
  const int threeBands = 3 * detail::PairsPerBand(400, 0, 10242);
  Check(alone.Pairs.MostKeptVectors > 0 && alone.Pairs.MostKeptVectors <= threeBands,
    "the solve held at most three bands of vectors (" +
      std::to_string(alone.Pairs.MostKeptVectors) + " columns, three bands " +
      std::to_string(threeBands) + ")");
  const MemoryEstimate spectrumOnly = EstimateBasisMemory(10242, 10242, 400, 0, 0, false);
  const MemoryEstimate withVectors = EstimateBasisMemory(10242, 10242, 400, 0, 0, true);
  Check(spectrumOnly.Eigenvectors < withVectors.Eigenvectors,
    "the estimate of a spectrum alone leaves out most of the solver's eigenvectors");
}

const Case Cases[] = {
  { "SameAsParts", SameAsParts },
  { "WarningsAndClamping", WarningsAndClamping },
  { "OneHarmonic", OneHarmonic },
  { "MemoryCheck", MemoryCheck },
  { "BadInput", BadInput },
  { "ProgressAndCancellation", ProgressAndCancellation },
  { "ComponentsOneByOne", ComponentsOneByOne },
  { "FewerHarmonicsThanComponents", FewerHarmonicsThanComponents },
  { "ScaleInvariance", ScaleInvariance },
  { "DuplicateTriangles", DuplicateTriangles },
  { "ScanDefectsGiveABasis", ScanDefectsGiveABasis },
  { "ThreadsMatchOneThread", ThreadsMatchOneThread },
  { "HeapLayoutDoesNotRound", HeapLayoutDoesNotRound },
  { "FrequencyWindow", FrequencyWindow },
  { "EigenvaluesOnly", EigenvaluesOnly },
  { "SpectrumAloneInBands", SpectrumAloneInBands },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
