// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Filtering/Transfer.h"

#include "Common/Constants.h"
#include "Common/Threads.h"
#include "Operators/Operators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace spectral
{
namespace
{

std::string Str(double value)
{
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", value);
  return buffer;
}

void Require(bool ok, const std::string& what)
{
  if (!ok)
  {
    throw InvalidInput(what);
  }
}

/// Validate the fields of p that its Kind uses.
void Validate(const FilterParameters& p)
{
  switch (p.Kind)
  {
    case FilterKind::BandPass:
    case FilterKind::BandStop:
    case FilterKind::BandExaggeration:
      Require(std::isfinite(p.UpperCutoff) && p.UpperCutoff >= p.Cutoff,
        "the upper cutoff (" + Str(p.UpperCutoff) + ") must be finite and >= the cutoff (" +
          Str(p.Cutoff) + ")");
      [[fallthrough]];
    case FilterKind::LowPass:
    case FilterKind::HighPass:
    case FilterKind::Enhancement:
      Require(std::isfinite(p.Cutoff) && p.Cutoff >= 0.0,
        "the cutoff frequency must be finite and >= 0, not " + Str(p.Cutoff));
      Require(std::isfinite(p.Transition) && p.Transition >= 0.0,
        "the transition width must be finite and >= 0, not " + Str(p.Transition));
      Require(std::isfinite(p.Gain), "the gain must be finite");
      break;
    case FilterKind::HeatDiffusion:
      Require(std::isfinite(p.Time) && p.Time >= 0.0,
        "the diffusion time must be finite and >= 0, not " + Str(p.Time));
      break;
    case FilterKind::Custom:
      Require(!p.ControlPoints.empty(), "a custom filter needs at least one control point");
      for (std::size_t i = 0; i < p.ControlPoints.size(); ++i)
      {
        Require(std::isfinite(p.ControlPoints[i].first) && std::isfinite(p.ControlPoints[i].second),
          "control point " + std::to_string(i) + " is not finite");
        Require(i == 0 || p.ControlPoints[i].first > p.ControlPoints[i - 1].first,
          "the frequencies of the control points must be strictly increasing (point " +
            std::to_string(i) + ")");
      }
      break;
    default:
      throw InvalidInput("unknown filter kind " + std::to_string(static_cast<int>(p.Kind)));
  }
}

/// Smooth step from 0 to 1: a raised cosine over [c (1 - w/2), c (1 + w/2)]; omega > c if sharp.
double Rise(double omega, double c, double w)
{
  const double a = c * (1.0 - 0.5 * w);
  const double b = c * (1.0 + 0.5 * w);
  if (!(b > a))
  {
    return omega > c ? 1.0 : 0.0;
  }
  if (omega <= a)
  {
    return 0.0;
  }
  if (omega >= b)
  {
    return 1.0;
  }
  return 0.5 - 0.5 * std::cos(Pi * (omega - a) / (b - a));
}

double InsideBand(const FilterParameters& p, double omega)
{
  return Rise(omega, p.Cutoff, p.Transition) * (1.0 - Rise(omega, p.UpperCutoff, p.Transition));
}

double Interpolate(const std::vector<std::pair<double, double>>& points, double omega)
{
  if (omega <= points.front().first)
  {
    return points.front().second;
  }
  if (omega >= points.back().first)
  {
    return points.back().second;
  }
  const auto upper = std::upper_bound(points.begin(),
    points.end(),
    omega,
    [](double w, const std::pair<double, double>& point) { return w < point.first; });
  const auto lower = upper - 1;
  const double s = (omega - lower->first) / (upper->first - lower->first);
  return (1.0 - s) * lower->second + s * upper->second;
}

/// F(omega) for validated parameters.
double Evaluate(const FilterParameters& p, double omega)
{
  switch (p.Kind)
  {
    case FilterKind::LowPass:
      return 1.0 - Rise(omega, p.Cutoff, p.Transition);
    case FilterKind::HighPass:
      return Rise(omega, p.Cutoff, p.Transition);
    case FilterKind::BandPass:
      return InsideBand(p, omega);
    case FilterKind::BandStop:
      return 1.0 - InsideBand(p, omega);
    case FilterKind::Enhancement:
      return 1.0 + (p.Gain - 1.0) * Rise(omega, p.Cutoff, p.Transition);
    case FilterKind::BandExaggeration:
      return 1.0 + (p.Gain - 1.0) * InsideBand(p, omega);
    case FilterKind::HeatDiffusion:
      return std::exp(-p.Time * omega * omega);
    case FilterKind::Custom:
      return Interpolate(p.ControlPoints, omega);
  }
  return 0.0;
}

void RequireFrequency(double omega)
{
  Require(
    std::isfinite(omega) && omega >= 0.0, "a frequency must be finite and >= 0, not " + Str(omega));
}

/// Where F or one of its derivatives may jump: the ends of every step, the control points.
std::vector<double> Breakpoints(const FilterParameters& p)
{
  std::vector<double> out;
  auto addStep = [&p, &out](double c)
  {
    out.push_back(c * (1.0 - 0.5 * p.Transition));
    out.push_back(c);
    out.push_back(c * (1.0 + 0.5 * p.Transition));
  };
  switch (p.Kind)
  {
    case FilterKind::BandPass:
    case FilterKind::BandStop:
    case FilterKind::BandExaggeration:
      addStep(p.UpperCutoff);
      addStep(p.Cutoff);
      break;
    case FilterKind::LowPass:
    case FilterKind::HighPass:
    case FilterKind::Enhancement:
      addStep(p.Cutoff);
      break;
    case FilterKind::Custom:
      for (const auto& point : p.ControlPoints)
      {
        out.push_back(point.first);
      }
      break;
    default:
      break;
  }
  return out;
}

/// Nodes and weights of the 10-point Gauss-Legendre rule on [-1, 1] (exact to degree 19).
struct GaussLegendre
{
  static constexpr int Order = 10;
  std::array<double, Order> Nodes;
  std::array<double, Order> Weights;

  GaussLegendre()
  {
    for (int i = 0; i < Order; ++i)
    {
      // Newton's iteration on P_n from the Chebyshev-like guess of the i-th root.
      double x = std::cos(Pi * (i + 0.75) / (Order + 0.5));
      double derivative = 1.0;
      for (int iteration = 0; iteration < 100; ++iteration)
      {
        double p0 = 1.0;
        double p1 = x;
        for (int k = 2; k <= Order; ++k)
        {
          const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        derivative = Order * (x * p1 - p0) / (x * x - 1.0);
        const double step = p1 / derivative;
        x -= step;
        if (std::abs(step) < 1e-16)
        {
          break;
        }
      }
      this->Nodes[i] = x;
      this->Weights[i] = 2.0 / ((1.0 - x * x) * derivative * derivative);
    }
  }
};

/**
 * Rows of the basis per block: about 256 KB of H, so that a block stays in cache while it is
 * used (packed by the product of the forward transform, converted to double for a float basis)
 * and the whole transform reads H from memory once.
 */
Eigen::Index BlockRows(Eigen::Index m)
{
  return std::max<Eigen::Index>(16, 32768 / std::max<Eigen::Index>(m, 1));
}

double Integrate(const FilterParameters& p, double a, double b)
{
  static const GaussLegendre rule;
  const double half = 0.5 * (b - a);
  const double mid = 0.5 * (a + b);
  double sum = 0.0;
  for (int i = 0; i < GaussLegendre::Order; ++i)
  {
    sum += rule.Weights[i] * Evaluate(p, mid + half * rule.Nodes[i]);
  }
  return half * sum;
}

/// Rows [first, first + count) of a double basis, in place.
Eigen::Map<const RowMatrix> DoubleRows(const BasisView& H,
  Eigen::Index first,
  Eigen::Index count,
  RowMatrix&)
{
  return Eigen::Map<const RowMatrix>(H.data() + first * H.cols(), count, H.cols());
}

/// Rows [first, first + count) of a float basis, converted to double into `buffer` (one block
/// of BlockRows rows, reused from block to block: the basis itself is never copied).
Eigen::Map<const RowMatrix> DoubleRows(const FloatBasisView& H,
  Eigen::Index first,
  Eigen::Index count,
  RowMatrix& buffer)
{
  buffer = H.middleRows(first, count).cast<double>();
  return Eigen::Map<const RowMatrix>(buffer.data(), count, H.cols());
}

/// X~ = H^T D X over row ranges on `threads` threads, one partial sum per range.
template<typename Basis>
RowMatrix Forward(const Basis& H, const Vector& mass, const ConstRowView& X, int threads)
{
  Require(mass.size() == H.rows() && X.rows() == H.rows(),
    "the basis has " + std::to_string(H.rows()) + " points, the mass " +
      std::to_string(mass.size()) + " and the signal " + std::to_string(X.rows()));
  const int parts = TransformThreads(H.rows(), H.cols(), threads);
  std::vector<RowMatrix> partial(
    static_cast<std::size_t>(parts), RowMatrix::Zero(H.cols(), X.cols()));
  const Eigen::Index block = BlockRows(H.cols());
  ForEachRowRange(H.rows(),
    parts,
    [&H, &mass, &X, &partial, block](int part, Eigen::Index first, Eigen::Index count)
    {
      RowMatrix buffer;
      RowMatrix weighted;
      RowMatrix& sum = partial[static_cast<std::size_t>(part)];
      for (Eigen::Index i = first; i < first + count; i += block)
      {
        const Eigen::Index rows = std::min(block, first + count - i);
        weighted = mass.segment(i, rows).asDiagonal() * X.middleRows(i, rows);
        for (Eigen::Index r = 0; r < rows; ++r)
        {
          if (mass[i + r] == 0.0)
          {
            // Outside the surface (or another process's point): no term, whatever X holds
            // there (0 * NaN would spoil every coefficient).
            weighted.row(r).setZero();
          }
        }
        sum.noalias() += DoubleRows(H, i, rows, buffer).transpose() * weighted;
      }
    });
  for (std::size_t part = 1; part < partial.size(); ++part)
  {
    partial[0] += partial[part];
  }
  return partial[0];
}

/// Y = H diag(gains - hf) X~ + hf X over row ranges on `threads` threads.
template<typename Basis>
RowMatrix Inverse(const Basis& H,
  const Vector& gains,
  const ConstRowView& coefficients,
  const ConstRowView& X,
  double hfGain,
  int threads)
{
  const Eigen::Index n = H.rows();
  const Eigen::Index c = coefficients.cols();
  Require(gains.size() == H.cols() && coefficients.rows() == H.cols(),
    "the basis has " + std::to_string(H.cols()) + " harmonics, the gains " +
      std::to_string(gains.size()) + " and the coefficients " +
      std::to_string(coefficients.rows()));
  Require(std::isfinite(hfGain), "the high-frequency gain must be finite");
  Require(X.rows() != 0 || hfGain == 0.0 || n == 0,
    "re-injecting high frequencies (gain " + Str(hfGain) + ") needs the original signal");
  Require(X.rows() == 0 || (X.rows() == n && X.cols() == c),
    "the original signal is " + std::to_string(X.rows()) + " by " + std::to_string(X.cols()) +
      ", expected " + std::to_string(n) + " by " + std::to_string(c));

  // Y = H diag(gains - hf) X~ + hf X: one pass over H, block by block, each thread its rows.
  // Each value of Y is the dot product of a row of H (contiguous) with a column of the scaled
  // coefficients (column-major, contiguous): for the few columns of a signal this beats a
  // matrix-matrix product, whose packing costs as much as reading H.
  const DenseMatrix scaled = (gains.array() - hfGain).matrix().asDiagonal() * coefficients;
  RowMatrix Y(n, c);
  const Eigen::Index block = BlockRows(H.cols());
  ForEachRowRange(n,
    TransformThreads(n, H.cols(), threads),
    [&H, &X, &scaled, &Y, hfGain, block](int, Eigen::Index first, Eigen::Index count)
    {
      RowMatrix buffer;
      for (Eigen::Index i = first; i < first + count; i += block)
      {
        const Eigen::Index rows = std::min(block, first + count - i);
        auto out = Y.middleRows(i, rows);
        if (hfGain != 0.0)
        {
          out = hfGain * X.middleRows(i, rows) + DoubleRows(H, i, rows, buffer).lazyProduct(scaled);
        }
        else
        {
          out = DoubleRows(H, i, rows, buffer).lazyProduct(scaled);
        }
      }
    });
  return Y;
}

/// The checks FilterSignal adds to those of InverseTransform.
void RequireSurfaceSignal(Eigen::Index n, const Vector& mass, const ConstRowView& X)
{
  Require(mass.size() == n && X.rows() == n,
    "the basis has " + std::to_string(n) + " points, the mass " + std::to_string(mass.size()) +
      " and the signal " + std::to_string(X.rows()));
}

/// Y with the rows of the points of zero mass (outside the surface) replaced by those of X.
RowMatrix KeepOutsidePoints(const Vector& mass, const ConstRowView& X, RowMatrix Y)
{
  for (Eigen::Index i = 0; i < mass.size(); ++i)
  {
    if (mass[i] == 0.0)
    {
      Y.row(i) = X.row(i);
    }
  }
  return Y;
}
} // namespace

//------------------------------------------------------------------------------
RowMatrix ForwardTransform(const BasisView& H,
  const Vector& mass,
  const ConstRowView& X,
  int threads)
{
  return Forward(H, mass, X, threads);
}

//------------------------------------------------------------------------------
RowMatrix ForwardTransform(const FloatBasisView& H,
  const Vector& mass,
  const ConstRowView& X,
  int threads)
{
  return Forward(H, mass, X, threads);
}

//------------------------------------------------------------------------------
RowMatrix InverseTransform(const BasisView& H,
  const Vector& gains,
  const ConstRowView& coefficients,
  const ConstRowView& X,
  double hfGain,
  int threads)
{
  return Inverse(H, gains, coefficients, X, hfGain, threads);
}

//------------------------------------------------------------------------------
RowMatrix InverseTransform(const FloatBasisView& H,
  const Vector& gains,
  const ConstRowView& coefficients,
  const ConstRowView& X,
  double hfGain,
  int threads)
{
  return Inverse(H, gains, coefficients, X, hfGain, threads);
}

//------------------------------------------------------------------------------
RowMatrix FilterSignal(const BasisView& H,
  const Vector& mass,
  const Vector& gains,
  const ConstRowView& coefficients,
  const ConstRowView& X,
  double hfGain,
  int threads)
{
  RequireSurfaceSignal(H.rows(), mass, X);
  return KeepOutsidePoints(mass, X, Inverse(H, gains, coefficients, X, hfGain, threads));
}

//------------------------------------------------------------------------------
RowMatrix FilterSignal(const FloatBasisView& H,
  const Vector& mass,
  const Vector& gains,
  const ConstRowView& coefficients,
  const ConstRowView& X,
  double hfGain,
  int threads)
{
  RequireSurfaceSignal(H.rows(), mass, X);
  return KeepOutsidePoints(mass, X, Inverse(H, gains, coefficients, X, hfGain, threads));
}

//------------------------------------------------------------------------------
double Gain(const FilterParameters& p, double omega)
{
  Validate(p);
  RequireFrequency(omega);
  return Evaluate(p, omega);
}

//------------------------------------------------------------------------------
Vector Gains(const FilterParameters& p, const Vector& lambda)
{
  Validate(p);
  Vector out(lambda.size());
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
  {
    Require(!std::isnan(lambda[k]), "eigenvalue " + std::to_string(k) + " is NaN");
    const double omega = std::sqrt(std::max(lambda[k], 0.0));
    RequireFrequency(omega);
    out[k] = Evaluate(p, omega);
  }
  return out;
}

//------------------------------------------------------------------------------
double ConstantAbove(const FilterParameters& p)
{
  Validate(p);
  const std::vector<double> breakpoints = Breakpoints(p);
  if (p.Kind == FilterKind::HeatDiffusion || breakpoints.empty())
  {
    return std::numeric_limits<double>::infinity();
  }
  return *std::max_element(breakpoints.begin(), breakpoints.end());
}

//------------------------------------------------------------------------------
double HighestFrequency(const Vector& lambda)
{
  return lambda.size() == 0 ? 0.0 : std::sqrt(std::max(lambda[lambda.size() - 1], 0.0));
}

//------------------------------------------------------------------------------
double HarmonicFrequency(const Vector& lambda, double index)
{
  Require(lambda.size() > 0, "a harmonic index needs a basis with at least one harmonic");
  Require(std::isfinite(index) && index >= 0.0,
    "a harmonic index must be finite and >= 0, not " + Str(index));
  const double last = static_cast<double>(lambda.size() - 1);
  if (index >= last)
  {
    return HighestFrequency(lambda);
  }
  const auto k = static_cast<Eigen::Index>(std::floor(index));
  const double s = index - static_cast<double>(k);
  const double low = std::sqrt(std::max(lambda[k], 0.0));
  const double high = std::sqrt(std::max(lambda[k + 1], 0.0));
  return s == 0.0 ? low : (1.0 - s) * low + s * high;
}

//------------------------------------------------------------------------------
FilterParameters ToAbsoluteUnits(const FilterParameters& p,
  FrequencyUnits units,
  const Vector& lambda,
  double firstNonZeroEigenvalue)
{
  Validate(p);
  if (units == FrequencyUnits::Absolute)
  {
    return p;
  }
  Require(units == FrequencyUnits::FractionOfHighest || units == FrequencyUnits::HarmonicIndex,
    "unknown frequency units " + std::to_string(static_cast<int>(units)));
  const double highest = HighestFrequency(lambda);
  const auto frequency = [&lambda, units, highest](double value)
  {
    return units == FrequencyUnits::FractionOfHighest ? value * highest
                                                      : HarmonicFrequency(lambda, value);
  };
  FilterParameters out = p;
  if (p.Kind != FilterKind::HeatDiffusion && p.Kind != FilterKind::Custom)
  {
    out.Cutoff = frequency(p.Cutoff);
    out.UpperCutoff = std::isfinite(p.UpperCutoff) && p.UpperCutoff >= 0.0
      ? frequency(p.UpperCutoff)
      : p.UpperCutoff;
  }
  for (auto& point : out.ControlPoints)
  {
    point.first = frequency(std::max(point.first, 0.0)) + std::min(point.first, 0.0);
  }
  out.Time = firstNonZeroEigenvalue > 0.0 ? p.Time / firstNonZeroEigenvalue : 0.0;
  return out;
}

//------------------------------------------------------------------------------
double NyquistFrequency(double edgeLengthSum, double edgeCount)
{
  const double h = edgeCount > 0.0 ? edgeLengthSum / edgeCount : 0.0;
  return h > 0.0 && std::isfinite(h) ? Pi / h : 0.0;
}

//------------------------------------------------------------------------------
double NyquistFrequency(const TriangleMesh& mesh)
{
  const double edges = EdgeCount(mesh);
  const double nyquist = NyquistFrequency(MeanEdgeLength(mesh) * edges, edges);
  Require(
    nyquist > 0.0, "the Nyquist frequency needs a mesh with cells of non-zero, finite edge length");
  return nyquist;
}

//------------------------------------------------------------------------------
double MeanGain(const FilterParameters& p, double omegaLow, double omegaHigh)
{
  Validate(p);
  RequireFrequency(omegaLow);
  Require(!std::isnan(omegaHigh), "the upper frequency is NaN");
  if (!(omegaHigh > omegaLow))
  {
    return Evaluate(p, omegaLow);
  }
  RequireFrequency(omegaHigh);
  const double width = omegaHigh - omegaLow;
  if (p.Kind == FilterKind::HeatDiffusion)
  {
    if (p.Time == 0.0)
    {
      return 1.0;
    }
    // Integral of exp(-t w^2) = sqrt(pi / t) / 2 (erf(sqrt(t) b) - erf(sqrt(t) a)), with erfc
    // so that the difference keeps its digits when both arguments are large.
    const double s = std::sqrt(p.Time);
    return 0.5 * std::sqrt(Pi) / s * (std::erfc(s * omegaLow) - std::erfc(s * omegaHigh)) / width;
  }
  std::vector<double> cuts = Breakpoints(p);
  cuts.push_back(omegaLow);
  cuts.push_back(omegaHigh);
  std::sort(cuts.begin(), cuts.end());
  double integral = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
  {
    const double a = std::max(cuts[i], omegaLow);
    const double b = std::min(cuts[i + 1], omegaHigh);
    if (b > a)
    {
      integral += Integrate(p, a, b);
    }
  }
  return integral / width;
}
} // namespace spectral
