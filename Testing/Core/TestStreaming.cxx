// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// A streamed basis (Filters/Spectral/Basis.h, BasisSink): each harmonic delivered once, with
// its index in the basis, equal to the in-memory basis of the same options (its eigenvalues,
// its columns, and its eigenspaces where eigenvalues cluster); the rows, the mass and the
// spectrum given before any harmonic; memory independent of m; cancellation mid-stream.
#include "Basis.h"
#include "Checks.h"
#include "Meshes.h"
#include "Streaming.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace spectral;
using namespace spectral::testing;

namespace
{
/// What a sink received.
struct Received
{
  BasisResult Begun;
  int BeginCalls = 0;
  bool HarmonicBeforeBegin = false;
  DenseMatrix Harmonics;
  Vector Values;
  std::vector<int> Times;
  int Blocks = 0;
};

/// A sink that assembles what it receives into an n by m matrix.
BasisSink Collecting(Received& received, int m)
{
  received.Values = Vector::Zero(m);
  received.Times.assign(static_cast<std::size_t>(m), 0);
  BasisSink sink;
  sink.Begin = [&received](const BasisResult& basis)
  {
    received.Begun = basis;
    ++received.BeginCalls;
    received.Harmonics = DenseMatrix::Zero(static_cast<Eigen::Index>(basis.InputPointIds.size()),
      static_cast<Eigen::Index>(received.Values.size()));
  };
  sink.Harmonics = [&received](int first, const Vector& values, const DenseMatrix& harmonics)
  {
    received.HarmonicBeforeBegin = received.HarmonicBeforeBegin || received.BeginCalls == 0;
    ++received.Blocks;
    for (Eigen::Index j = 0; j < values.size(); ++j)
    {
      const Eigen::Index k = first + j;
      if (k < 0 || k >= received.Values.size() || harmonics.rows() != received.Harmonics.rows())
      {
        received.HarmonicBeforeBegin = true; // recorded as a failure below
        continue;
      }
      ++received.Times[static_cast<std::size_t>(k)];
      received.Values[k] = values[j];
      received.Harmonics.col(k) = harmonics.col(j);
    }
  };
  return sink;
}

/// The end of the group of eigenvalues from k on: those closer than 1e-6 relative in a chain.
Eigen::Index GroupEnd(const Vector& lambda, Eigen::Index k)
{
  Eigen::Index end = k + 1;
  while (end < lambda.size() &&
    lambda[end] - lambda[end - 1] <= 1e-6 * std::max(std::abs(lambda[end]), 1e-300))
  {
    ++end;
  }
  return end;
}

/**
 * The largest distance between the streamed and the in-memory harmonics, by groups of
 * eigenvalues closer than 1e-6 relative (a cluster's eigenspace is compared, not its vectors):
 * a single harmonic by its D-norm difference, a group by the sine of the largest principal
 * angle between the two spans: the largest D-norm of a column of B - A (A^T D B), B's part
 * outside A's span (computed so, it resolves angles down to round-off, where the singular
 * values of A^T D B would only resolve their square, 1e-8).
 */
double HarmonicsDifference(const DenseMatrix& A,
  const DenseMatrix& B,
  const Vector& lambda,
  const Vector& mass)
{
  double worst = 0.0;
  const Eigen::Index m = lambda.size();
  for (Eigen::Index k = 0; k < m;)
  {
    const Eigen::Index end = GroupEnd(lambda, k);
    const Eigen::Index size = end - k;
    if (size == 1)
    {
      const Vector d = A.col(k) - B.col(k);
      worst = std::max(worst, std::sqrt(d.cwiseProduct(mass).dot(d)));
    }
    else
    {
      const auto a = A.middleCols(k, size);
      const auto b = B.middleCols(k, size);
      const DenseMatrix outside = b - a * (a.transpose() * mass.asDiagonal() * b);
      for (Eigen::Index j = 0; j < size; ++j)
      {
        const Vector d = outside.col(j);
        worst = std::max(worst, std::sqrt(d.cwiseProduct(mass).dot(d)));
      }
    }
    k = end;
  }
  return worst;
}

/// The largest |a_k - b_k| / max(|b_k|, b_max * 1e-300).
double EigenvalueDifference(const Vector& a, const Vector& b)
{
  double worst = 0.0;
  for (Eigen::Index k = 0; k < b.size(); ++k)
  {
    const double scale = std::max(std::abs(b[k]), 1e-300);
    worst = std::max(worst, a[k] == b[k] ? 0.0 : std::abs(a[k] - b[k]) / scale);
  }
  return worst;
}

/**
 * Streams `mesh` with `options` and compares with the in-memory basis: every index once, Begin
 * first with the rows and the mass, the same eigenvalues, harmonics within `tolerance`.
 */
void SameAsInMemory(const TriangleMesh& mesh,
  BasisOptions options,
  const std::string& name,
  double tolerance,
  double valueTolerance = 1e-24)
{
  const BasisResult memory = ComputeBasis(mesh, options);
  const int m = static_cast<int>(memory.Pairs.Eigenvalues.size());
  Received received;
  options.Sink = Collecting(received, m);
  const BasisResult streamed = ComputeBasis(mesh, options);
  Check(received.BeginCalls == 1 && !received.HarmonicBeforeBegin,
    name + "Begin once, before every harmonic");
  Check(std::all_of(received.Times.begin(), received.Times.end(), [](int t) { return t == 1; }),
    name + "each of the " + std::to_string(m) + " indices delivered exactly once, in " +
      std::to_string(received.Blocks) + " blocks");
  Check(streamed.Pairs.Eigenvectors.size() == 0, name + "no harmonics returned");
  Check(received.Begun.InputPointIds == memory.InputPointIds &&
      streamed.InputPointIds == memory.InputPointIds,
    name + "the same rows (InputPointIds), given to Begin");
  CheckBelow((received.Begun.LumpedMass - memory.LumpedMass).cwiseAbs().maxCoeff(),
    0.0,
    name + "the same mass, given to Begin");
  const double values = EigenvalueDifference(received.Values, memory.Pairs.Eigenvalues);
  std::printf("    %seigenvalues: largest relative difference %.3e\n", name.c_str(), values);
  CheckBelow(values, valueTolerance, name + "the same eigenvalues (relative)");
  CheckBelow((streamed.Pairs.Eigenvalues - received.Values).cwiseAbs().maxCoeff(),
    0.0,
    name + "the result's eigenvalues are the delivered ones");
  if (received.Begun.Pairs.Eigenvalues.size() > 0)
  {
    CheckBelow(EigenvalueDifference(received.Begun.Pairs.Eigenvalues, received.Values),
      valueTolerance,
      name + "the spectrum given first is the delivered one");
  }
  const double harmonics = HarmonicsDifference(
    received.Harmonics, memory.Pairs.Eigenvectors, memory.Pairs.Eigenvalues, memory.LumpedMass);
  std::printf("    %sharmonics: largest difference %.3e (D-norm, or sine of the angle between "
              "eigenspaces)\n",
    name.c_str(),
    harmonics);
  CheckBelow(harmonics, tolerance, name + "the same harmonics (eigenspaces in clusters)");
  std::printf("    %slargest entry difference of the columns: %.3e\n",
    name.c_str(),
    (received.Harmonics - memory.Pairs.Eigenvectors).cwiseAbs().maxCoeff());
}

//------------------------------------------------------------------------------
void OneComponent()
{
  // 4,000 points, 300 harmonics: three bands of 100 pairs, so that the solver lets pairs go
  // (retires them) before the end.
  BasisOptions options;
  options.NumberOfHarmonics = 300;
  SameAsInMemory(NoisyTorusOfSize(4000, 0.1), options, "torus: ", 1e-12);
  options.Sink.SpectrumFirst = true;
  SameAsInMemory(NoisyTorusOfSize(4000, 0.1), options, "torus, spectrum first: ", 1e-12);
}

//------------------------------------------------------------------------------
void SeveralComponents()
{
  // A sphere, a torus and tiny islands (12 and 42 points): their pairs interleave in the basis.
  TriangleMesh mesh = Join(Icosphere(4), Translated(NoisyTorusOfSize(2500, 0.1), 3.0));
  for (int island = 0; island < 4; ++island)
  {
    TriangleMesh small = Icosphere(island % 2);
    small.Vertices *= 0.05 * (island + 1);
    mesh = Join(mesh, Translated(small, -2.0 - island));
  }
  BasisOptions options;
  options.NumberOfHarmonics = 260;
  SameAsInMemory(mesh, options, "sphere, torus and islands: ", 1e-12);
  // Fewer harmonics than components: the components none represents are left out.
  options.NumberOfHarmonics = 4;
  SameAsInMemory(mesh, options, "4 harmonics of 6 components: ", 1e-12);
}

//------------------------------------------------------------------------------
void ScanDefects()
{
  // A scan's defects (near-coincident points, needles, 12 islands of 3 to 80 points): pairs
  // verified to the residual tolerance 1e-8 on operators whose rounding is amplified by 1e8
  // cotangents. Here the two paths differ: in memory a later band merges again (Rayleigh-Ritz
  // on the joint span, Bands.h) pairs that the streamed solve has already verified and let go,
  // and on these operators that moves them within their verification accuracy (measured: the
  // eigenvalues by 1.9e-9 relative, the harmonics by 1.9e-7). Both are verified pairs; the
  // streamed basis is held to that accuracy: eigenvalues to the residual tolerance, harmonics
  // to it over the relative gaps of the spectrum (1e-6).
  spectral::testing::ScanDefects defects;
  defects.Islands = 12;
  defects.NearCoincident = 20;
  defects.Needles = 10;
  const TriangleMesh mesh =
    WithScanDefects(Join(Icosphere(4), Translated(NoisyTorusOfSize(2500, 0.1), 3.0)), defects);
  BasisOptions options;
  options.NumberOfHarmonics = 260;
  SameAsInMemory(mesh, options, "scan: ", 1e-6, 1e-8);
}

//------------------------------------------------------------------------------
void Volume()
{
  BasisOptions options;
  options.NumberOfHarmonics = 40;
  SameAsInMemory(TetrahedralBall(8), options, "ball: ", 1e-12);
}

//------------------------------------------------------------------------------
void CancelledMidStream()
{
  // Bands of 20 pairs: the first block is let go after a few bands (cheap under the sanitizers).
  BasisOptions options;
  options.NumberOfHarmonics = 100;
  options.Solver.BandSize = 20;
  Received received;
  options.Sink = Collecting(received, 100);
  bool stop = false;
  const auto collect = options.Sink.Harmonics;
  options.Sink.Harmonics = [&](int first, const Vector& values, const DenseMatrix& harmonics)
  {
    collect(first, values, harmonics);
    stop = true;
  };
  Monitor monitor;
  monitor.Cancelled = [&stop]() { return stop; };
  const TriangleMesh torus = NoisyTorusOfSize(1500, 0.1);
  CheckThrows<Cancelled>(
    [&]() { ComputeBasis(torus, options, monitor); }, "cancelled after the first block");
  const long delivered = std::count(received.Times.begin(), received.Times.end(), 1);
  Check(delivered > 0 && delivered < 100,
    "it stopped mid-stream: " + std::to_string(delivered) + " of 100 delivered");
}

//------------------------------------------------------------------------------
void RefusedAndMemory()
{
  BasisOptions options;
  options.NumberOfHarmonics = 10;
  options.UpperFrequency = 5.0;
  Received received;
  options.Sink = Collecting(received, 10);
  CheckThrows<InvalidInput>(
    [&]() { ComputeBasis(Icosphere(3), options); }, "a frequency window is not streamed");

  // Beyond three bands the streamed estimate no longer grows with m.
  const MemoryEstimate a = EstimateStreamedMemory(1000000, 1000000, 1000, 0);
  const MemoryEstimate b = EstimateStreamedMemory(1000000, 1000000, 3000, 0);
  Check(a.Total() == b.Total(), "the streamed estimate of 1000 and 3000 harmonics are equal");
  Check(b.Total() < EstimateBasisMemory(1000000, 1000000, 1000, 0, 8).Total(),
    "3000 streamed harmonics take less than 1000 in memory");

  // A limit between the two estimates: in memory refused, streamed computed.
  const TriangleMesh torus = NoisyTorusOfSize(3000, 0.1);
  const std::uint64_t n = static_cast<std::uint64_t>(torus.Vertices.rows());
  BasisOptions limited;
  limited.NumberOfHarmonics = 900;
  limited.MemoryLimit =
    (EstimateStreamedMemory(n, n, 900, 0).Total() + EstimateBasisMemory(n, n, 900, 0, 8).Total()) /
    2;
  CheckThrows<InsufficientMemory>(
    [&]() { ComputeBasis(torus, limited); }, "the limit refuses the basis in memory");
  Received streamed;
  limited.Sink = Collecting(streamed, 900);
  ComputeBasis(torus, limited);
  Check(std::count(streamed.Times.begin(), streamed.Times.end(), 1) == 900,
    "and streams it: 900 harmonics");
}

/**
 * Whether the harmonics B, computed in other bands than A, are A's to within what their residuals
 * allow: for each group of eigenvalues closer than 1e-6 relative (GroupEnd),
 * Davis and Kahan's bound on the sine of the angle between a computed eigenspace and the exact
 * one, ||R||_{D^-1} / gap, for both: sqrt(size) (residualA + residualB) max(|lambda|, lambda_1)
 * / gap (the block residual R of a group of `size` pairs at most sqrt(size) times its worst), with
 * the relative residuals of EigenResult::MaxResidual and the gap to the nearest eigenvalue
 * outside the group (the last group, whose gap above is unknown, is left out), plus 1e-12 for
 * rounding. \return the largest ratio of a group's difference to its bound (pass: <= 1).
 */
double WorstAgainstResidualBound(const DenseMatrix& A,
  const DenseMatrix& B,
  const Vector& lambda,
  const Vector& mass,
  double residualA,
  double residualB)
{
  const Eigen::Index m = lambda.size();
  double lambda1 = 0.0;
  for (Eigen::Index k = 0; k < m && lambda1 == 0.0; ++k)
  {
    lambda1 = lambda[k] > 0.0 ? lambda[k] : 0.0;
  }
  double worst = 0.0;
  for (Eigen::Index k = 0; k < m;)
  {
    const Eigen::Index end = GroupEnd(lambda, k);
    if (end == m)
    {
      break;
    }
    const double gap =
      std::min(lambda[end] - lambda[end - 1], k > 0 ? lambda[k] - lambda[k - 1] : HUGE_VAL);
    const double bound = std::sqrt(static_cast<double>(end - k)) * (residualA + residualB) *
        std::max(std::abs(lambda[end - 1]), lambda1) / gap +
      1e-12;
    const Vector groupLambda = lambda.segment(k, end - k);
    const double difference =
      HarmonicsDifference(A.middleCols(k, end - k), B.middleCols(k, end - k), groupLambda, mass);
    worst = std::max(worst, difference / bound);
    k = end;
  }
  return worst;
}

//------------------------------------------------------------------------------
// A limit that the automatic bands of 100 do not fit but bands of 40 do: the memory plan
// (PlanStreamedMemory, Solver/Memory.h) streams in bands of 40 and says so, and the basis is the
// one of the automatic bands: eigenvalues to 1e-12 relative, harmonics within their residual bound.
void SmallerBandsToFit()
{
  const TriangleMesh torus = NoisyTorusOfSize(3000, 0.1);
  const std::uint64_t n = static_cast<std::uint64_t>(torus.Vertices.rows());
  const int m = 300;
  BasisOptions options;
  options.NumberOfHarmonics = m;
  const BasisResult memory = ComputeBasis(torus, options);
  Received unlimitedReceived;
  options.Sink = Collecting(unlimitedReceived, m);
  const BasisResult unlimited = ComputeBasis(torus, options);
  // A step of the band takes 56 to 60 bytes a point (TestMemory.PlanChoosesBands): 24 above the
  // estimate at 40 is below the one at 41.
  options.MemoryLimit = EstimateStreamedMemory(n, n, m, 40).Total() + 24 * n;
  Check(EstimateStreamedMemory(n, n, m, 0).Total() > options.MemoryLimit,
    "the automatic bands do not fit the limit");
  Received received;
  options.Sink = Collecting(received, m);
  const BasisResult planned = ComputeBasis(torus, options);
  const bool warned = std::any_of(planned.Warnings.begin(),
    planned.Warnings.end(),
    [](const std::string& w) { return w.find("Bands of 40 eigenpairs instead of 100") == 0; });
  Check(warned, "a warning says the bands are of 40 eigenpairs instead of 100");
  std::printf("    bands: %d automatic, %d planned\n", unlimited.Pairs.Bands, planned.Pairs.Bands);
  Check(planned.Pairs.Bands >= m / 40 && planned.Pairs.Bands > unlimited.Pairs.Bands,
    "the solve ran in more, smaller bands");
  Check(std::all_of(received.Times.begin(), received.Times.end(), [](int t) { return t == 1; }),
    "every harmonic delivered once");
  const double values = EigenvalueDifference(received.Values, memory.Pairs.Eigenvalues);
  std::printf("    eigenvalues: largest relative difference %.3e\n", values);
  CheckBelow(values, 1e-12, "the eigenvalues of the automatic bands (relative)");
  const double ratio = WorstAgainstResidualBound(memory.Pairs.Eigenvectors,
    received.Harmonics,
    memory.Pairs.Eigenvalues,
    memory.LumpedMass,
    memory.Pairs.MaxResidual,
    planned.Pairs.MaxResidual);
  std::printf("    harmonics: largest difference / residual bound %.3e\n", ratio);
  CheckBelow(ratio, 1.0, "the harmonics of the automatic bands, within their residual bound");

  // Below the estimate at the smallest planned band: refused, naming that estimate.
  options.MemoryLimit = EstimateStreamedMemory(n, n, m, SmallestPlannedBand).Total() - 1;
  try
  {
    ComputeBasis(torus, options);
    Check(false, "below the smallest planned band: refused");
  }
  catch (const InsufficientMemory& e)
  {
    Check(e.Needed.Total() == EstimateStreamedMemory(n, n, m, SmallestPlannedBand).Total(),
      "below the smallest planned band: refused with the estimate at that band");
  }
}

/**
 * The streamed filter of `signals` against ForwardTransform + FilterSignal on the in-memory basis
 * (a low pass at half the highest frequency, re-injecting the rest with its mean gain), relative
 * to the largest signal value.
 */
void FilterMatches(const TriangleMesh& mesh,
  int m,
  const RowMatrix& signals,
  const std::string& name,
  bool oneComponent)
{
  BasisOptions options;
  options.NumberOfHarmonics = m;
  // A volume has no triangles to measure: any Nyquist frequency above the basis's highest gives
  // this low pass the re-injection gain 0, as on the surfaces.
  const double nyquist = mesh.IsVolume() ? 1e6 : NyquistFrequency(mesh);
  FilterParameters relative;
  relative.Cutoff = 0.5;
  const auto design = [&](double highest, double& hfGain)
  {
    const Vector top = Vector::Constant(1, highest);
    const FilterParameters p =
      ToAbsoluteUnits(relative, FrequencyUnits::FractionOfHighest, top, 0.0);
    hfGain = MeanGain(p, HighestFrequency(top), nyquist);
    return p;
  };
  // In memory: the basis on every input point (zero rows outside the used ones).
  const BasisResult memory = ComputeBasis(mesh, options);
  const Eigen::Index n = signals.rows();
  const Eigen::Index used = static_cast<Eigen::Index>(memory.InputPointIds.size());
  RowMatrix H = RowMatrix::Zero(n, memory.Pairs.Eigenvalues.size());
  Vector mass = Vector::Zero(n);
  for (Eigen::Index r = 0; r < used; ++r)
  {
    const int row = memory.InputPointIds[static_cast<std::size_t>(r)];
    H.row(row) = memory.Pairs.Eigenvectors.row(r);
    mass[row] = memory.LumpedMass[r];
  }
  const ConstRowView X(signals.data(), signals.rows(), signals.cols());
  const BasisView basis(H.data(), H.rows(), H.cols());
  const RowMatrix coefficients = ForwardTransform(basis, mass, X);
  double hfGain = 0.0;
  const Vector& lambda = memory.Pairs.Eigenvalues;
  const Vector gains = Gains(design(lambda[lambda.size() - 1], hfGain), lambda);
  const RowMatrix expected = FilterSignal(basis,
    mass,
    gains,
    ConstRowView(coefficients.data(), coefficients.rows(), coefficients.cols()),
    X,
    hfGain);
  StreamedFilter filter(X, design);
  options.Sink = filter.Sink();
  // Which harmonics the filter received: those of a gain other than hfGain at least (the others
  // add nothing), and, for this low pass, not all (BasisSink::Wanted).
  std::vector<int> received(static_cast<std::size_t>(gains.size()), 0);
  const auto add = options.Sink.Harmonics;
  options.Sink.Harmonics = [&](int first, const Vector& values, const DenseMatrix& harmonics)
  {
    for (Eigen::Index j = 0; j < values.size(); ++j)
    {
      ++received[static_cast<std::size_t>(first + j)];
    }
    add(first, values, harmonics);
  };
  const BasisResult streamed = ComputeBasis(mesh, options);
  const RowMatrix Y = filter.Result();
  int receivedCount = 0;
  int wantedCount = 0;
  int twice = 0;
  int missing = 0;
  for (Eigen::Index j = 0; j < gains.size(); ++j)
  {
    const int times = received[static_cast<std::size_t>(j)];
    receivedCount += times;
    wantedCount += gains[j] != hfGain ? 1 : 0;
    twice += times > 1 ? 1 : 0;
    missing += gains[j] != hfGain && times == 0 ? 1 : 0;
  }
  Check(twice == 0, name + "no harmonic received twice");
  Check(missing == 0, name + "every harmonic of a gain other than hfGain received");
  std::printf("    %s%d of %d harmonics solved and filtered, %d of them with a gain other than "
              "hfGain %g\n",
    name.c_str(),
    receivedCount,
    static_cast<int>(gains.size()),
    wantedCount,
    hfGain);
  Check(wantedCount < gains.size() && receivedCount < gains.size(),
    name + "the low pass solved fewer harmonics than the basis has");
  // The solves' work, in vectors solved with a factor: with one component the streamed low pass
  // finds the highest eigenvalue alone and solves the harmonics below its transition, less
  // than the in-memory basis of all m harmonics (several components solve the spectrum first).
  const double work = static_cast<double>(streamed.Pairs.OperatorApplications) /
    static_cast<double>(memory.Pairs.OperatorApplications);
  std::printf("    %ssolved vectors: %lld streamed, %lld in memory (%.2f)\n",
    name.c_str(),
    streamed.Pairs.OperatorApplications,
    memory.Pairs.OperatorApplications,
    work);
  if (oneComponent)
  {
    // (Before the highest eigenvalue was found alone, it was twice the work at least.)
    CheckBelow(work, 1.0, name + "streamed with less work than the basis in memory");
  }
  // The eigenvalues the stream reports: those of the harmonics it solved, and the highest.
  const Eigen::Index last = lambda.size() - 1;
  double eigenvalues = 0.0;
  for (Eigen::Index k = 0; k <= last; ++k)
  {
    if (received[static_cast<std::size_t>(k)] == 1 || k == last)
    {
      eigenvalues = std::max(eigenvalues,
        std::abs(streamed.Pairs.Eigenvalues[k] - lambda[k]) /
          std::max(std::abs(lambda[k]), 1e-6 * lambda[last]));
    }
  }
  CheckBelow(eigenvalues, 1e-10, name + "the eigenvalues it reports equal the in-memory ones");
  const double scale = signals.cwiseAbs().maxCoeff();
  CheckBelow((Y - expected).cwiseAbs().maxCoeff() / scale,
    1e-12,
    name + "the streamed filter equals ForwardTransform + FilterSignal (relative)");
  Check((Y - signals).cwiseAbs().maxCoeff() > 1e-3 * scale, name + "and it filtered");
  for (Eigen::Index i = 0; i < n; ++i)
  {
    if (mass[i] == 0.0)
    {
      Check(Y.row(i) == signals.row(i), name + "a point no cell uses keeps its value");
    }
  }
}

//------------------------------------------------------------------------------
void FilterMatchesInMemory()
{
  // The coordinates and a scalar, on one component in bands and on several components with a
  // point no triangle uses (it keeps its value).
  const TriangleMesh torus = NoisyTorusOfSize(4000, 0.1);
  RowMatrix signals(torus.Vertices.rows(), 4);
  signals.leftCols(3) = torus.Vertices;
  signals.col(3) = torus.Vertices.col(0).array().square();
  FilterMatches(torus, 300, signals, "torus: ", true);
  // One component with a boundary (Weyl's law, which gives the first shift of the search for
  // the highest eigenvalue, counts a closed surface's), a sphere whose 95th eigenvalue lies in
  // the near-multiplet of degree 9, and a volume (its own law, lambda^(3/2)).
  const TriangleMesh disc = Disc(40);
  FilterMatches(disc, 150, disc.Vertices, "disc: ", true);
  const TriangleMesh sphere = Icosphere(4);
  // (Its coordinates are harmonics of degree 1, which the low pass keeps: x^7 has degrees to 7.)
  const RowMatrix seventh = sphere.Vertices.array().pow(7);
  FilterMatches(sphere, 95, seventh, "sphere: ", true);
  const TriangleMesh ball = TetrahedralBall(12);
  FilterMatches(ball, 120, ball.Vertices, "ball: ", true);
  TriangleMesh mesh = Join(Icosphere(3), Translated(NoisyTorusOfSize(1500, 0.1), 3.0));
  mesh.Vertices.conservativeResize(mesh.Vertices.rows() + 1, 3);
  mesh.Vertices.bottomRows(1) << 9.0, 9.0, 9.0;
  RowMatrix more(mesh.Vertices.rows(), 3);
  more = mesh.Vertices;
  FilterMatches(mesh, 120, more, "two components and an unused point: ", false);
}

const Case Cases[] = {
  { "OneComponent", OneComponent },
  { "SeveralComponents", SeveralComponents },
  { "ScanDefects", ScanDefects },
  { "Volume", Volume },
  { "CancelledMidStream", CancelledMidStream },
  { "RefusedAndMemory", RefusedAndMemory },
  { "SmallerBandsToFit", SmallerBandsToFit },
  { "FilterMatchesInMemory", FilterMatchesInMemory },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
