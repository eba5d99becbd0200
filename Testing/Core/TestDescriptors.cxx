// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Properties of the spectral shape descriptors (Filters/Spectral/Filtering/Descriptors.h):
// analytic values on the unit sphere, invariance under isometries, symmetry of the distances,
// scale invariance of ShapeDNA, float bases, and refused input.
#include "Basis.h"
#include "Checks.h"
#include "Filtering/Descriptors.h"
#include "Meshes.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

using namespace spectral;
using namespace spectral::testing;

namespace
{
const double Pi = 3.14159265358979323846;
/// The eigensolver's verified bound on the relative residual of every pair (EigenSolver.h).
const double SolverResidual = 1e-8;

/// A basis in the row-major layout of the VTK point-data array, with its mass and spectrum.
struct Basis
{
  RowMatrix H; // n x m
  Vector Mass;
  Spectrum Pairs;

  BasisView View() const { return BasisView(this->H.data(), this->H.rows(), this->H.cols()); }
  double Area() const { return this->Mass.sum(); }
};

/// The basis of m harmonics through the core's entry point; the zero eigenvalues are the first
/// Components ones (one constant harmonic per connected component).
Basis MakeBasis(const TriangleMesh& mesh, int m)
{
  BasisOptions options;
  options.NumberOfHarmonics = m;
  options.CheckMemory = false;
  const BasisResult result = ComputeBasis(mesh, options);
  Basis b;
  b.H = result.Pairs.Eigenvectors;
  b.Mass = result.LumpedMass;
  b.Pairs.Lambda = result.Pairs.Eigenvalues;
  b.Pairs.NonZero.assign(static_cast<std::size_t>(m), true);
  for (int k = 0; k < result.Components; ++k)
  {
    b.Pairs.NonZero[k] = false;
  }
  return b;
}

/// The largest |a - b| relative to the largest |b| of each column.
double ColumnRelativeDifference(const RowMatrix& a, const RowMatrix& b)
{
  double worst = 0.0;
  for (Eigen::Index c = 0; c < b.cols(); ++c)
  {
    const double scale = b.col(c).cwiseAbs().maxCoeff();
    worst = std::max(worst, (a.col(c) - b.col(c)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

/// The heat kernel signature of the unit sphere at time t, the same at every point:
/// sum_l (2l + 1) e^{-l(l+1)t} / (4 pi), summed until the terms no longer count.
double SphereHeatKernel(double t)
{
  double sum = 0.0;
  for (int l = 0; l < 10000; ++l)
  {
    const double term = (2 * l + 1) * std::exp(-l * (l + 1.0) * t);
    sum += term;
    if (l > 1 && term < 1e-18 * sum)
    {
      break;
    }
  }
  return sum / (4.0 * Pi);
}

/// The degree l of the k-th eigenvalue of the unit sphere, l(l+1) with multiplicity 2l + 1.
int SphereDegree(Eigen::Index k)
{
  return static_cast<int>(std::floor(std::sqrt(static_cast<double>(k))));
}

//------------------------------------------------------------------------------
void SphereHeatKernelSignature()
{
  // 2562 points, 121 harmonics: the complete clusters l = 0 ... 10.
  const Basis b = MakeBasis(Icosphere(4), 121);
  const Eigen::Index m = b.Pairs.Lambda.size();
  Vector exactLambda(m);
  for (Eigen::Index k = 0; k < m; ++k)
  {
    const int l = SphereDegree(k);
    exactLambda[k] = l * (l + 1.0);
  }
  const double area = b.Area();
  // Times at which the first missing cluster (l = 11, lambda = 132) weighs less than 1e-8 of
  // the trace: the comparison measures the discretization, not the truncation.
  const Vector times = (Vector(4) << 0.15, 0.3, 1.0, 3.0).finished();
  const RowMatrix hks = HeatKernelSignature(b.View(), b.Pairs, times, false);
  for (Eigen::Index j = 0; j < times.size(); ++j)
  {
    const double t = times[j];
    const double exact = SphereHeatKernel(t);
    char label[64];
    std::snprintf(label, sizeof(label), "t = %g: ", t);
    const std::string at(label);
    // The exact tail beyond the basis, l >= 11.
    double tail = 0.0;
    for (int l = 11; l < 200; ++l)
    {
      tail += (2 * l + 1) * std::exp(-l * (l + 1.0) * t) / (4.0 * Pi);
    }
    CheckBelow(tail / exact, 1e-8, at + "truncation of the exact series at l = 10 is negligible");
    CheckBelow(HeatKernelHarmonicsNeeded(b.Pairs, area, 2, t),
      static_cast<double>(m),
      at + "Weyl estimate: the basis is long enough for 1%");

    // Identity: the mass-weighted mean of the signature is the heat trace over the area.
    const double mean = b.Mass.dot(hks.col(j)) / area;
    const double trace = HeatTrace(b.Pairs, Vector::Constant(1, t))[0];
    CheckNear(mean, trace / area, 1e-12 * mean, at + "mass-weighted mean = heat trace / area");

    // The mesh's heat trace differs from the sphere's through its eigenvalue errors and its
    // area only: |Z/A - Z*/(4 pi)| <= sum_k |e^{-lambda_k t} - e^{-l(l+1)t}| / A
    //                                   + Z* |1/A - 1/(4 pi)| (+ the tail).
    const Vector meshTerms = (-t * HeatEigenvalues(b.Pairs)).array().exp();
    const Vector exactTerms = (-t * exactLambda).array().exp();
    const double eigenvalueBound = (meshTerms - exactTerms).cwiseAbs().sum() / area;
    const double areaBound = exactTerms.sum() * std::abs(1.0 / area - 1.0 / (4.0 * Pi));
    // (The bound is attained when all errors have one sign; 1e-12 of the value covers the
    // round-off of the sums.)
    CheckBelow(std::abs(mean - exact),
      eigenvalueBound + areaBound + tail + 1e-12 * exact,
      at + "mean HKS vs sum_l (2l+1) e^{-l(l+1)t} / 4 pi within the eigenvalue and area error");

    // Pointwise: the signature is the sphere's at every point. Cluster l contributes
    // e^{-lambda_k t} sum_{k in l} h_k(i)^2. Its eigenvalue errors change the exponentials by
    // |e^{-lambda_k t} - e^{-l(l+1)t}| (measured, weighed by h_k(i)^2 at the point); the mesh's
    // area normalizes the harmonics (sum_{k in l} h_k^2 averages (2l+1)/A, not (2l+1)/(4 pi));
    // and the projector diagonal sum_{k in l} h_k(i)^2 departs from its mean by the eigenvector
    // error. For a Galerkin approximation lambda_h - lambda = |u - u_h|_a^2 - lambda |u - u_h|^2
    // (Strang and Fix, An Analysis of the Finite Element Method, ch. 6): the relative
    // eigenvector error is of the order of sqrt(eps_l), eps_l the largest relative eigenvalue
    // error of cluster l, and the squares change by twice that:
    // bound(i) = sum_k |e^{-lambda_k t} - e^{-l(l+1)t}| h_k(i)^2 + Z*(t) |1/A - 1/(4 pi)|
    //            + sum_l e^{-l(l+1)t} (2l+1)/(4 pi) 2 sqrt(eps_l).
    double vectorBound = 0.0;
    for (int l = 1; (l + 1) * (l + 1) <= m; ++l)
    {
      double epsilon = 0.0;
      for (Eigen::Index k = l * l; k < (l + 1) * (l + 1); ++k)
      {
        epsilon = std::max(epsilon, std::abs(b.Pairs.Lambda[k] - exactLambda[k]) / exactLambda[k]);
      }
      vectorBound +=
        (2 * l + 1) * std::exp(-l * (l + 1.0) * t) / (4.0 * Pi) * 2.0 * std::sqrt(epsilon);
    }
    const RowMatrix squared = b.H.cwiseAbs2();
    double worst = 0.0;
    double worstRatio = 0.0;
    for (Eigen::Index i = 0; i < b.H.rows(); ++i)
    {
      const double eigenvalueTerm = squared.row(i).dot((meshTerms - exactTerms).cwiseAbs());
      const double bound = eigenvalueTerm + areaBound + vectorBound + tail;
      const double error = std::abs(hks(i, j) - exact);
      worst = std::max(worst, error);
      worstRatio = std::max(worstRatio, error / bound);
    }
    std::printf("    t = %g: HKS exact %.6g, max pointwise error %.3e (relative %.2e); bounds: "
                "eigenvalues and area on the mean %.3e, eigenvectors %.3e\n",
      t,
      exact,
      worst,
      worst / exact,
      eigenvalueBound + areaBound,
      vectorBound);
    CheckBelow(worstRatio, 1.0, at + "pointwise error / its bound");
  }
}

/// The same basis stored in single precision.
FloatRowMatrix ToFloat(const Basis& b)
{
  return b.H.cast<float>();
}

/// The relative tolerance of comparing heat kernel signatures of two bases of the same
/// operators (equal to round-off), which differ only by the eigensolver's residual r = 1e-8:
/// the eigenvalues by r lambda at most, which moves e^{-lambda t} by r lambda t e^{-lambda t}
/// <= r / e, and the projector onto each group of (nearly) equal eigenvalues by r / gap
/// (Davis and Kahan), gap the smallest relative distance between groups, which moves its
/// h_k(i)^2 by twice that. Groups are eigenvalues within 1e-6 relative of each other (exact
/// multiplicities to round-off); inside one, e^{-lambda t} varies by at most 1e-6 / e.
/// \param lambda m + 1 eigenvalues: the last one measures the gap after the basis.
double EigensolverTolerance(const Vector& lambda, int zeros)
{
  double gap = std::numeric_limits<double>::infinity();
  for (Eigen::Index k = zeros; k + 1 < lambda.size(); ++k)
  {
    const double relative = (lambda[k + 1] - lambda[k]) / lambda[k + 1];
    if (relative > 1e-6)
    {
      gap = std::min(gap, relative);
    }
  }
  std::printf("    smallest relative gap between eigenvalue groups %.3e\n", gap);
  return 2.0 * SolverResidual / gap + SolverResidual / std::exp(1.0) + 1e-6 / std::exp(1.0);
}

/// The first m harmonics of a basis of m + 1.
Basis FirstHarmonics(const Basis& b, int m)
{
  Basis first;
  first.H = b.H.leftCols(m);
  first.Mass = b.Mass;
  first.Pairs.Lambda = b.Pairs.Lambda.head(m);
  first.Pairs.NonZero.assign(b.Pairs.NonZero.begin(), b.Pairs.NonZero.begin() + m);
  return first;
}

/// The largest |a - b| / |b| over all entries.
double EntrywiseRelativeDifference(const RowMatrix& a, const RowMatrix& b)
{
  return ((a - b).array().abs() / b.array().abs()).maxCoeff();
}

//------------------------------------------------------------------------------
void IsometryInvariance()
{
  const int m = 40;
  const Vector times = (Vector(3) << 0.02, 0.1, 0.5).finished();
  // A flat strip rolled into a half cylinder of radius 1: the flat points are a chord c apart
  // along x, so every edge keeps its length exactly (the chord in the xz plane is c in both,
  // the y step is the same): the cotangent Laplacian and the mass, functions of the edge
  // lengths, are the same.
  const int nx = 24;
  const int ny = 8;
  const double step = Pi / nx;
  const double chord = 2.0 * std::sin(step / 2.0);
  const TriangleMesh flat = Rectangle(nx * chord, 1.0, nx, ny);
  TriangleMesh rolled = flat;
  for (Eigen::Index i = 0; i < rolled.Vertices.rows(); ++i)
  {
    const double angle = std::round(flat.Vertices(i, 0) / chord) * step;
    rolled.Vertices.row(i) << std::cos(angle), flat.Vertices(i, 1), std::sin(angle);
  }
  // A rigid motion of a generic (noisy) torus: rotation about (1, 2, 3) by 0.7, translation.
  const TriangleMesh torus = NoisyTorus(24, 12, 0.1);
  const Eigen::Matrix3d rotation =
    Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  TriangleMesh moved = torus;
  moved.Vertices =
    (torus.Vertices * rotation.transpose()).rowwise() + Eigen::RowVector3d(3.0, -1.0, 2.0);

  const std::pair<TriangleMesh, TriangleMesh> pairs[] = { { flat, rolled }, { torus, moved } };
  const char* names[] = { "strip rolled into a half cylinder", "torus rotated and translated" };
  for (int p = 0; p < 2; ++p)
  {
    const Basis a = MakeBasis(pairs[p].first, m + 1);
    const Basis b = MakeBasis(pairs[p].second, m + 1);
    const double tolerance = EigensolverTolerance(a.Pairs.Lambda, 1);
    const RowMatrix hksA =
      HeatKernelSignature(FirstHarmonics(a, m).View(), FirstHarmonics(a, m).Pairs, times, false);
    const RowMatrix hksB =
      HeatKernelSignature(FirstHarmonics(b, m).View(), FirstHarmonics(b, m).Pairs, times, false);
    CheckBelow(EntrywiseRelativeDifference(hksB, hksA),
      tolerance,
      std::string(names[p]) + ": HKS unchanged (relative, every point and time)");
  }
}

//------------------------------------------------------------------------------
void DistancesSymmetric()
{
  const Basis b = MakeBasis(NoisyTorus(24, 12, 0.1), 40);
  const Eigen::Index x = 7;
  const Eigen::Index y = 150;
  const char* names[] = { "diffusion", "commute time", "biharmonic" };
  for (int kind = 0; kind < 3; ++kind)
  {
    const Vector w = DistanceWeights(b.Pairs, static_cast<DistanceKind>(kind), 0.05);
    const Vector fromX = SpectralDistance(b.View(), w, x);
    const Vector fromY = SpectralDistance(b.View(), w, y);
    const std::string name = names[kind];
    CheckNear(fromX[y], fromY[x], 1e-12 * fromX.maxCoeff(), name + ": d(x, y) = d(y, x)");
    Check(fromX[x] == 0.0 && fromY[y] == 0.0, name + ": zero at the source");
    Vector others = fromX;
    others[x] = std::numeric_limits<double>::infinity();
    const double smallest = others.minCoeff() / fromX.maxCoeff();
    std::printf(
      "    %s: smallest distance to another point / largest %.3e\n", names[kind], smallest);
    Check(smallest > 1e-6, name + ": positive at every other point");
  }
  // The global point signature with every non-constant harmonic embeds the commute-time
  // distance: |GPS(x) - GPS(y)| = d_C(x, y).
  const RowMatrix gps = GlobalPointSignature(b.View(), b.Pairs, 39);
  const Vector commute =
    SpectralDistance(b.View(), DistanceWeights(b.Pairs, DistanceKind::CommuteTime), x);
  CheckNear((gps.row(y) - gps.row(x)).norm(),
    commute[y],
    1e-12 * commute[y],
    "|GPS(x) - GPS(y)| = commute-time distance");
}

//------------------------------------------------------------------------------
void ShapeDNAScaleInvariant()
{
  const int m = 25; // the complete clusters l = 0 ... 4 of the sphere
  const TriangleMesh unit = Icosphere(4);
  TriangleMesh large = unit;
  large.Vertices *= 3.0;
  const Basis small = MakeBasis(unit, m);
  const Basis big = MakeBasis(large, m);
  const Basis torus = MakeBasis(Torus(1.0, 0.35, 40, 14), m);
  const Vector dnaSmall = ShapeDNA(small.Pairs.Lambda, small.Area());
  const Vector dnaBig = ShapeDNA(big.Pairs.Lambda, big.Area());
  const Vector dnaTorus = ShapeDNA(torus.Pairs.Lambda, torus.Area());
  CheckNear(big.Area() / small.Area(), 9.0, 1e-12, "the radius-3 sphere has 9 times the area");
  // The operators of the two spheres are the same up to the factor 9 of the mass (cotangents do
  // not change with scale): lambda A agrees to the eigensolver's residual.
  CheckBelow(
    ((dnaBig - dnaSmall).tail(m - 1).array() / dnaSmall.tail(m - 1).array()).abs().maxCoeff(),
    SolverResidual,
    "ShapeDNA of radius 1 and 3 equal (relative)");
  Vector exact(m);
  for (int k = 0; k < m; ++k)
  {
    exact[k] = 4.0 * Pi * SphereDegree(k) * (SphereDegree(k) + 1.0);
  }
  const double discretization = (dnaSmall - exact).norm() / exact.norm();
  const double torusDifference = (dnaTorus - dnaSmall).norm() / dnaSmall.norm();
  std::printf(
    "    sphere vs 4 pi l(l+1): %.3e; torus vs sphere: %.3e\n", discretization, torusDifference);
  Check(torusDifference > 10.0 * discretization,
    "the torus's ShapeDNA differs from the sphere's by more than 10 times the sphere's "
    "discretization error");
}

//------------------------------------------------------------------------------
void FloatBasisMatchesDouble()
{
  // A float basis rounds each entry by 6e-8 relative; squares and products by 1.2e-7. The
  // descriptors accumulate in double, so they agree to a few 1e-7 of each column's largest
  // value (distances near the source are small differences: relative to the largest).
  const Basis b = MakeBasis(NoisyTorus(24, 12, 0.1), 40);
  const FloatRowMatrix f = ToFloat(b);
  const FloatBasisView F(f.data(), f.rows(), f.cols());
  const Vector times = DefaultHeatKernelTimes(b.Pairs);
  CheckBelow(ColumnRelativeDifference(HeatKernelSignature(F, b.Pairs, times, true),
               HeatKernelSignature(b.View(), b.Pairs, times, true)),
    1e-6,
    "HKS");
  const WaveKernelEnergies energies = DefaultWaveKernelEnergies(b.Pairs);
  CheckBelow(ColumnRelativeDifference(WaveKernelSignature(F, b.Pairs, energies),
               WaveKernelSignature(b.View(), b.Pairs, energies)),
    1e-6,
    "WKS");
  CheckBelow(ColumnRelativeDifference(
               GlobalPointSignature(F, b.Pairs, 10), GlobalPointSignature(b.View(), b.Pairs, 10)),
    1e-6,
    "GPS");
  for (int kind = 0; kind < 3; ++kind)
  {
    const Vector w = DistanceWeights(b.Pairs, static_cast<DistanceKind>(kind), 0.05);
    CheckBelow(
      ColumnRelativeDifference(SpectralDistance(F, w, 3), SpectralDistance(b.View(), w, 3)),
      1e-6,
      "distance kind " + std::to_string(kind));
  }
}

//------------------------------------------------------------------------------
void TimesAndEnergies()
{
  const Basis b = MakeBasis(NoisyTorus(24, 12, 0.1), 40);
  const double lambda1 = b.Pairs.Lambda[1];
  const double lambdaMax = b.Pairs.Lambda[39];
  const Vector times = DefaultHeatKernelTimes(b.Pairs);
  const double fourLn10 = 4.0 * std::log(10.0);
  Check(times.size() == 16, "16 default times");
  CheckNear(times[0], fourLn10 / lambdaMax, 1e-12 * times[0], "first time 4 ln 10 / lambda_max");
  CheckNear(times[15], fourLn10 / lambda1, 1e-12 * times[15], "last time 4 ln 10 / lambda_1");
  const Vector ratios = times.tail(15).cwiseQuotient(times.head(15));
  CheckBelow(ratios.maxCoeff() - ratios.minCoeff(), 1e-12, "times log-spaced");

  for (int count : { 1, 5, 100 })
  {
    const WaveKernelEnergies e = DefaultWaveKernelEnergies(b.Pairs, count);
    const std::string at = std::to_string(count) + " energies: ";
    const double step = (std::log(lambdaMax) - std::log(lambda1)) / (count + 27);
    CheckNear(e.Sigma, 7.0 * step, 1e-12 * e.Sigma, at + "sigma = 7 steps");
    CheckNear(e.Energies[0],
      std::log(lambda1) + 2.0 * e.Sigma,
      1e-12,
      at + "first energy log lambda_1 + 2 sigma");
    CheckNear(e.Energies[count - 1],
      std::log(lambdaMax) - 2.0 * e.Sigma,
      1e-12,
      at + "last energy log lambda_max - 2 sigma");
    // Each column is a weighted mean of the h_k^2: its integral is 1 for an orthonormal basis.
    const RowMatrix wks = WaveKernelSignature(b.View(), b.Pairs, e);
    CheckBelow(((b.Mass.transpose() * wks).array() - 1.0).abs().maxCoeff(),
      1e-10,
      at + "sum_i D_ii WKS(i, e) = 1");
  }
  const WaveKernelEnergies explicitSigma = DefaultWaveKernelEnergies(b.Pairs, 10, 0.1);
  CheckNear(explicitSigma.Energies[0], std::log(lambda1) + 0.2, 1e-12, "explicit sigma margins");
  // The scale-normalized signature integrates to 1 at every time.
  const RowMatrix normalized = HeatKernelSignature(b.View(), b.Pairs, times, true);
  CheckBelow(((b.Mass.transpose() * normalized).array() - 1.0).abs().maxCoeff(),
    1e-10,
    "sum_i D_ii HKS(i, t) / Z(t) = 1");
}

//------------------------------------------------------------------------------
// HeatKernelHarmonicsNeeded from the 16 lowest of an exact spectrum (ascending, long enough for
// the times) of a shape of the given measure and dimension, against the exact number of
// harmonics for a 1% tail of the heat trace at each time: within a factor 2, fewer for longer
// times, every harmonic at t = 0.
void CheckWeylEstimate(const std::vector<double>& exact,
  double measure,
  int dimension,
  std::initializer_list<double> times)
{
  Spectrum sixteen;
  sixteen.Lambda = Eigen::Map<const Vector>(exact.data(), 16);
  sixteen.NonZero.assign(16, true);
  sixteen.NonZero[0] = false;
  int previous = std::numeric_limits<int>::max();
  for (double t : times)
  {
    double total = 0.0;
    for (double lambda : exact)
    {
      total += std::exp(-lambda * t);
    }
    std::size_t needed = exact.size();
    double tail = 0.0;
    while (needed > 0 && tail + std::exp(-exact[needed - 1] * t) <= 0.01 * total)
    {
      tail += std::exp(-exact[--needed] * t);
    }
    const int estimate = HeatKernelHarmonicsNeeded(sixteen, measure, dimension, t);
    std::printf("    t = %g: %zu harmonics needed, Weyl estimate %d\n", t, needed, estimate);
    Check(estimate >= 0.5 * needed && estimate <= 2.0 * needed,
      "t = " + std::to_string(t) + ": estimate within a factor 2");
    Check(estimate <= previous, "fewer harmonics for longer times");
    previous = estimate;
  }
  Check(
    HeatKernelHarmonicsNeeded(sixteen, measure, dimension, 0.0) == std::numeric_limits<int>::max(),
    "t = 0 needs every harmonic");
}

//------------------------------------------------------------------------------
void WeylEstimate()
{
  // The unit sphere's exact spectrum l(l+1).
  std::vector<double> exact;
  for (int l = 0; l < 400; ++l)
  {
    for (int k = 0; k <= 2 * l; ++k)
    {
      exact.push_back(l * (l + 1.0));
    }
  }
  CheckWeylEstimate(exact, 4.0 * Pi, 2, { 0.005, 0.02, 0.1, 0.5 });
}

//------------------------------------------------------------------------------
void WeylEstimateOfVolumes()
{
  // The unit cube's exact Neumann spectrum pi^2 (i^2 + j^2 + k^2): the estimate must use the
  // volume's law lambda_k ~ (6 pi^2 k / V)^(2/3) (the surface's law, with the volume as the
  // area, estimates 20 times too few at t = 0.001).
  const int n = 50; // e^{-pi^2 50^2 t} is negligible for the times below
  std::vector<double> exact;
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int k = 0; k < n; ++k)
      {
        exact.push_back(Pi * Pi * (i * i + j * j + k * k));
      }
    }
  }
  std::sort(exact.begin(), exact.end());
  CheckWeylEstimate(exact, 1.0, 3, { 0.001, 0.002, 0.005, 0.01, 0.02 });
  Spectrum sixteen;
  sixteen.Lambda = Eigen::Map<const Vector>(exact.data(), 16);
  sixteen.NonZero.assign(16, true);
  CheckThrows<InvalidInput>([&sixteen]() { HeatKernelHarmonicsNeeded(sixteen, 1.0, 4, 0.01); },
    "a dimension other than 2 and 3 is refused");
}

//------------------------------------------------------------------------------
void InvalidInputRefused()
{
  const Basis b = MakeBasis(Icosphere(2), 10);
  const Vector negative = Vector::Constant(1, -1.0);
  CheckThrows<InvalidInput>([&b, &negative]
    { HeatKernelSignature(b.View(), b.Pairs, negative, false); },
    "negative heat kernel time");
  CheckThrows<InvalidInput>(
    [&b] { DistanceWeights(b.Pairs, DistanceKind::Diffusion, -0.5); }, "negative diffusion time");
  CheckThrows<InvalidInput>(
    [&b] { SpectralDistance(b.View(), Vector::Ones(10), 162); }, "source point out of range");
  CheckThrows<InvalidInput>(
    [&b] { SpectralDistance(b.View(), Vector::Ones(9), 0); }, "weights of the wrong size");
  CheckThrows<InvalidInput>([&b] { GlobalPointSignature(b.View(), b.Pairs, 10); },
    "more GPS components than non-constant harmonics");
  CheckThrows<InvalidInput>(
    [&b] { GlobalPointSignature(b.View(), b.Pairs, 0); }, "no GPS component");
  CheckThrows<InvalidInput>([&b] { DefaultWaveKernelEnergies(b.Pairs, 10, 10.0); },
    "a sigma wider than a quarter of the log spectrum");
  Spectrum zeros = b.Pairs;
  zeros.NonZero.assign(10, false);
  CheckThrows<InvalidInput>(
    [&zeros] { DefaultHeatKernelTimes(zeros); }, "default times without a non-zero eigenvalue");
  Spectrum wrongSize = b.Pairs;
  wrongSize.NonZero.pop_back();
  CheckThrows<InvalidInput>(
    [&wrongSize] { HeatEigenvalues(wrongSize); }, "flags of the wrong size");
  CheckThrows<InvalidInput>([&b] { ShapeDNA(b.Pairs.Lambda, 0.0); }, "ShapeDNA of zero area");
}
} // anonymous namespace

const Case Cases[] = {
  { "SphereHeatKernelSignature", SphereHeatKernelSignature },
  { "IsometryInvariance", IsometryInvariance },
  { "DistancesSymmetric", DistancesSymmetric },
  { "ShapeDNAScaleInvariant", ShapeDNAScaleInvariant },
  { "FloatBasisMatchesDouble", FloatBasisMatchesDouble },
  { "TimesAndEnergies", TimesAndEnergies },
  { "WeylEstimate", WeylEstimate },
  { "WeylEstimateOfVolumes", WeylEstimateOfVolumes },
  { "InvalidInputRefused", InvalidInputRefused },
};

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
