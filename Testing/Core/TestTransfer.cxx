// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Properties of the manifold harmonic transform and the transfer functions
// (Filters/Spectral/Filtering/Transfer.h).
#include "Checks.h"
#include "Solver/EigenSolver.h"
#include "Meshes.h"
#include "Operators/Operators.h"
#include "Common/Eigenvalues.h"
#include "Common/Threads.h"
#include "Filtering/Transfer.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

using namespace spectral;
using namespace spectral::testing;

namespace
{
const double Pi = 3.14159265358979323846;

/// A basis in the row-major layout of the VTK point-data array, with its mass and spectrum.
struct Basis
{
  RowMatrix H; // n x m
  Vector Mass;
  Vector Lambda;
  TriangleMesh Mesh;

  BasisView View() const { return BasisView(this->H.data(), this->H.rows(), this->H.cols()); }
};

Basis MakeBasis(const TriangleMesh& mesh, int m)
{
  Basis b;
  b.Mesh = mesh;
  b.Mass = LumpedMass(mesh);
  EigenOptions options;
  options.NumberOfEigenpairs = m;
  const EigenResult r = SmallestEigenpairs(CotanStiffness(mesh), Diagonal(b.Mass), options);
  b.H = r.Eigenvectors;
  b.Lambda = r.Eigenvalues;
  return b;
}

ConstRowView View(const RowMatrix& A)
{
  return ConstRowView(A.data(), A.rows(), A.cols());
}

RowMatrix RandomSignals(Eigen::Index n, Eigen::Index c, unsigned seed)
{
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal;
  RowMatrix X(n, c);
  for (Eigen::Index i = 0; i < X.size(); ++i)
  {
    X.data()[i] = normal(generator);
  }
  return X;
}

double MaxAbs(const RowMatrix& A)
{
  return A.size() ? A.cwiseAbs().maxCoeff() : 0.0;
}

/// The empty signal: no re-injection.
const ConstRowView NoSignal(nullptr, 0, 0);

//------------------------------------------------------------------------------
void RoundTripFullBasis()
{
  // m = n: the dense path gives a complete basis, so the transform is invertible.
  const Basis b = MakeBasis(Icosphere(1), 42);
  const RowMatrix X = RandomSignals(42, 3, 1u);
  const RowMatrix coefficients = ForwardTransform(b.View(), b.Mass, View(X));
  Check(coefficients.rows() == 42 && coefficients.cols() == 3, "coefficients are m x c = 42 x 3");
  const RowMatrix Y = InverseTransform(
    b.View(), Vector::Ones(42), View(coefficients), NoSignal, 0.0);
  CheckBelow(MaxAbs(Y - X), 1e-10 * MaxAbs(X), "m = n: max |inverse(forward(X)) - X|");
  // Parseval: sum_k x~_k^2 = x^T D x per component.
  const double energy = (X.array().square().colwise() * b.Mass.array()).sum();
  CheckNear(coefficients.squaredNorm(), energy, 1e-10 * energy, "Parseval: |X~|^2 = X^T D X");
}

//------------------------------------------------------------------------------
void ReinjectionAndProjection()
{
  const int m = 30;
  const Basis b = MakeBasis(Icosphere(2), m);
  const Eigen::Index n = b.H.rows();
  const RowMatrix X = RandomSignals(n, 3, 2u);
  const RowMatrix coefficients = ForwardTransform(b.View(), b.Mass, View(X));
  const Vector ones = Vector::Ones(m);

  const RowMatrix same = InverseTransform(b.View(), ones, View(coefficients), View(X), 1.0);
  CheckBelow(MaxAbs(same - X), 1e-10 * MaxAbs(X), "m < n, gains 1, hfGain 1: max |Y - X|");

  // Gains 1 without re-injection: the D-orthogonal projection onto the span of H.
  const RowMatrix P = InverseTransform(b.View(), ones, View(coefficients), NoSignal, 0.0);
  const RowMatrix again = ForwardTransform(b.View(), b.Mass, View(P));
  CheckBelow(MaxAbs(again - coefficients), 1e-10 * MaxAbs(coefficients),
    "projection keeps the coefficients: max |forward(P X) - X~|");
  const RowMatrix rest = X - P;
  CheckBelow(MaxAbs(ForwardTransform(b.View(), b.Mass, View(rest))), 1e-10 * MaxAbs(X),
    "X - P X is D-orthogonal to every harmonic");

  // General gains and re-injection against the definition.
  const Vector gains = Vector::LinSpaced(m, 1.5, -0.5);
  const double hf = 0.37;
  const RowMatrix Y = InverseTransform(b.View(), gains, View(coefficients), View(X), hf);
  const RowMatrix expected =
    b.H * (gains.asDiagonal() * coefficients) + hf * (X - b.H * coefficients);
  CheckBelow(MaxAbs(Y - expected), 1e-12 * MaxAbs(expected),
    "Y = sum g_k x~_k H^k + hf (X - sum x~_k H^k)");
}

//------------------------------------------------------------------------------
void Linearity()
{
  const int m = 40;
  const Basis b = MakeBasis(Icosphere(2), m);
  const Eigen::Index n = b.H.rows();
  const RowMatrix X = RandomSignals(n, 2, 3u);
  const RowMatrix Z = RandomSignals(n, 2, 4u);
  const double alpha = 2.5;
  const double beta = -0.75;
  const RowMatrix mix = alpha * X + beta * Z;
  FilterParameters p;
  p.Kind = FilterKind::Enhancement;
  p.Cutoff = 3.0;
  p.Gain = 3.0;
  const Vector gains = Gains(p, b.Lambda);
  const double hf = 3.0;
  auto filter = [&b, &gains, hf](const RowMatrix& S) {
    const RowMatrix C = ForwardTransform(b.View(), b.Mass, View(S));
    return RowMatrix(InverseTransform(b.View(), gains, View(C), View(S), hf));
  };
  const RowMatrix left = filter(mix);
  const RowMatrix right = alpha * filter(X) + beta * filter(Z);
  CheckBelow(
    MaxAbs(left - right), 1e-12 * MaxAbs(right), "filter(a X + b Z) = a filter(X) + b filter(Z)");
  const RowMatrix Cmix = ForwardTransform(b.View(), b.Mass, View(mix));
  const RowMatrix Csum = alpha * ForwardTransform(b.View(), b.Mass, View(X)) +
    beta * ForwardTransform(b.View(), b.Mass, View(Z));
  CheckBelow(MaxAbs(Cmix - Csum), 1e-12 * MaxAbs(Csum), "forward transform is linear");
}

/// Largest |F(w + h) - F(w)| / h over a fine grid of [lo, hi].
double MaxSlope(const FilterParameters& p, double lo, double hi)
{
  const int steps = 20000;
  const double h = (hi - lo) / steps;
  double out = 0.0;
  for (int i = 0; i < steps; ++i)
  {
    const double w = lo + i * h;
    out = std::max(out, std::abs(Gain(p, w + h) - Gain(p, w)) / h);
  }
  return out;
}

//------------------------------------------------------------------------------
void StepShapes()
{
  FilterParameters p;
  p.Cutoff = 2.0;
  p.Transition = 0.0;
  p.Kind = FilterKind::LowPass;
  Check(Gain(p, 0.0) == 1.0 && Gain(p, 2.0) == 1.0 && Gain(p, 2.0 + 1e-12) == 0.0 &&
      Gain(p, 50.0) == 0.0,
    "sharp low pass: 1 up to and at the cutoff, 0 above");
  p.Kind = FilterKind::HighPass;
  Check(Gain(p, 0.0) == 0.0 && Gain(p, 2.0) == 0.0 && Gain(p, 2.0 + 1e-12) == 1.0,
    "sharp high pass: 0 up to and at the cutoff, 1 above");

  p.Transition = 0.2; // raised cosine over [1.8, 2.2]
  p.Kind = FilterKind::LowPass;
  Check(Gain(p, 0.0) == 1.0 && Gain(p, 1.8) == 1.0 && Gain(p, 2.2) == 0.0 && Gain(p, 9.0) == 0.0,
    "smooth low pass: 1 below 1.8, 0 above 2.2");
  CheckNear(Gain(p, 2.0), 0.5, 1e-14, "smooth low pass: halfway at the cutoff");
  CheckNear(Gain(p, 1.9) + Gain(p, 2.1), 1.0, 1e-14, "smooth low pass: symmetric about the cutoff");
  const double slope = MaxSlope(p, 1.5, 2.5);
  CheckNear(slope, Pi / (2.0 * 0.4), 1e-3 * Pi / 0.8,
    "smooth low pass: continuous, largest slope pi / (2 width)");
  const double h = 1e-6;
  const double endSlope =
    std::max(std::abs(Gain(p, 1.8 + h) - Gain(p, 1.8)), std::abs(Gain(p, 2.2) - Gain(p, 2.2 - h)));
  CheckBelow(endSlope / h, 1e-4, "smooth low pass: zero slope at the transition's ends (C^1)");
  bool monotone = true;
  for (double w = 1.7; w < 2.3; w += 1e-3)
  {
    monotone = monotone && Gain(p, w + 1e-3) <= Gain(p, w);
  }
  Check(monotone, "smooth low pass: non-increasing");
  FilterParameters high = p;
  high.Kind = FilterKind::HighPass;
  double complement = 0.0;
  for (double w = 0.0; w < 4.0; w += 0.01)
  {
    complement = std::max(complement, std::abs(Gain(p, w) + Gain(high, w) - 1.0));
  }
  CheckBelow(complement, 1e-14, "high pass = 1 - low pass");

  p.Kind = FilterKind::Enhancement;
  p.Gain = 3.0;
  Check(Gain(p, 0.0) == 1.0 && Gain(p, 1.8) == 1.0 && Gain(p, 2.2) == 3.0 && Gain(p, 100.0) == 3.0,
    "enhancement: 1 below the transition, Gain above");
  CheckNear(Gain(p, 2.0), 2.0, 1e-14, "enhancement: (1 + Gain) / 2 at the cutoff");
}

//------------------------------------------------------------------------------
void BandShapes()
{
  FilterParameters p;
  p.Cutoff = 2.0;
  p.UpperCutoff = 6.0;
  p.Transition = 0.1; // [1.9, 2.1] and [5.7, 6.3]
  p.Kind = FilterKind::BandPass;
  Check(Gain(p, 0.0) == 0.0 && Gain(p, 1.9) == 0.0 && Gain(p, 2.1) == 1.0 && Gain(p, 4.0) == 1.0 &&
      Gain(p, 5.7) == 1.0 && Gain(p, 6.3) == 0.0 && Gain(p, 20.0) == 0.0,
    "band pass: 0 outside, 1 inside the band");
  CheckNear(Gain(p, 2.0), 0.5, 1e-14, "band pass: halfway at the lower edge");
  CheckNear(Gain(p, 6.0), 0.5, 1e-14, "band pass: halfway at the upper edge");
  const double slope = MaxSlope(p, 0.0, 8.0);
  CheckBelow(slope, (1.0 + 1e-3) * Pi / (2.0 * 0.2), "band pass: continuous (largest slope)");

  FilterParameters stop = p;
  stop.Kind = FilterKind::BandStop;
  FilterParameters exaggerate = p;
  exaggerate.Kind = FilterKind::BandExaggeration;
  exaggerate.Gain = 4.0;
  double worstStop = 0.0;
  double worstExaggeration = 0.0;
  for (double w = 0.0; w < 10.0; w += 0.01)
  {
    worstStop = std::max(worstStop, std::abs(Gain(stop, w) - (1.0 - Gain(p, w))));
    worstExaggeration =
      std::max(worstExaggeration, std::abs(Gain(exaggerate, w) - (1.0 + 3.0 * Gain(p, w))));
  }
  CheckBelow(worstStop, 1e-14, "band stop = 1 - band pass");
  CheckBelow(worstExaggeration, 1e-14, "band exaggeration = 1 + (Gain - 1) band pass");
  Check(
    Gain(exaggerate, 4.0) == 4.0 && Gain(exaggerate, 0.5) == 1.0 && Gain(exaggerate, 9.0) == 1.0,
    "band exaggeration: Gain inside, 1 outside");

  // Sharp edges: omega = cutoff counts as below each cutoff, so the band is (Cutoff, UpperCutoff].
  p.Transition = 0.0;
  Check(Gain(p, 2.0) == 0.0 && Gain(p, 2.0 + 1e-12) == 1.0 && Gain(p, 6.0) == 1.0 &&
      Gain(p, 6.0 + 1e-12) == 0.0,
    "sharp band pass: (Cutoff, UpperCutoff]");
}

//------------------------------------------------------------------------------
void HeatAndCustomShapes()
{
  FilterParameters heat;
  heat.Kind = FilterKind::HeatDiffusion;
  heat.Time = 0.03;
  const Vector lambda = (Vector(5) << -1e-14, 0.0, 2.0, 6.0, 110.0).finished();
  const Vector g = Gains(heat, lambda);
  double worst = 0.0;
  for (Eigen::Index k = 1; k < lambda.size(); ++k)
  {
    worst = std::max(worst, std::abs(g[k] - std::exp(-0.03 * lambda[k])));
  }
  CheckBelow(worst, 1e-14, "heat diffusion: gains = exp(-t lambda)");
  Check(g[0] == 1.0, "heat diffusion: a slightly negative eigenvalue counts as omega = 0");
  CheckNear(Gain(heat, 3.0), std::exp(-0.27), 1e-15, "heat diffusion: F(omega) = exp(-t omega^2)");

  FilterParameters custom;
  custom.Kind = FilterKind::Custom;
  custom.ControlPoints = { { 1.0, 2.0 }, { 3.0, 0.0 }, { 4.0, 1.0 } };
  Check(Gain(custom, 0.0) == 2.0 && Gain(custom, 1.0) == 2.0 && Gain(custom, 3.0) == 0.0 &&
      Gain(custom, 4.0) == 1.0 && Gain(custom, 50.0) == 1.0,
    "custom: control values, constant beyond the ends");
  CheckNear(Gain(custom, 2.5), 0.5, 1e-14, "custom: linear between control points");
  CheckNear(Gain(custom, 3.25), 0.25, 1e-14, "custom: linear on the last segment");
  custom.ControlPoints = { { 2.0, 0.7 } };
  Check(Gain(custom, 0.0) == 0.7 && Gain(custom, 9.0) == 0.7, "custom: one point is a constant");
}

//------------------------------------------------------------------------------
void InvalidParameters()
{
  auto throwsFor = [](FilterParameters p, double omega, const std::string& what) {
    CheckThrows<InvalidInput>([&p, omega]() { Gain(p, omega); }, what);
  };
  FilterParameters p;
  p.Cutoff = -1.0;
  throwsFor(p, 1.0, "negative cutoff");
  p = FilterParameters();
  p.Transition = -0.1;
  throwsFor(p, 1.0, "negative transition");
  p = FilterParameters();
  p.Kind = FilterKind::BandPass;
  p.Cutoff = 3.0;
  p.UpperCutoff = 2.0;
  throwsFor(p, 1.0, "band pass with UpperCutoff < Cutoff");
  p.Kind = FilterKind::LowPass;
  Check(Gain(p, 1.0) == 1.0, "low pass ignores UpperCutoff");
  p = FilterParameters();
  p.Kind = FilterKind::HeatDiffusion;
  p.Time = -1.0;
  throwsFor(p, 1.0, "negative diffusion time");
  p = FilterParameters();
  p.Kind = FilterKind::Custom;
  throwsFor(p, 1.0, "custom without control points");
  p.ControlPoints = { { 1.0, 1.0 }, { 1.0, 2.0 } };
  throwsFor(p, 1.0, "custom with a repeated omega");
  p.ControlPoints = { { 2.0, 1.0 }, { 1.0, 2.0 } };
  throwsFor(p, 1.0, "custom with decreasing omega");
  p = FilterParameters();
  p.Kind = static_cast<FilterKind>(42);
  throwsFor(p, 1.0, "unknown kind");
  p = FilterParameters();
  throwsFor(p, -1.0, "negative omega");
  throwsFor(p, std::numeric_limits<double>::quiet_NaN(), "NaN omega");
  CheckThrows<InvalidInput>(
    [&p]() { Gains(p, Vector::Constant(3, std::numeric_limits<double>::quiet_NaN())); },
    "NaN eigenvalue");
}

/// Mean of F over [a, b] by the composite trapezoid rule on a fine grid.
double TrapezoidMean(const FilterParameters& p, double a, double b)
{
  const int steps = 200000;
  const double h = (b - a) / steps;
  double sum = 0.5 * (Gain(p, a) + Gain(p, b));
  for (int i = 1; i < steps; ++i)
  {
    sum += Gain(p, a + i * h);
  }
  return sum * h / (b - a);
}

//------------------------------------------------------------------------------
void MeanGains()
{
  FilterParameters constant;
  constant.Kind = FilterKind::Custom;
  constant.ControlPoints = { { 3.0, 0.7 } };
  CheckNear(MeanGain(constant, 1.0, 5.0), 0.7, 1e-14, "mean of a constant custom filter");
  constant.Kind = FilterKind::Enhancement;
  constant.Gain = 1.0;
  CheckNear(MeanGain(constant, 0.5, 40.0), 1.0, 1e-14, "mean of enhancement with Gain 1");
  constant.Kind = FilterKind::HeatDiffusion;
  constant.Time = 0.0;
  CheckNear(MeanGain(constant, 0.0, 40.0), 1.0, 0.0, "mean of heat diffusion at t = 0");

  FilterParameters low;
  low.Cutoff = 2.0;
  for (double w : { 0.0, 0.3, 1.0 })
  {
    low.Transition = w;
    CheckNear(MeanGain(low, 0.0, 4.0), 0.5, 1e-14,
      "low pass over [0, 2 cutoff], transition " + std::to_string(w) + ": 1/2 by symmetry");
  }
  low.Transition = 0.3;
  CheckNear(MeanGain(low, 2.5, 4.0), 0.0, 1e-14, "low pass above its transition: 0");
  CheckNear(MeanGain(low, 3.0, 3.0), Gain(low, 3.0), 0.0, "empty interval: F(omegaLow)");
  CheckNear(MeanGain(low, 1.0, 0.5), Gain(low, 1.0), 0.0, "reversed interval: F(omegaLow)");

  FilterParameters heat;
  heat.Kind = FilterKind::HeatDiffusion;
  heat.Time = 0.02;
  CheckNear(MeanGain(heat, 3.0, 25.0), TrapezoidMean(heat, 3.0, 25.0), 1e-9,
    "heat diffusion mean (erfc) vs trapezoid rule");
  heat.Time = 1e4;
  CheckBelow(MeanGain(heat, 10.0, 30.0), 1e-300, "heat diffusion mean, large t: 0, no NaN");

  FilterParameters band;
  band.Kind = FilterKind::BandExaggeration;
  band.Cutoff = 2.0;
  band.UpperCutoff = 3.0;
  band.Transition = 0.5;
  band.Gain = 5.0;
  CheckNear(MeanGain(band, 0.5, 7.0), TrapezoidMean(band, 0.5, 7.0), 1e-9,
    "band exaggeration with overlapping transitions: quadrature vs trapezoid rule");
  FilterParameters custom;
  custom.Kind = FilterKind::Custom;
  custom.ControlPoints = { { 1.0, 2.0 }, { 3.0, 0.0 }, { 4.0, 1.0 } };
  // Integral over [0, 5]: 2 + 2 + 0.5 + 1 = 5.5.
  CheckNear(MeanGain(custom, 0.0, 5.0), 5.5 / 5.0, 1e-14, "custom piecewise linear mean");
}

//------------------------------------------------------------------------------
void HeatDiffusionLimits()
{
  // A complete basis (m = n) so that t -> 0 must give back the signal itself.
  const Basis b = MakeBasis(Icosphere(2), 162);
  const Eigen::Index n = b.H.rows();
  RowMatrix X = RandomSignals(n, 3, 5u);
  X.col(2) = b.Mesh.Vertices.col(2) + Vector::Constant(n, 4.0); // a smooth signal too
  const RowMatrix coefficients = ForwardTransform(b.View(), b.Mass, View(X));
  FilterParameters heat;
  heat.Kind = FilterKind::HeatDiffusion;

  heat.Time = 100.0;
  const RowMatrix Y =
    InverseTransform(b.View(), Gains(heat, b.Lambda), View(coefficients), NoSignal, 0.0);
  double worst = 0.0;
  for (Eigen::Index c = 0; c < 3; ++c)
  {
    const double mean = X.col(c).dot(b.Mass) / b.Mass.sum();
    worst = std::max(worst, (Y.col(c).array() - mean).abs().maxCoeff());
  }
  CheckBelow(worst, 1e-10 * MaxAbs(X), "t = 100: every signal becomes its mass-weighted mean");

  heat.Time = 0.0;
  const RowMatrix same =
    InverseTransform(b.View(), Gains(heat, b.Lambda), View(coefficients), NoSignal, 0.0);
  CheckBelow(MaxAbs(same - X), 1e-10 * MaxAbs(X), "t = 0: identity");
  heat.Time = 1e-13;
  const RowMatrix close =
    InverseTransform(b.View(), Gains(heat, b.Lambda), View(coefficients), NoSignal, 0.0);
  CheckBelow(MaxAbs(close - X), 1e-9 * MaxAbs(X), "t = 1e-13: identity to 1e-9");

  // With an incomplete basis, the heat kernel's high-frequency gain goes to 0 as t grows.
  const Basis partial = MakeBasis(Icosphere(3), 30);
  heat.Time = 100.0;
  const double omegaM = std::sqrt(partial.Lambda[29]);
  CheckBelow(MeanGain(heat, omegaM, NyquistFrequency(partial.Mesh)), 1e-12,
    "t = 100: high-frequency gain above omega_m");
}

//------------------------------------------------------------------------------
void Nyquist()
{
  const double h = (0.1 + 0.1 + std::sqrt(0.02)) / 3.0;
  CheckNear(NyquistFrequency(Rectangle(2.0, 1.0, 20, 10)), Pi / h, 1e-12,
    "Nyquist frequency of a 2 x 1 grid of 20 x 10 cells: pi / mean edge");
  CheckThrows<InvalidInput>([]() { NyquistFrequency(TriangleMesh()); }, "mesh without triangles");

  // From edge sums added up over pieces (the distributed filter): the two halves of the grid's
  // triangles, each summing its own edges, give the frequency of the whole.
  const TriangleMesh grid = Rectangle(2.0, 1.0, 20, 10);
  double sums[2][2] = { { 0.0, 0.0 }, { 0.0, 0.0 } };
  for (Eigen::Index f = 0; f < grid.Faces.rows(); ++f)
  {
    double (&piece)[2] = sums[2 * f < grid.Faces.rows() ? 0 : 1];
    for (int c = 0; c < 3; ++c)
    {
      piece[0] += (grid.Vertices.row(grid.Faces(f, (c + 1) % 3)) -
        grid.Vertices.row(grid.Faces(f, c))).norm();
      piece[1] += 1.0;
    }
  }
  CheckNear(NyquistFrequency(sums[0][0] + sums[1][0], sums[0][1] + sums[1][1]), Pi / h, 1e-12,
    "Nyquist frequency from the edge sums of two pieces");
  Check(NyquistFrequency(0.0, 0.0) == 0.0, "no edge: Nyquist frequency 0, not a division by 0");
  Check(NyquistFrequency(0.0, 6.0) == 0.0, "edges of zero length: Nyquist frequency 0");
  Check(NyquistFrequency(std::numeric_limits<double>::infinity(), 6.0) == 0.0,
    "infinite edge lengths: Nyquist frequency 0");
}

//------------------------------------------------------------------------------
// The zero-eigenvalue rule (Common/Eigenvalues.h) on a computed spectrum with the mesh's scale
// omega_N^2: the constant harmonic's eigenvalue (round-off) is zero, lambda_1 = 2 of the unit
// sphere is not, whichever of the top of the spectrum or omega_N^2 is the scale.
void ZeroEigenvalues()
{
  const Basis b = MakeBasis(Icosphere(3), 10);
  const double nyquist = NyquistFrequency(b.Mesh);
  const double scale = nyquist * nyquist;
  Check(IsZeroEigenvalue(b.Lambda[0], scale), "lambda_0 of a sphere is a zero eigenvalue");
  Check(IsZeroEigenvalue(-std::abs(b.Lambda[0]), scale), "negative round-off is zero");
  CheckNear(b.Lambda[1], 2.0, 0.05, "lambda_1 of the unit sphere is about l(l+1) = 2");
  Check(!IsZeroEigenvalue(b.Lambda[1], scale), "lambda_1 of a sphere is not zero");
  Check(!IsZeroEigenvalue(b.Lambda[1], 1e6 * scale), "lambda_1 not zero even for 1e6 omega_N^2");
  Check(!IsZeroEigenvalue(1e-300, 0.0), "scale 0: a positive eigenvalue is not zero");
  Check(!IsZeroEigenvalue(std::numeric_limits<double>::quiet_NaN(), scale), "NaN is not zero");
}

//------------------------------------------------------------------------------
void InvalidSizes()
{
  const Basis b = MakeBasis(Icosphere(1), 10);
  const RowMatrix X = RandomSignals(42, 3, 6u);
  const RowMatrix shortX = RandomSignals(41, 3, 7u);
  const RowMatrix C = ForwardTransform(b.View(), b.Mass, View(X));
  const BasisView H = b.View();
  const Vector& mass = b.Mass;
  CheckThrows<InvalidInput>([&H, &mass, &shortX]() { ForwardTransform(H, mass, View(shortX)); },
    "forward: signal with n - 1 rows");
  CheckThrows<InvalidInput>([&H, &mass, &X]() { ForwardTransform(H, mass.head(41), View(X)); },
    "forward: mass of length n - 1");
  CheckThrows<InvalidInput>(
    [&H, &C, &X]() { InverseTransform(H, Vector::Ones(9), View(C), View(X), 0.0); },
    "inverse: m - 1 gains");
  CheckThrows<InvalidInput>(
    [&H, &C]() { InverseTransform(H, Vector::Ones(10), View(C), NoSignal, 0.5); },
    "inverse: re-injection without the signal");
  CheckThrows<InvalidInput>(
    [&H, &C, &shortX]() { InverseTransform(H, Vector::Ones(10), View(C), View(shortX), 0.5); },
    "inverse: signal with n - 1 rows");
  const RowMatrix Y = InverseTransform(b.View(), Vector::Ones(10), View(C), NoSignal, 0.0);
  Check(Y.rows() == 42 && Y.cols() == 3, "inverse without re-injection: n x c result");
}

//------------------------------------------------------------------------------
void FloatBasisMatchesDouble()
{
  // The basis of BasisPrecision Float: the same harmonics rounded to float. Transform and
  // filter accumulate in double, so the results differ by the rounding of the basis only.
  const int m = 60;
  const Basis b = MakeBasis(Icosphere(3), m);
  const Eigen::Index n = b.H.rows();
  const FloatRowMatrix Hf = b.H.cast<float>();
  const FloatBasisView floats(Hf.data(), n, m);
  RowMatrix X = RandomSignals(n, 3, 8u);
  X.col(0) = b.Mesh.Vertices.col(0);
  const RowMatrix C = ForwardTransform(b.View(), b.Mass, View(X));
  const RowMatrix Cf = ForwardTransform(floats, b.Mass, View(X));
  CheckBelow(MaxAbs(Cf - C) / MaxAbs(C), 1e-5, "float basis: forward transform, relative");

  FilterParameters p;
  p.Cutoff = 0.5 * std::sqrt(b.Lambda[m - 1]);
  const Vector gains = Gains(p, b.Lambda);
  const double hf = 0.25;
  const RowMatrix Y = InverseTransform(b.View(), gains, View(C), View(X), hf);
  const RowMatrix Yf = InverseTransform(floats, gains, View(Cf), View(X), hf);
  CheckBelow(MaxAbs(Yf - Y) / MaxAbs(Y), 1e-5, "float basis: inverse transform, relative");
  const RowMatrix F = FilterSignal(b.View(), b.Mass, gains, View(C), View(X), hf);
  const RowMatrix Ff = FilterSignal(floats, b.Mass, gains, View(Cf), View(X), hf);
  CheckBelow(MaxAbs(Ff - F) / MaxAbs(F), 1e-5, "float basis: filter stage, relative");
  CheckBelow(MaxAbs(F - Y), 0.0, "filter stage = inverse transform on a closed surface");
}

//------------------------------------------------------------------------------
void ThreadsMatchOneThread()
{
  // Row ranges: every row exactly once, uneven splits, exceptions carried to the caller.
  for (int parts : { 1, 2, 3, 7 })
  {
    std::vector<std::atomic<int>> seen(10);
    ForEachRowRange(10, parts, [&seen](int, Eigen::Index first, Eigen::Index count) {
      for (Eigen::Index i = first; i < first + count; ++i)
      {
        ++seen[static_cast<std::size_t>(i)];
      }
    });
    bool once = true;
    for (const auto& count : seen)
    {
      once = once && count == 1;
    }
    Check(once, std::to_string(parts) + " ranges of 10 rows: each row once");
  }
  CheckThrows<std::runtime_error>(
    []() {
      ForEachRowRange(100, 2, [](int part, Eigen::Index, Eigen::Index) {
        if (part == 1)
        {
          throw std::runtime_error("range 1 failed");
        }
      });
    },
    "an exception on a helper thread reaches the caller");
  // The helper threads kept between calls (RunOnHelpers): calls in a row with more and fewer
  // ranges, calls from within a range (nested) and from several threads at once must each
  // cover their rows exactly once and return only when every range has finished.
  const auto coverage = [](Eigen::Index n,
                          int parts,
                          std::vector<std::atomic<int>>& seen,
                          std::size_t offset,
                          bool nested)
  {
    ForEachRowRange(n,
      parts,
      [&seen, offset, nested](int part, Eigen::Index first, Eigen::Index count)
      {
        if (nested && count > 0)
        {
          // Each range splits itself again, into part + 1 ranges.
          ForEachRowRange(count,
            part + 1,
            [&seen, offset, first](int, Eigen::Index innerFirst, Eigen::Index innerCount)
            {
              for (Eigen::Index i = innerFirst; i < innerFirst + innerCount; ++i)
              {
                ++seen[offset + static_cast<std::size_t>(first + i)];
              }
            });
          return;
        }
        for (Eigen::Index i = first; i < first + count; ++i)
        {
          ++seen[offset + static_cast<std::size_t>(i)];
        }
      });
  };
  const auto exactlyOnce = [](const std::vector<std::atomic<int>>& seen, int times)
  {
    for (const auto& count : seen)
    {
      if (count != times)
      {
        return false;
      }
    }
    return true;
  };
  {
    std::vector<std::atomic<int>> seen(1000);
    for (int call = 0; call < 200; ++call)
    {
      coverage(1000, 1 + call % 8, seen, 0, call % 3 == 0);
    }
    Check(exactlyOnce(seen, 200),
      "200 calls in a row, 1 to 8 ranges, some nested: each row once a call");
  }
  {
    // Four threads, each with its own rows, calling at the same time.
    std::vector<std::atomic<int>> seen(4 * 500);
    std::vector<std::thread> callers;
    for (int caller = 0; caller < 4; ++caller)
    {
      callers.emplace_back(
        [&coverage, &seen, caller]()
        {
          for (int call = 0; call < 100; ++call)
          {
            coverage(500,
              2 + (call + caller) % 4,
              seen,
              static_cast<std::size_t>(caller) * 500,
              call % 5 == 0);
          }
        });
    }
    for (std::thread& caller : callers)
    {
      caller.join();
    }
    Check(
      exactlyOnce(seen, 100), "4 threads calling at once, 100 calls each: each row once a call");
  }
  CheckThrows<std::runtime_error>(
    []()
    {
      ForEachRowRange(100,
        3,
        [](int part, Eigen::Index, Eigen::Index)
        {
          if (part == 2)
          {
            throw std::runtime_error("range 2 failed");
          }
        });
    },
    "an exception on a kept helper thread reaches the caller");
  {
    std::vector<std::atomic<int>> seen(10);
    coverage(10, 3, seen, 0, false);
    Check(exactlyOnce(seen, 1), "the helpers work again after an exception");
  }
  {
    // A child of fork() (a Python multiprocessing worker, say) has none of the parent's helper
    // threads: its calls start their own, and it exits without waiting for the parent's.
    const pid_t child = fork();
    if (child == 0)
    {
      std::vector<std::atomic<int>> seen(1000);
      for (int call = 0; call < 20; ++call)
      {
        coverage(1000, 2 + call % 3, seen, 0, call % 4 == 0);
      }
      std::exit(exactlyOnce(seen, 20) ? 0 : 1); // static destructors run: the helpers' too
    }
    int status = -1;
    bool ended = false;
    for (int wait = 0; wait < 1200 && !ended; ++wait)
    {
      ended = child > 0 && waitpid(child, &status, WNOHANG) == child;
      if (!ended)
      {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
    }
    if (!ended && child > 0)
    {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
    }
    Check(ended && WIFEXITED(status) && WEXITSTATUS(status) == 0,
      "a forked child: its calls cover their rows, and it exits within a minute");
  }
  Check(TransformThreads(100, 10) == 1, "automatic: 1 thread for a small product");
  Check(TransformThreads(5, 1000, 8) == 5, "at most one thread a row");
  Check(TransformThreads(100000, 4, 8) == 8, "8 threads asked: 8");
  Check(TransformThreads(Eigen::Index(1) << 20, 1 << 10) == ResolveThreads(0),
    "automatic for a large product: every core (" + std::to_string(ResolveThreads(0)) + ")");

  // Transforms on 1, 2, 3, 4, 7 and 8 threads (random basis, n not a multiple of the blocks;
  // 4 and more oversubscribe a small machine, which is the point: correctness, not speed).
  const Eigen::Index n = 10007;
  const Eigen::Index m = 37;
  const RowMatrix H = RandomSignals(n, m, 9u);
  const FloatRowMatrix Hf = H.cast<float>();
  const BasisView doubles(H.data(), n, m);
  const FloatBasisView floats(Hf.data(), n, m);
  const Vector mass = RandomSignals(n, 1, 10u).cwiseAbs();
  const RowMatrix X = RandomSignals(n, 3, 11u);
  const Vector gains = Vector::LinSpaced(m, 1.0, 0.0);
  const RowMatrix C1 = ForwardTransform(doubles, mass, View(X), 1);
  const RowMatrix Y1 = InverseTransform(doubles, gains, View(C1), View(X), 0.5, 1);
  const RowMatrix C1f = ForwardTransform(floats, mass, View(X), 1);
  const RowMatrix Y1f = InverseTransform(floats, gains, View(C1f), View(X), 0.5, 1);
  for (int threads : { 0, 2, 3, 4, 7, 8 })
  {
    const std::string on = " on " + std::to_string(threads) + " threads";
    const RowMatrix C = ForwardTransform(doubles, mass, View(X), threads);
    CheckBelow(MaxAbs(C - C1) / MaxAbs(C1), 1e-13, "forward" + on + " vs 1");
    CheckBelow(MaxAbs(InverseTransform(doubles, gains, View(C1), View(X), 0.5, threads) - Y1) /
        MaxAbs(Y1),
      1e-13, "inverse" + on + " vs 1");
    const RowMatrix Cf = ForwardTransform(floats, mass, View(X), threads);
    CheckBelow(MaxAbs(Cf - C1f) / MaxAbs(C1f), 1e-13, "float forward" + on + " vs 1");
    CheckBelow(MaxAbs(InverseTransform(floats, gains, View(C1f), View(X), 0.5, threads) - Y1f) /
        MaxAbs(Y1f),
      1e-13, "float inverse" + on + " vs 1");
  }
}

//------------------------------------------------------------------------------
/// A random n x m "basis" with unit masses, except zero at the rows `outside` (points no
/// triangle uses): the transform and filter stage do not care whether H is orthonormal.
struct OutsideFixture
{
  RowMatrix H;
  Vector Mass;

  OutsideFixture(Eigen::Index n, Eigen::Index m, unsigned seed, std::initializer_list<int> outside)
    : H(RandomSignals(n, m, seed))
    , Mass(Vector::Ones(n))
  {
    for (const int i : outside)
    {
      this->Mass[i] = 0.0;
    }
  }
  BasisView View() const { return BasisView(this->H.data(), this->H.rows(), this->H.cols()); }
};

/// max |A_i - B_i| over the rows i of zero mass (outside) or of non-zero mass (inside).
double MaxRowDifference(const RowMatrix& A, const RowMatrix& B, const Vector& mass, bool outside)
{
  double worst = 0.0;
  for (Eigen::Index i = 0; i < A.rows(); ++i)
  {
    if ((mass[i] == 0.0) == outside)
    {
      worst = std::max(worst, (A.row(i) - B.row(i)).cwiseAbs().maxCoeff());
    }
  }
  return worst;
}

//------------------------------------------------------------------------------
void FilterSignalKeepsOutsidePoints()
{
  const Eigen::Index n = 50;
  const Eigen::Index m = 5;
  const OutsideFixture f(n, m, 12u, { 3, 17 });
  const BasisView view = f.View();
  const RowMatrix X = RandomSignals(n, 2, 13u);
  const RowMatrix C = ForwardTransform(view, f.Mass, View(X));
  const Vector gains = Vector::Constant(m, 0.5);
  const RowMatrix Y = InverseTransform(view, gains, View(C), View(X), 0.2);
  const RowMatrix F = FilterSignal(view, f.Mass, gains, View(C), View(X), 0.2);
  CheckBelow(MaxRowDifference(F, Y, f.Mass, false), 0.0,
    "points of the surface: the inverse transform");
  CheckBelow(MaxRowDifference(F, X, f.Mass, true), 0.0,
    "points of zero mass keep their input value");
  CheckThrows<InvalidInput>(
    [&view, &gains, &C]() { FilterSignal(view, Vector::Ones(n), gains, View(C), NoSignal, 0.0); },
    "filter stage without the signal");
}

//------------------------------------------------------------------------------
void OutsidePointsMayHoldNaN()
{
  // Points used by no triangle have zero mass: whatever they hold (NaN coordinates of an
  // unused point) must not reach the coefficients, nor the filtered surface.
  const Eigen::Index n = 40;
  const Eigen::Index m = 4;
  const OutsideFixture f(n, m, 14u, { 5, 30 });
  const BasisView view = f.View();
  const RowMatrix X = RandomSignals(n, 3, 15u);
  RowMatrix bad = X;
  bad.row(5).setConstant(std::numeric_limits<double>::quiet_NaN());
  bad(30, 1) = std::numeric_limits<double>::infinity();
  for (const int threads : { 1, 2 })
  {
    const RowMatrix C = ForwardTransform(view, f.Mass, View(X), threads);
    const RowMatrix D = ForwardTransform(view, f.Mass, View(bad), threads);
    Check(D.allFinite(), "coefficients finite with NaN and infinity at points of zero mass");
    CheckBelow(MaxAbs(D - C), 0.0, "coefficients independent of the values at zero mass");
    const Vector gains = Vector::Constant(m, 0.5);
    const RowMatrix F = FilterSignal(view, f.Mass, gains, View(D), View(bad), 0.2, threads);
    const RowMatrix G = FilterSignal(view, f.Mass, gains, View(C), View(X), 0.2, threads);
    CheckBelow(MaxRowDifference(F, G, f.Mass, false), 0.0, "filtered surface points unaffected");
  }
}

//------------------------------------------------------------------------------
// Relative units name absolute frequencies: a fraction of omega_max, the frequency of a harmonic
// (linear between two, omega_max beyond the last), a time in units of 1 / lambda_1; negative
// values are refused in the units they are given in.
void RelativeUnits()
{
  Vector lambda(5);
  lambda << -1e-14, 4.0, 9.0, 9.0, 25.0;
  const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-15 * std::abs(b); };
  Check(HighestFrequency(lambda) == 5.0 && HighestFrequency(Vector()) == 0.0, "highest frequency");
  Check(HarmonicFrequency(lambda, 0.0) == 0.0, "harmonic 0: negative round-off is frequency 0");
  Check(HarmonicFrequency(lambda, 1.0) == 2.0 && near(HarmonicFrequency(lambda, 1.5), 2.5),
    "harmonic 1 and 1.5");
  Check(HarmonicFrequency(lambda, 7.0) == 5.0, "an index beyond the last is the last");
  CheckThrows<InvalidInput>([&lambda]() { HarmonicFrequency(lambda, -1.0); }, "negative index");
  FilterParameters p;
  p.Kind = FilterKind::BandPass;
  p.Cutoff = 0.2;
  p.UpperCutoff = 0.8;
  p.Time = 2.0;
  p.ControlPoints = { { 0.0, 1.0 }, { 1.0, 0.0 } };
  const FilterParameters f = ToAbsoluteUnits(p, FrequencyUnits::FractionOfHighest, lambda, 4.0);
  Check(near(f.Cutoff, 1.0) && near(f.UpperCutoff, 4.0) && f.Time == 0.5 &&
      f.ControlPoints[1].first == 5.0 && f.ControlPoints[1].second == 0.0,
    "fractions of the highest frequency, time in units of 1 / lambda_1");
  p.Cutoff = 1.0;
  p.UpperCutoff = 2.5;
  const FilterParameters h = ToAbsoluteUnits(p, FrequencyUnits::HarmonicIndex, lambda, 4.0);
  Check(h.Cutoff == 2.0 && h.UpperCutoff == 3.0 && h.Time == 0.5, "harmonic indices");
  const FilterParameters a = ToAbsoluteUnits(p, FrequencyUnits::Absolute, lambda, 4.0);
  Check(a.Cutoff == 1.0 && a.UpperCutoff == 2.5 && a.Time == 2.0, "absolute units unchanged");
  Check(ToAbsoluteUnits(p, FrequencyUnits::FractionOfHighest, lambda, 0.0).Time == 0.0,
    "no non-constant harmonic: a relative time is 0");
  p.Cutoff = -0.1;
  for (FrequencyUnits units : { FrequencyUnits::Absolute, FrequencyUnits::FractionOfHighest,
         FrequencyUnits::HarmonicIndex })
  {
    CheckThrows<InvalidInput>([&p, units, &lambda]() { ToAbsoluteUnits(p, units, lambda, 4.0); },
      "negative cutoff in units " + std::to_string(static_cast<int>(units)));
  }
}

const Case Cases[] = {
  { "RoundTripFullBasis", RoundTripFullBasis },
  { "ReinjectionAndProjection", ReinjectionAndProjection },
  { "Linearity", Linearity },
  { "StepShapes", StepShapes },
  { "BandShapes", BandShapes },
  { "HeatAndCustomShapes", HeatAndCustomShapes },
  { "InvalidParameters", InvalidParameters },
  { "MeanGains", MeanGains },
  { "HeatDiffusionLimits", HeatDiffusionLimits },
  { "Nyquist", Nyquist },
  { "ZeroEigenvalues", ZeroEigenvalues },
  { "InvalidSizes", InvalidSizes },
  { "FloatBasisMatchesDouble", FloatBasisMatchesDouble },
  { "ThreadsMatchOneThread", ThreadsMatchOneThread },
  { "FilterSignalKeepsOutsidePoints", FilterSignalKeepsOutsidePoints },
  { "OutsidePointsMayHoldNaN", OutsidePointsMayHoldNaN },
  { "RelativeUnits", RelativeUnits },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
