// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Spectral shape descriptors as sums over the eigenpairs of a basis (see Descriptors.h).
#include "Filtering/Descriptors.h"
#include "Common/Constants.h"
#include "Common/Eigenvalues.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace spectral
{
namespace
{
/// Weyl's estimate of sum_{k >= M} e^{-rate k^(2/3)} in a volume (rate = t lambda_1 by Weyl):
/// the integral of e^{-rate x^(2/3)} over x >= M - 1/2, which is
/// 3/2 rate^(-3/2) Gamma(3/2, z) with z = rate (M - 1/2)^(2/3) and
/// Gamma(3/2, z) = sqrt(z) e^{-z} + sqrt(pi) / 2 erfc(sqrt(z)).
double VolumeWeylTail(double rate, double count)
{
  const double z = rate * std::pow(std::max(count - 0.5, 0.0), 2.0 / 3.0);
  const double root = std::sqrt(z);
  const double gamma = root * std::exp(-z) + 0.5 * std::sqrt(Pi) * std::erfc(root);
  return 1.5 * std::pow(rate, -1.5) * gamma;
}

/// The smallest M >= 1 with VolumeWeylTail(rate, M) <= tolerance * trace (the tail decreases
/// with M): doubling, then bisection. The largest int when no int is enough.
int VolumeHarmonicsNeeded(double rate, double trace, double tolerance)
{
  const double target = tolerance * trace;
  const double most = static_cast<double>(std::numeric_limits<int>::max());
  double high = 1.0;
  while (VolumeWeylTail(rate, high) > target)
  {
    high *= 2.0;
    if (high > most)
    {
      return std::numeric_limits<int>::max();
    }
  }
  double low = std::floor(high / 2.0); // the tail at low is above the target, or low < 1
  while (high - low > 1.0)
  {
    const double middle = std::floor(0.5 * (low + high));
    (VolumeWeylTail(rate, middle) > target ? low : high) = middle;
  }
  return static_cast<int>(high);
}

/// Rows of the basis converted to double per block: the descriptors read H once.
constexpr Eigen::Index BlockRows = 256;

void CheckSpectrum(const Spectrum& spectrum)
{
  if (spectrum.NonZero.size() != static_cast<std::size_t>(spectrum.Lambda.size()))
  {
    throw InvalidInput("the spectrum has " + std::to_string(spectrum.Lambda.size()) +
      " eigenvalues but " + std::to_string(spectrum.NonZero.size()) + " zero flags");
  }
  for (Eigen::Index k = 0; k < spectrum.Lambda.size(); ++k)
  {
    const double lambda = spectrum.Lambda[k];
    if (spectrum.NonZero[k] && !(lambda > 0.0 && std::isfinite(lambda)))
    {
      throw InvalidInput("eigenvalue " + std::to_string(k) + " (" + std::to_string(lambda) +
        ") is flagged non-zero but is not a positive finite number");
    }
  }
}

template<typename View>
void CheckBasis(const View& H, const Spectrum& spectrum)
{
  CheckSpectrum(spectrum);
  if (H.cols() != spectrum.Lambda.size())
  {
    throw InvalidInput("the basis has " + std::to_string(H.cols()) + " harmonics but " +
      std::to_string(spectrum.Lambda.size()) + " eigenvalues");
  }
}

void CheckTimes(const Vector& times)
{
  for (Eigen::Index j = 0; j < times.size(); ++j)
  {
    if (!(times[j] >= 0.0 && std::isfinite(times[j])))
    {
      throw InvalidInput("time " + std::to_string(times[j]) + " is not a finite number >= 0");
    }
  }
}

/// The smallest and largest non-zero eigenvalue. \throws InvalidInput if there is none.
std::pair<double, double> NonZeroRange(const Spectrum& spectrum)
{
  const std::vector<Eigen::Index> nonZero = NonZeroIndices(spectrum);
  if (nonZero.empty())
  {
    throw InvalidInput("the basis has no non-constant harmonic (every eigenvalue is zero)");
  }
  return { spectrum.Lambda[nonZero.front()], spectrum.Lambda[nonZero.back()] };
}

/// (H o H) W: the squared harmonics of each point weighed by the m by c matrix W.
template<typename View>
RowMatrix SquaredTimes(const View& H, const DenseMatrix& W)
{
  RowMatrix result(H.rows(), W.cols());
  for (Eigen::Index first = 0; first < H.rows(); first += BlockRows)
  {
    const Eigen::Index rows = std::min(BlockRows, H.rows() - first);
    const RowMatrix block = H.middleRows(first, rows).template cast<double>();
    result.middleRows(first, rows).noalias() = block.cwiseAbs2() * W;
  }
  return result;
}

template<typename View>
RowMatrix HeatKernelSignatureOf(const View& H,
  const Spectrum& spectrum,
  const Vector& times,
  bool scaleNormalize)
{
  CheckBasis(H, spectrum);
  CheckTimes(times);
  const Vector lambda = HeatEigenvalues(spectrum);
  // W_kj = e^{-lambda_k t_j}, divided by the trace sum_k W_kj when scale-normalized.
  DenseMatrix W = (-lambda * times.transpose()).array().exp().matrix();
  if (scaleNormalize)
  {
    W.array().rowwise() /= W.colwise().sum().array();
  }
  return SquaredTimes(H, W);
}

template<typename View>
RowMatrix WaveKernelSignatureOf(const View& H,
  const Spectrum& spectrum,
  const WaveKernelEnergies& energies)
{
  CheckBasis(H, spectrum);
  return SquaredTimes(H, WaveKernelWeights(spectrum, energies));
}

template<typename View>
RowMatrix GlobalPointSignatureOf(const View& H, const Spectrum& spectrum, int components)
{
  CheckBasis(H, spectrum);
  const std::vector<Eigen::Index> nonZero = NonZeroIndices(spectrum);
  if (components < 1 || static_cast<std::size_t>(components) > nonZero.size())
  {
    throw InvalidInput("the global point signature needs 1 to " + std::to_string(nonZero.size()) +
      " components (the non-constant harmonics), not " + std::to_string(components));
  }
  RowMatrix result(H.rows(), components);
  for (int c = 0; c < components; ++c)
  {
    const Eigen::Index k = nonZero[c];
    result.col(c) = H.col(k).template cast<double>() / std::sqrt(spectrum.Lambda[k]);
  }
  return result;
}

template<typename View>
Vector SpectralDistanceOf(const View& H, const Vector& weights, Eigen::Index source)
{
  if (weights.size() != H.cols())
  {
    throw InvalidInput("the distance has " + std::to_string(weights.size()) +
      " weights for a basis of " + std::to_string(H.cols()) + " harmonics");
  }
  if (source < 0 || source >= H.rows())
  {
    throw InvalidInput("source point " + std::to_string(source) + " is outside [0, " +
      std::to_string(H.rows()) + ")");
  }
  const Eigen::RowVectorXd origin = H.row(source).template cast<double>();
  Vector distance(H.rows());
  for (Eigen::Index first = 0; first < H.rows(); first += BlockRows)
  {
    const Eigen::Index rows = std::min(BlockRows, H.rows() - first);
    const RowMatrix block = H.middleRows(first, rows).template cast<double>();
    distance.segment(first, rows) = ((block.rowwise() - origin).cwiseAbs2() * weights).cwiseSqrt();
  }
  return distance;
}
} // anonymous namespace

//------------------------------------------------------------------------------
Vector HeatEigenvalues(const Spectrum& spectrum)
{
  CheckSpectrum(spectrum);
  Vector lambda = spectrum.Lambda;
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
  {
    if (!spectrum.NonZero[k])
    {
      lambda[k] = 0.0;
    }
  }
  return lambda;
}

//------------------------------------------------------------------------------
std::vector<Eigen::Index> NonZeroIndices(const Spectrum& spectrum)
{
  CheckSpectrum(spectrum);
  std::vector<Eigen::Index> indices;
  for (Eigen::Index k = 0; k < spectrum.Lambda.size(); ++k)
  {
    if (spectrum.NonZero[k])
    {
      indices.push_back(k);
    }
  }
  return indices;
}

//------------------------------------------------------------------------------
Vector DefaultHeatKernelTimes(const Spectrum& spectrum, int count)
{
  if (count < 1)
  {
    throw InvalidInput("the number of heat kernel times must be at least 1");
  }
  const auto range = NonZeroRange(spectrum);
  const double fourLn10 = 4.0 * std::log(10.0);
  const double logFirst = std::log(fourLn10 / range.second);
  const double logLast = std::log(fourLn10 / range.first);
  if (count == 1)
  {
    return Vector::Constant(1, std::exp(0.5 * (logFirst + logLast)));
  }
  return Vector::LinSpaced(count, logFirst, logLast).array().exp().matrix();
}

//------------------------------------------------------------------------------
Vector HeatTrace(const Spectrum& spectrum, const Vector& times)
{
  CheckTimes(times);
  const Vector lambda = HeatEigenvalues(spectrum);
  return (-times * lambda.transpose()).array().exp().rowwise().sum().matrix();
}

//------------------------------------------------------------------------------
RowMatrix HeatKernelSignature(const BasisView& H,
  const Spectrum& spectrum,
  const Vector& times,
  bool scaleNormalize)
{
  return HeatKernelSignatureOf(H, spectrum, times, scaleNormalize);
}

//------------------------------------------------------------------------------
RowMatrix HeatKernelSignature(const FloatBasisView& H,
  const Spectrum& spectrum,
  const Vector& times,
  bool scaleNormalize)
{
  return HeatKernelSignatureOf(H, spectrum, times, scaleNormalize);
}

//------------------------------------------------------------------------------
int HeatKernelHarmonicsNeeded(const Spectrum& spectrum,
  double measure,
  int dimension,
  double time,
  double tolerance)
{
  if (!(measure > 0.0 && std::isfinite(measure)))
  {
    throw InvalidInput("the area or volume must be a positive finite number");
  }
  if (dimension != 2 && dimension != 3)
  {
    throw InvalidInput("the dimension must be 2 (a surface) or 3 (a volume)");
  }
  if (!(tolerance > 0.0 && tolerance < 1.0))
  {
    throw InvalidInput("the truncation tolerance must lie in (0, 1)");
  }
  CheckTimes(Vector::Constant(1, time));
  if (time == 0.0)
  {
    return std::numeric_limits<int>::max();
  }
  const double computed = HeatTrace(spectrum, Vector::Constant(1, time))[0];
  const double m = static_cast<double>(spectrum.Lambda.size());
  // Weyl: lambda_k ~ WeylEigenvalue(1) k^(2 / dimension).
  const double rate = time * WeylEigenvalue(1.0, measure, dimension);
  if (dimension == 3)
  {
    return VolumeHarmonicsNeeded(rate, computed + VolumeWeylTail(rate, m), tolerance);
  }
  // On a surface lambda_k ~ 4 pi k / A, so sum_{k >= M} e^{-lambda_k t} ~ q^M / (1 - q).
  const double logQ = -rate;
  const double oneMinusQ = -std::expm1(logQ);
  const double trace = computed + std::exp(m * logQ) / oneMinusQ;
  // The smallest M with q^M / (1 - q) <= tolerance * trace.
  const double needed = std::ceil(std::log(tolerance * trace * oneMinusQ) / logQ);
  if (!(needed < static_cast<double>(std::numeric_limits<int>::max())))
  {
    return std::numeric_limits<int>::max();
  }
  return std::max(1, static_cast<int>(needed));
}

//------------------------------------------------------------------------------
WaveKernelEnergies DefaultWaveKernelEnergies(const Spectrum& spectrum, int count, double sigma)
{
  if (count < 1)
  {
    throw InvalidInput("the number of wave kernel energies must be at least 1");
  }
  if (!(sigma >= 0.0 && std::isfinite(sigma)))
  {
    throw InvalidInput("the wave kernel sigma must be a finite number >= 0");
  }
  const auto range = NonZeroRange(spectrum);
  const double low = std::log(range.first);
  const double width = std::log(range.second) - low;
  WaveKernelEnergies result;
  if (sigma == 0.0)
  {
    // sigma = 7 delta, margins 2 sigma, count energies delta apart: width = (count + 27) delta.
    const double delta = width / (static_cast<double>(count) + 4.0 * WaveKernelSigmaInSteps - 1.0);
    result.Sigma = WaveKernelSigmaInSteps * delta;
    result.Energies = Vector::LinSpaced(count,
      low + 2.0 * result.Sigma,
      low + 2.0 * result.Sigma + static_cast<double>(count - 1) * delta);
    if (width == 0.0)
    {
      // A single non-zero eigenvalue: one filter width of nothing; any sigma > 0 will do.
      result.Sigma = 1.0;
    }
    return result;
  }
  if (4.0 * sigma > width)
  {
    std::ostringstream message;
    message << "the wave kernel sigma " << sigma
            << " leaves no energies between the margins of 2 sigma at both ends of"
               " [log lambda_1, log lambda_max]; it must be at most "
            << width / 4.0;
    throw InvalidInput(message.str());
  }
  result.Sigma = sigma;
  result.Energies = Vector::LinSpaced(count, low + 2.0 * sigma, low + width - 2.0 * sigma);
  if (count == 1)
  {
    result.Energies[0] = low + 0.5 * width;
  }
  return result;
}

//------------------------------------------------------------------------------
DenseMatrix WaveKernelWeights(const Spectrum& spectrum, const WaveKernelEnergies& energies)
{
  if (!(energies.Sigma > 0.0 && std::isfinite(energies.Sigma)))
  {
    throw InvalidInput("the wave kernel sigma must be a positive finite number");
  }
  const std::vector<Eigen::Index> nonZero = NonZeroIndices(spectrum);
  if (nonZero.empty())
  {
    throw InvalidInput("the basis has no non-constant harmonic (every eigenvalue is zero)");
  }
  const Eigen::Index E = energies.Energies.size();
  // Exponents of g_k(e_j); each column is shifted by its largest exponent before exp(), which
  // cancels in the normalization and keeps a narrow filter from underflowing to 0 / 0.
  DenseMatrix exponents =
    DenseMatrix::Constant(spectrum.Lambda.size(), E, -std::numeric_limits<double>::infinity());
  const double twoSigma2 = 2.0 * energies.Sigma * energies.Sigma;
  for (Eigen::Index k : nonZero)
  {
    const double logLambda = std::log(spectrum.Lambda[k]);
    exponents.row(k) =
      -(energies.Energies.transpose().array() - logLambda).square().matrix() / twoSigma2;
  }
  DenseMatrix W = (exponents.rowwise() - exponents.colwise().maxCoeff()).array().exp().matrix();
  W.array().rowwise() /= W.colwise().sum().array();
  return W;
}

//------------------------------------------------------------------------------
RowMatrix WaveKernelSignature(const BasisView& H,
  const Spectrum& spectrum,
  const WaveKernelEnergies& energies)
{
  return WaveKernelSignatureOf(H, spectrum, energies);
}

//------------------------------------------------------------------------------
RowMatrix WaveKernelSignature(const FloatBasisView& H,
  const Spectrum& spectrum,
  const WaveKernelEnergies& energies)
{
  return WaveKernelSignatureOf(H, spectrum, energies);
}

//------------------------------------------------------------------------------
RowMatrix GlobalPointSignature(const BasisView& H, const Spectrum& spectrum, int components)
{
  return GlobalPointSignatureOf(H, spectrum, components);
}

//------------------------------------------------------------------------------
RowMatrix GlobalPointSignature(const FloatBasisView& H, const Spectrum& spectrum, int components)
{
  return GlobalPointSignatureOf(H, spectrum, components);
}

//------------------------------------------------------------------------------
Vector DistanceWeights(const Spectrum& spectrum, DistanceKind kind, double time)
{
  CheckTimes(Vector::Constant(1, time));
  const Vector lambda = HeatEigenvalues(spectrum);
  switch (kind)
  {
    case DistanceKind::Diffusion:
      return (-2.0 * time * lambda).array().exp().matrix();
    case DistanceKind::CommuteTime:
    case DistanceKind::Biharmonic:
    {
      const double power = kind == DistanceKind::CommuteTime ? 1.0 : 2.0;
      Vector weights = Vector::Zero(lambda.size());
      for (Eigen::Index k : NonZeroIndices(spectrum))
      {
        weights[k] = std::pow(lambda[k], -power);
      }
      return weights;
    }
  }
  throw InvalidInput("unknown distance kind " + std::to_string(static_cast<int>(kind)));
}

//------------------------------------------------------------------------------
Vector SpectralDistance(const BasisView& H, const Vector& weights, Eigen::Index source)
{
  return SpectralDistanceOf(H, weights, source);
}

//------------------------------------------------------------------------------
Vector SpectralDistance(const FloatBasisView& H, const Vector& weights, Eigen::Index source)
{
  return SpectralDistanceOf(H, weights, source);
}

//------------------------------------------------------------------------------
Vector ShapeDNA(const Vector& lambda, double measure, int dimension)
{
  if (!(measure > 0.0 && std::isfinite(measure)))
  {
    throw InvalidInput("ShapeDNA needs a positive finite area or volume");
  }
  if (dimension < 1)
  {
    throw InvalidInput("ShapeDNA needs a dimension of at least 1");
  }
  return lambda * std::pow(measure, 2.0 / static_cast<double>(dimension));
}
} // namespace spectral
