// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The cutoff units of vtkSpectralFilter (see vtkManifoldHarmonicsCutoffs.h): their checked
// mapping, the slider ranges in each, and the warnings about cutoffs outside the spectrum.
#include "vtkManifoldHarmonicsCutoffs.h"

#include "vtkSpectralFilter.h"

#include "Spectral/Common/Eigenvalues.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
/// The slider ranges of a filter that has not run, or ran on constant harmonics only: they keep
/// the panel's defaults (Cutoff 0.5, UpperCutoff 1, Time 0; see GetFrequencyRange). Absolute
/// frequencies keep the range they had before relative units came, [0, 2].
constexpr double InitialFrequencyRange[2] = { 0.0, 1.0 };
constexpr double InitialAbsoluteFrequencyRange[2] = { 0.0, 2.0 };
constexpr double InitialTimeRange[2] = { 0.0, 1.0 };
/// The Time slider ends where heat diffusion damps the lowest non-constant harmonic to exp(-4).
constexpr double TimeRangeInUnitsOfFirstEigenvalue = 4.0;

/// Whether harmonic k is a constant one: its eigenvalue is zero by spectral::IsZeroEigenvalue
/// with the scale omega_N^2 (omega_N the Nyquist frequency), or not finite.
bool IsConstantHarmonic(double lambda, double nyquist)
{
  return spectral::IsZeroEigenvalue(lambda, nyquist * nyquist) || !std::isfinite(lambda);
}

/// The relative units of a value, for messages.
const char* UnitsText(int units)
{
  switch (units)
  {
    case vtkSpectralFilter::FRACTION_OF_HIGHEST:
      return "of the highest computed frequency";
    default:
      return "(harmonic index)";
  }
}

/// Gains that differ by at most this are the same gain in the warnings' wording (0, 1, one gain
/// for all).
constexpr double SameGain = 1e-12;

/// What the gains do to the non-constant harmonics (and to the details above them when they are
/// re-injected), for the warnings about cutoffs outside the spectrum.
std::string Consequence(const spectral::Vector& gains,
  const std::vector<bool>& constant,
  double highFrequencyGain,
  bool reinject)
{
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (Eigen::Index k = 0; k < gains.size(); ++k)
  {
    if (!constant[k])
    {
      low = std::min(low, gains[k]);
      high = std::max(high, gains[k]);
    }
  }
  const double tiny = SameGain;
  std::ostringstream text;
  if (high - low <= tiny)
  {
    text << "every non-constant harmonic gets the gain " << low;
  }
  else
  {
    text << "the non-constant harmonics get gains from " << low << " to " << high;
  }
  if (reinject)
  {
    text << ", the details above them " << highFrequencyGain;
  }
  const double hf = reinject ? highFrequencyGain : low;
  if (std::abs(low) <= tiny && std::abs(high) <= tiny && std::abs(hf) <= tiny)
  {
    text << ": every point moves to the centroid of its connected component";
  }
  else if (std::abs(low - 1.0) <= tiny && std::abs(high - 1.0) <= tiny &&
    std::abs(hf - 1.0) <= tiny)
  {
    text << (reinject ? ": the output equals the input"
                      : ": the output is the input's projection onto the computed harmonics");
  }
  return text.str();
}

/// The non-zero frequencies of a basis: the first, the highest, and the index of the highest.
struct SpectrumEnds
{
  double First;
  double Highest;
  Eigen::Index Last;
};

/// Warns if the cutoff `name`, `value` in the filter's units and `frequency` in absolute ones,
/// lies below the first non-zero frequency or above the highest computed one (or, as a harmonic
/// index, beyond the last harmonic), with what the gains do (`consequence`).
void WarnIfOutside(vtkObject* self,
  int units,
  const char* name,
  double value,
  double frequency,
  const SpectrumEnds& ends,
  const std::string& consequence)
{
  std::ostringstream where;
  if (frequency < ends.First)
  {
    where << "lies below the first non-zero frequency " << ends.First << " of the basis";
  }
  else if (units == vtkSpectralFilter::HARMONIC_INDEX && value > static_cast<double>(ends.Last))
  {
    where << "lies beyond the last computed harmonic, " << ends.Last << " (frequency "
          << ends.Highest << ")";
  }
  else if (frequency > ends.Highest)
  {
    where << "lies above the highest computed frequency " << ends.Highest << " (harmonic "
          << ends.Last << ")";
  }
  else
  {
    return;
  }
  std::ostringstream given;
  given << name << " " << value;
  if (units != vtkSpectralFilter::ABSOLUTE_FREQUENCY)
  {
    given << " " << UnitsText(units) << " (frequency " << frequency << ")";
  }
  vtkWarningWithObjectMacro(
    self, << given.str() << " " << where.str() << ": " << consequence << ".");
}

/// Constant harmonics are meant to get F(0); a rounding-sized frequency that crosses a step
/// gives them another gain, which scales their components towards the origin: a warning.
/// `constant` marks them, `largestZero` is their largest eigenvalue.
void WarnAboutConstantHarmonics(vtkObject* self,
  const spectral::FilterParameters& absolute,
  const spectral::Vector& gains,
  const std::vector<bool>& constant,
  double largestZero)
{
  const double atZero = spectral::Gain(absolute, 0.0);
  Eigen::Index moved = 0;
  Eigen::Index constants = 0;
  double movedGain = atZero;
  for (Eigen::Index k = 0; k < gains.size(); ++k)
  {
    constants += constant[k] ? 1 : 0;
    if (constant[k] && std::abs(gains[k] - atZero) > 1e-6)
    {
      ++moved;
      movedGain = std::abs(gains[k] - atZero) > std::abs(movedGain - atZero) ? gains[k] : movedGain;
    }
  }
  if (moved > 0)
  {
    vtkWarningWithObjectMacro(self,
      << moved << " of the " << constants
      << " constant harmonic(s) (eigenvalue 0 up to rounding, frequencies up to "
      << std::sqrt(std::max(largestZero, 0.0)) << ") get the gain " << movedGain
      << " instead of F(0) = " << atZero
      << ": the transfer function changes among their rounding-sized frequencies, so the points "
         "of those components move towards the origin. Choose a cutoff (or a time) clear of "
         "them.");
  }
}

} // anonymous namespace

