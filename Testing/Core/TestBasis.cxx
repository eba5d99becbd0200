// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The core's one entry point (Filters/Spectral/Basis.h): it computes what its parts compute
// when called one by one, maps rows back to input points, clamps, warns, checks memory and
// honours cancellation.
#include "Basis.h"
#include "Checks.h"
#include "Meshes.h"

#include <string>
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
  CheckBelow(std::abs(basis.Pairs.Eigenvalues[1]), 1e-9, "two zero eigenvalues");
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
  CheckBelow(std::abs(basis.Pairs.Eigenvalues[0]), 1e-10, "its eigenvalue is zero");
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
    const MemoryEstimate expected =
      EstimateBasisMemory(static_cast<std::uint64_t>(mesh.Vertices.rows()),
        static_cast<std::uint64_t>(mesh.Vertices.rows() - 1),
        20,
        0,
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

const Case Cases[] = {
  { "SameAsParts", SameAsParts },
  { "WarningsAndClamping", WarningsAndClamping },
  { "OneHarmonic", OneHarmonic },
  { "MemoryCheck", MemoryCheck },
  { "BadInput", BadInput },
  { "ProgressAndCancellation", ProgressAndCancellation },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