namespace vtkManifoldHarmonicsCutoffs
{
//------------------------------------------------------------------------------
void InitialRanges(double frequency[2], double time[2])
{
  std::copy(InitialFrequencyRange, InitialFrequencyRange + 2, frequency);
  std::copy(InitialTimeRange, InitialTimeRange + 2, time);
}

//------------------------------------------------------------------------------
double FirstNonZeroEigenvalue(const spectral::Vector& lambda, double nyquist)
{
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
  {
    if (!IsConstantHarmonic(lambda[k], nyquist))
    {
      return lambda[k];
    }
  }
  return 0.0;
}

//------------------------------------------------------------------------------
void SliderRanges(const spectral::Vector& lambda,
  double firstNonZero,
  int units,
  double frequency[2],
  double time[2])
{
  const double* initial = units == vtkSpectralFilter::ABSOLUTE_FREQUENCY
    ? InitialAbsoluteFrequencyRange
    : InitialFrequencyRange;
  std::copy(initial, initial + 2, frequency);
  std::copy(InitialTimeRange, InitialTimeRange + 2, time);
  if (units == vtkSpectralFilter::HARMONIC_INDEX && lambda.size() > 1)
  {
    frequency[1] = static_cast<double>(lambda.size() - 1);
  }
  if (!(firstNonZero > 0.0))
  {
    return; // no non-constant harmonic: the ranges of an unexecuted filter
  }
  time[1] = TimeRangeInUnitsOfFirstEigenvalue;
  if (units == vtkSpectralFilter::ABSOLUTE_FREQUENCY)
  {
    frequency[1] = spectral::HighestFrequency(lambda);
    time[1] /= firstNonZero;
  }
}

//------------------------------------------------------------------------------
void WarnAboutCutoffs(vtkObject* self,
  int units,
  bool reinject,
  const spectral::FilterParameters& given,
  const spectral::FilterParameters& absolute,
  const spectral::Vector& lambda,
  double nyquist,
  const spectral::Vector& gains,
  double highFrequencyGain)
{
  const Eigen::Index m = lambda.size();
  std::vector<bool> constant(static_cast<std::size_t>(m));
  Eigen::Index constants = 0;
  double largestZero = 0.0;
  for (Eigen::Index k = 0; k < m; ++k)
  {
    constant[k] = IsConstantHarmonic(lambda[k], nyquist);
    constants += constant[k] ? 1 : 0;
    largestZero = constant[k] && std::isfinite(lambda[k]) ? lambda[k] : largestZero;
  }
  if (m > 0 && constants == m)
  {
    // Each point is its component's centroid times F(0) plus, when re-injected, its offset from
    // the centroid times the gain above the basis. (Components without a harmonic were left out
    // by the basis, with its warning: their points stay.)
    const double tiny = SameGain;
    const double centroidGain = gains[0];
    const double offsetGain = reinject ? highFrequencyGain : 0.0;
    std::ostringstream effect;
    if (std::abs(centroidGain - 1.0) <= tiny && std::abs(offsetGain) <= tiny)
    {
      effect << "the points of each component with a harmonic move to its centroid";
    }
    else if (std::abs(centroidGain - 1.0) <= tiny && std::abs(offsetGain - 1.0) <= tiny)
    {
      effect << "the points stay where they are";
    }
    else
    {
      effect << "each point becomes " << centroidGain
             << " times the centroid of its component plus " << offsetGain
             << " times its offset from that centroid";
    }
    vtkWarningWithObjectMacro(self,
      << "The basis has no non-constant harmonic: its " << m
      << " eigenvalue(s) are all zero up to rounding (at most " << largestZero
      << "), one constant harmonic per connected component (faces that share no points, e.g. "
         "an OBJ unwelded at its texture seams): the filter cannot smooth or enhance a "
         "component, and here "
      << effect.str() << ".");
  }
  WarnAboutConstantHarmonics(self, absolute, gains, constant, largestZero);
  const bool band = given.Kind == spectral::FilterKind::BandPass ||
    given.Kind == spectral::FilterKind::BandStop ||
    given.Kind == spectral::FilterKind::BandExaggeration;
  const bool step = band || given.Kind == spectral::FilterKind::LowPass ||
    given.Kind == spectral::FilterKind::HighPass || given.Kind == spectral::FilterKind::Enhancement;
  if (constants == m || !step)
  {
    return;
  }
  const SpectrumEnds ends = {
    std::sqrt(FirstNonZeroEigenvalue(lambda, nyquist)), spectral::HighestFrequency(lambda), m - 1
  };
  const std::string consequence = Consequence(gains, constant, highFrequencyGain, reinject);
  WarnIfOutside(self, units, "Cutoff", given.Cutoff, absolute.Cutoff, ends, consequence);
  if (band)
  {
    WarnIfOutside(
      self, units, "UpperCutoff", given.UpperCutoff, absolute.UpperCutoff, ends, consequence);
  }
}
} // namespace vtkManifoldHarmonicsCutoffs
