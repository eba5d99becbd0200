// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/Bands.h"
#include "Common/Eigenvalues.h"
#include "Solver/BandWorkspace.h"
#include "Solver/BlockLanczos.h"
#include "Solver/BlockProducts.h"
#include "Solver/Diagnostics.h"
#include "Solver/Factorization.h"
#include "Solver/LanczosKernels.h"
#include "Solver/MassMatrix.h"
#include "Solver/SpectraBand.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace spectral
{
//------------------------------------------------------------------------------
int SingleBandSize(int m)
{
  return m + m / 4 + 10;
}

//------------------------------------------------------------------------------
int EffectiveBandSize(int m, int bandSize)
{
  if (bandSize > 0)
  {
    return bandSize;
  }
  // Up to 160 pairs one band beats two bands of 100: on the benchmark tori, m = 100 took 0.38 s
  // instead of 0.54 s (10K points) and 4.0 s instead of 5.5 s (100K); m = 150 in one band of 197
  // was slower than in two (0.66 s against 0.54 s).
  const int single = SingleBandSize(m);
  return single <= 160 ? single : 100;
}

namespace detail
{
//------------------------------------------------------------------------------
int RetryPairs(int pairs, int attempt)
{
  return attempt <= 0 ? pairs : std::max(1, 2 * pairs / (attempt + 2));
}

//------------------------------------------------------------------------------
int BandReturnPairs(int m, int nev, int pairs)
{
  return std::max(1, nev >= SingleBandSize(m) ? (4 * pairs) / 5 : (9 * pairs) / 10);
}

//------------------------------------------------------------------------------
int PairsPerBand(int m, int bandSize, Eigen::Index n)
{
  return static_cast<int>(
    std::min<Eigen::Index>(std::min(EffectiveBandSize(m, bandSize), SingleBandSize(m)), n / 2));
}

namespace
{

/// Eigenpairs accepted so far, ascending. The first Retired are final: no later band merges
/// them again (RetireOldVectors), whether their vectors are kept or not, so that a basis kept in
/// memory and one streamed out (EigenOptions::KeepEigenvectors false) are the same computation.
/// Without KeepEigenvectors the vectors of the retired values are let go (verified) and Dropped
/// == Retired; with it Dropped stays 0. Column j of Vectors is the vector of value Dropped + j.
struct Accepted
{
  DenseMatrix Vectors;
  std::vector<double> Values;
  int Retired = 0;
  int Dropped = 0;
  /// The first Fixed pairs are the null vectors of MassMatrix::Deflation, known in advance: no
  /// merge changes them. Their values are the Rayleigh quotients of the null vectors (0 up to
  /// the rounding of L), where every inertia count of L as rounded sees them, until Run returns
  /// them as exactly 0.
  int Fixed = 0;
  /// Between the last retired value and the first kept one; -infinity while none is retired.
  double RetiredBelow = -std::numeric_limits<double>::infinity();

  int Count() const { return static_cast<int>(this->Values.size()); }
  /// Number of values whose vectors are kept.
  int Kept() const { return this->Count() - this->Dropped; }
  /// Number of values that later bands may still merge.
  int Active() const { return this->Count() - this->Retired; }
  int CountBelow(double x) const
  {
    return static_cast<int>(
      std::lower_bound(this->Values.begin(), this->Values.end(), x) - this->Values.begin());
  }
};

/**
 * Merge the trusted vectors of a band into the accepted set. The accepted vectors with
 * eigenvalue >= windowLow and the band's vectors span the eigenspaces of the overlap; a
 * Rayleigh-Ritz step on the rank-revealed joint span replaces them, so a direction found by both
 * bands is kept once, and a multiple eigenvalue split by the seam is kept whole.
 */
void Merge(Accepted& accepted,
  const Vector& values,
  const Eigen::Ref<const DenseMatrix>& vectors,
  double windowLow,
  const SparseMatrix& L,
  const MassMatrix& M,
  Workspace& work)
{
  const int first = std::max({ accepted.CountBelow(windowLow), accepted.Retired, accepted.Fixed });
  const int fromAccepted = accepted.Count() - first;
  const Eigen::Index p = fromAccepted + values.size();
  if (p == 0)
  {
    return;
  }
  // The joint span in place: the band's vectors right after the accepted ones.
  if (accepted.Vectors.cols() < accepted.Kept() + values.size())
  {
    accepted.Vectors.conservativeResize(Eigen::NoChange, accepted.Kept() + 2 * values.size());
  }
  accepted.Vectors.middleCols(accepted.Kept(), values.size()) = vectors;
  auto Y = accepted.Vectors.middleCols(first - accepted.Dropped, p);

  DenseMatrix G = M.Identity ? TransposeProduct(Y, Y) : TransposeProduct(Y, M.Matrix * Y);
  auto LY = Workspace::Columns(work.Image, Y.rows(), p);
  SymmetricSparseProduct(L, Y, LY);
  DenseMatrix S = TransposeProduct(Y, LY);
  G = 0.5 * (G + G.transpose()).eval();
  S = 0.5 * (S + S.transpose()).eval();

  Eigen::SelfAdjointEigenSolver<DenseMatrix> gram(G);
  const Vector& g = gram.eigenvalues();
  const double keep = 1e-8 * g.maxCoeff();
  std::vector<int> columns;
  for (Eigen::Index i = 0; i < g.size(); ++i)
  {
    if (g[i] > keep)
    {
      columns.push_back(static_cast<int>(i));
    }
  }
  DenseMatrix C1(p, columns.size());
  for (std::size_t j = 0; j < columns.size(); ++j)
  {
    C1.col(j) = gram.eigenvectors().col(columns[j]) / std::sqrt(g[columns[j]]);
  }
  DenseMatrix T = C1.transpose() * S * C1;
  T = 0.5 * (T + T.transpose()).eval();
  Eigen::SelfAdjointEigenSolver<DenseMatrix> ritz(T);
  MultiplyInPlace(Y, C1 * ritz.eigenvectors());
  accepted.Values.resize(first);
  for (Eigen::Index i = 0; i < ritz.eigenvalues().size(); ++i)
  {
    accepted.Values.push_back(ritz.eigenvalues()[i]);
  }
}

/// What the loop over bands does next.
enum class Step
{
  Proceed,  ///< go on with this iteration
  Again,    ///< start the next iteration (a new shift, or a retry)
  Finished, ///< the m smallest eigenpairs are proven
};

/// The loop over bands: its shifts, what is accepted and proven so far, and its retry counters.
class BandLoop
{
public:
  BandLoop(const SparseMatrix& L,
    const MassMatrix& M,
    double area,
    const EigenOptions& options,
    const Monitor& monitor,
    const RetirePairs& retire);

  /// Run bands until the m smallest eigenpairs are proven; \return them.
  EigenResult Run();

private:
  void AcceptNullVectors();
  Step ProveTop();
  bool FactorAtShift();
  bool RunBand(Band& band);
  void AcceptBand(const Band& band);
  bool InertiaAgrees(const Vector& trusted, double low);
  void UpdateReference(const Vector& trusted);
  void Retire(int end);
  void RetireOldVectors();
  void RollBack(const std::string& what);
  void Report(double fraction);
  void CountFailure(const std::string& what);

  const SparseMatrix& L;
  const MassMatrix& M;
  const EigenOptions& Options;
  const Monitor& Watch;
  const Eigen::Index N;
  const int Count; ///< m
  const int Nev;
  /// The eigenvalues below StartValue, counted as found (EigenOptions::StartIndex).
  const int Offset;
  const RetirePairs& RetireCheck;

  EigenResult Result;
  Clock::time_point Start;
  ShiftedFactor Factor;
  /// The scale of the operator: trace(L) / trace(M).
  const double Scale;
  const double FirstShift;
  double Sigma;
  /// Every eigenvalue below Proven is accepted: an inertia count says so. The bands claim the
  /// same up to Complete; the part above Proven is proven by the next inertia count.
  double Proven = -std::numeric_limits<double>::infinity();
  double Complete = -std::numeric_limits<double>::infinity();
  double Radius = 0.0;
  double Reference = 0.0; ///< the first non-zero eigenvalue, once known
  Accepted AcceptedPairs;
  Workspace Work;
  double Reported = 0.0; ///< progress never moves backwards, whatever a band turns out to add
  int Attempt = 0;
  int Gaps = 0;
  int ShortBands = 0;   ///< bands in a row that did not reach down to Complete
  double MeanGap = 0.0; ///< between eigenvalues, from the last band; 0 before the first
};

//------------------------------------------------------------------------------
BandLoop::BandLoop(const SparseMatrix& L,
  const MassMatrix& M,
  double area,
  const EigenOptions& options,
  const Monitor& monitor,
  const RetirePairs& retire)
  : L(L)
  , M(M)
  , Options(options)
  , Watch(monitor)
  , N(L.rows())
  , Count(options.NumberOfEigenpairs)
  , Nev(PairsPerBand(options.NumberOfEigenpairs, options.BandSize, L.rows()))
  , Offset(options.StartIndex)
  , RetireCheck(retire)
  , Start(Clock::now())
  , Factor(L, M.Matrix, options.Factorization)
  , Scale(L.diagonal().sum() / M.Matrix.diagonal().sum())
  // A shift below zero keeps L - sigma M positive definite for the first band. Too near zero it
  // would make the null space dominate the operator by orders of magnitude and cost accuracy
  // elsewhere; 1 / area is below the first non-zero eigenvalue of most shapes (8 pi / area on
  // a sphere) and keeps the two of similar size.
  , FirstShift(-1.0 / area)
  , Sigma(this->FirstShift)
{
  this->Result.Seconds.Factorization += SecondsSince(this->Start);
  const int columns = this->Count + 2 * this->Nev;
  this->AcceptedPairs.Vectors.resize(
    this->N, this->Options.KeepEigenvectors ? columns : std::min(columns, 3 * this->Nev));
  if (this->Offset == 0 && M.Deflation && M.Deflation->cols() > 0)
  {
    this->AcceptNullVectors();
  }
  if (this->Offset > 0)
  {
    // What lies below StartValue is proven by the caller; the bands start above it, from the
    // density of the eigenvalues below (Weyl's law).
    this->Proven = this->Complete = options.StartValue;
    this->MeanGap = options.StartValue / this->Offset;
    this->Sigma = options.StartValue + 0.375 * this->Nev * this->MeanGap;
  }
}

//------------------------------------------------------------------------------
// The null vectors of M.Deflation become the first accepted pairs (Accepted::Fixed), at their
// Rayleigh quotients z^T L z.
void BandLoop::AcceptNullVectors()
{
  const DenseMatrix& Z = *this->M.Deflation;
  const Eigen::Index k = std::min<Eigen::Index>(Z.cols(), this->Count);
  const Vector quotients = (Z.leftCols(k).transpose() * (this->L * Z.leftCols(k))).diagonal();
  for (Eigen::Index j = 0; j < k; ++j)
  {
    this->AcceptedPairs.Vectors.col(j) = Z.col(j);
    this->AcceptedPairs.Values.push_back(quotients[j]);
  }
  std::sort(this->AcceptedPairs.Values.begin(), this->AcceptedPairs.Values.end());
  this->AcceptedPairs.Fixed = static_cast<int>(k);
}

//------------------------------------------------------------------------------
EigenResult BandLoop::Run()
{
  while (true)
  {
    this->Watch.ThrowIfCancelled();
    this->Start = Clock::now();
    const Step top = this->ProveTop();
    if (top == Step::Finished)
    {
      break;
    }
    if (top == Step::Again || !this->FactorAtShift())
    {
      continue;
    }
    Band band;
    if (!this->RunBand(band))
    {
      continue;
    }
    ++this->Result.Bands;
    this->AcceptBand(band);
  }
  this->Result.Eigenvalues =
    Eigen::Map<const Vector>(this->AcceptedPairs.Values.data(), this->Count);
  this->Result.Eigenvalues.head(this->AcceptedPairs.Fixed).setZero();
  if (!this->Options.KeepEigenvectors)
  {
    this->Retire(this->Count);
    this->Result.Eigenvectors.resize(0, 0);
    return std::move(this->Result);
  }
  // Hand the accepted block over without a second n x m copy (gigabytes for large meshes).
  this->AcceptedPairs.Vectors.conservativeResize(Eigen::NoChange, this->Count);
  this->Result.Eigenvectors = std::move(this->AcceptedPairs.Vectors);
  return std::move(this->Result);
}

//------------------------------------------------------------------------------
// Make the accepted pairs below index `end` final; without KeepEigenvectors, verify them and let
// their vectors go.
void BandLoop::Retire(int end)
{
  Accepted& accepted = this->AcceptedPairs;
  const int count = std::min(end, accepted.Count()) - accepted.Retired;
  if (count <= 0)
  {
    return;
  }
  if (!this->Options.KeepEigenvectors)
  {
    const Vector values =
      Eigen::Map<const Vector>(accepted.Values.data() + accepted.Retired, count);
    this->RetireCheck(values, accepted.Vectors.leftCols(count), accepted.Retired, this->Result);
    const int kept = accepted.Kept() - count;
    for (int j = 0; j < kept; ++j)
    {
      accepted.Vectors.col(j) = accepted.Vectors.col(count + j);
    }
    accepted.Dropped += count;
  }
  accepted.Retired += count;
  accepted.RetiredBelow = accepted.Retired < accepted.Count()
    ? 0.5 * (accepted.Values[accepted.Retired - 1] + accepted.Values[accepted.Retired])
    : accepted.Values[accepted.Retired - 1];
}

//------------------------------------------------------------------------------
// Once more than two bands' worth of pairs are active, retire those a band below what is
// proven, at a gap of the spectrum (a multiple eigenvalue stays whole): the same pairs with and
// without KeepEigenvectors, which decides only whether their vectors are kept (Retire).
void BandLoop::RetireOldVectors()
{
  const Accepted& accepted = this->AcceptedPairs;
  if (accepted.Active() <= 2 * this->Nev)
  {
    return;
  }
  int end = std::min(accepted.CountBelow(this->Proven), this->Count) - this->Nev;
  while (end > accepted.Retired &&
    !(accepted.Values[end] - accepted.Values[end - 1] > 1e-6 * std::abs(accepted.Values[end])))
  {
    --end;
  }
  if (end > accepted.Retired)
  {
    this->Retire(end);
  }
}

//------------------------------------------------------------------------------
// Once more than m pairs are complete, the inertia just above the m-th eigenvalue (past any
// multiplet) proves the top.
Step BandLoop::ProveTop()
{
  const Accepted& accepted = this->AcceptedPairs;
  if (accepted.CountBelow(this->Complete) <= this->Count)
  {
    return Step::Proceed;
  }
  int j = this->Count;
  while (j < accepted.CountBelow(this->Complete) &&
    !(accepted.Values[j] - accepted.Values[j - 1] > 1e-9 * std::abs(accepted.Values[j])))
  {
    ++j;
  }
  if (j >= accepted.CountBelow(this->Complete))
  {
    return Step::Proceed;
  }
  const double tau = 0.5 * (accepted.Values[j - 1] + accepted.Values[j]);
  if (tau <= this->Proven)
  {
    return Step::Finished;
  }
  j += this->Offset;
  if (!this->Factor.Factor(tau))
  {
    this->CountFailure("the LDL^T factorization of L - sigma M failed at " + Str(tau));
    return Step::Proceed;
  }
  ++this->Result.Factorizations;
  const int below = this->Factor.NegativePivots();
  if (below != j)
  {
    this->RollBack("the inertia of L - sigma M at " + Str(tau) + " counts " +
      std::to_string(below) + " eigenvalues below it, the bands found " + std::to_string(j));
  }
  this->Result.Seconds.Verification += SecondsSince(this->Start);
  return below == j ? Step::Finished : Step::Again;
}

//------------------------------------------------------------------------------
// Factor L - sigma M at the band's shift; false (and a nudged shift) where it fails.
bool BandLoop::FactorAtShift()
{
  if (!this->Factor.Factor(this->Sigma))
  {
    // sigma hit an eigenvalue to working precision: nudge it.
    this->Sigma +=
      1e-7 * std::max(std::abs(this->Sigma), this->Scale / static_cast<double>(this->N));
    this->CountFailure(
      "the LDL^T factorization of L - sigma M failed at shift " + Str(this->Sigma));
    return false;
  }
  ++this->Result.Factorizations;
  this->Result.Seconds.Factorization += SecondsSince(this->Start);
  return true;
}

//------------------------------------------------------------------------------
// One band at the shift; false where it must be run again (another start, another shift).
bool BandLoop::RunBand(Band& band)
{
  this->Start = Clock::now();
  const int pairs = RetryPairs(this->Nev, this->Attempt);
  const BandRequest request{ this->Sigma,
    pairs,
    this->Attempt,
    this->Reference,
    this->MeanGap,
    this->Nev,
    BandReturnPairs(this->Count, this->Nev, pairs) };
  if (this->Options.Method == LanczosMethod::Spectra)
  {
    band = RunSpectraBand(this->Factor, this->M, request, this->Options, this->Watch, this->Work);
    this->Result.Seconds.Solve += SecondsSince(this->Start);
    return true;
  }
  // Within the band, progress moves across the pairs the band is expected to add.
  const int m = this->Count;
  const double done = std::min<double>(this->AcceptedPairs.CountBelow(this->Complete), m);
  const double share = std::min<double>(0.8 * this->Nev, m - done);
  Monitor bandMonitor;
  bandMonitor.Cancelled = this->Watch.Cancelled;
  bandMonitor.Progress = [this, done, share, m](double f) { this->Report((done + f * share) / m); };
  try
  {
    band = RunBlockBand(
      this->Factor, this->M, request, this->Options, bandMonitor, this->Work, this->Result);
  }
  catch (const SolverFailure&)
  {
    // The band stalled: once more from another start vector, fewer pairs in the same subspace.
    if (++this->Attempt > 3)
    {
      throw;
    }
    ++this->Result.Retries;
    return false;
  }
  catch (const ShiftTooClose& moved)
  {
    // Half a mean gap away from that eigenvalue, on the shift's side; where that was tried and
    // met another eigenvalue (two of them half a gap apart made the shift go back and forth),
    // other fractions of the gap.
    static constexpr double Fractions[] = { 0.5, 0.3, 0.7, 0.2 };
    const double fraction = Fractions[this->Gaps % 4];
    this->Sigma = moved.Eigenvalue + moved.Side * fraction * this->MeanGap;
    this->CountFailure("no shift near " + Str(this->Sigma) + " is far enough from an eigenvalue");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
// Keep the band's trusted pairs if the inertia at its shift agrees, and place the next shift.
void BandLoop::AcceptBand(const Band& band)
{
  this->Start = Clock::now();
  const Vector& values = band.Values;
  this->Radius =
    std::max(std::abs(values[0] - this->Sigma), std::abs(values[values.size() - 1] - this->Sigma));
  const double slack = 1e-8 * std::max(std::abs(this->Sigma), this->Radius);
  const double low = this->Sigma - this->Radius + slack;
  const double high = this->Sigma + this->Radius - slack;
  if (low >= this->Complete && std::isfinite(this->Complete))
  {
    // The band does not reach down to what is known: move the shift closer and try again.
    // Twice in a row, a cluster of eigenvalues at the seam holds the band's lower edge
    // (eigenvalues at the edge of a band are trusted by neither band): a shift below the
    // seam makes the band reach across it.
    this->Sigma = ++this->ShortBands < 2 ? this->Complete + 0.5 * (this->Sigma - this->Complete)
                                         : this->Complete - 0.5 * this->MeanGap;
    this->CountFailure("the bands do not overlap near " + Str(this->Complete));
    return;
  }
  // The trusted pairs, inside (low, high) and not below StartValue: a range of the ascending
  // band.
  const double floor = this->Offset > 0 ? this->Options.StartValue : low;
  Eigen::Index firstTrusted = 0;
  while (
    firstTrusted < values.size() && !(values[firstTrusted] > low && values[firstTrusted] >= floor))
  {
    ++firstTrusted;
  }
  Eigen::Index endTrusted = firstTrusted;
  while (endTrusted < values.size() && values[endTrusted] < high)
  {
    ++endTrusted;
  }
  const Vector trusted = values.segment(firstTrusted, endTrusted - firstTrusted);
  if (!this->InertiaAgrees(trusted, low))
  {
    return;
  }
  this->UpdateReference(trusted);
  // Pairs below the retired vectors are already accepted (values only): not merged again.
  Eigen::Index skip = 0;
  while (skip < trusted.size() && trusted[skip] < this->AcceptedPairs.RetiredBelow)
  {
    ++skip;
  }
  Merge(this->AcceptedPairs,
    trusted.tail(trusted.size() - skip),
    this->Work.Basis.middleCols(firstTrusted + skip, trusted.size() - skip),
    low - 0.25 * this->Radius,
    this->L,
    this->M,
    this->Work);
  this->Result.MostKeptVectors =
    std::max(this->Result.MostKeptVectors, static_cast<int>(this->AcceptedPairs.Vectors.cols()));
  this->Complete = std::max(this->Complete, high);
  this->Result.Seconds.RayleighRitz += SecondsSince(this->Start);
  this->Report(static_cast<double>(this->AcceptedPairs.CountBelow(this->Complete)) / this->Count);

  // Weyl's law makes the eigenvalue density nearly constant: size the next band from this one.
  const double spread = values[values.size() - 1] - std::max(0.0, values[0]);
  const double density = static_cast<double>(values.size()) / std::max(spread, slack);
  this->MeanGap = 1.0 / density;
  this->Sigma = this->Complete + 0.75 * static_cast<double>(values.size()) / (2.0 * density);
  this->RetireOldVectors();
}

//------------------------------------------------------------------------------
// Sylvester's inertia: the accepted eigenvalues below `low` and the trusted ones below the shift
// must be as many as the negative pivots at the shift. Where they agree the shift is proven;
// where they do not, this band, or the unproven top of the one before, missed or invented
// eigenvalues below the shift: roll back.
bool BandLoop::InertiaAgrees(const Vector& trusted, double low)
{
  const Accepted& accepted = this->AcceptedPairs;
  int belowShift = this->Offset + accepted.CountBelow(low);
  for (Eigen::Index i = 0; i < trusted.size(); ++i)
  {
    belowShift += (trusted[i] < this->Sigma) ? 1 : 0;
  }
  // The known null pairs are no band's: they count wherever they lie below the shift.
  for (int j = 0; j < accepted.Fixed; ++j)
  {
    belowShift += (accepted.Values[j] >= low && accepted.Values[j] < this->Sigma) ? 1 : 0;
  }
  if (belowShift != this->Factor.NegativePivots())
  {
    this->RollBack("the band at shift " + Str(this->Sigma) + " found " +
      std::to_string(belowShift) + " eigenvalues below the shift, but the inertia of L - sigma M " +
      "counts " + std::to_string(this->Factor.NegativePivots()));
    this->Result.Seconds.Verification += SecondsSince(this->Start);
    return false;
  }
  // Only a band that proves more than before resets the retry counters: a shift moved below
  // the seam may repeat what is proven, and must not keep the bands going round forever.
  if (this->Sigma > this->Proven)
  {
    this->Proven = this->Sigma;
    this->Attempt = 0;
    this->Gaps = 0;
    this->ShortBands = 0;
  }
  return true;
}

//------------------------------------------------------------------------------
// The first non-zero eigenvalue (IsZeroEigenvalue with the band's largest as the scale), once a
// band has found it.
void BandLoop::UpdateReference(const Vector& trusted)
{
  if (!(this->Reference > 0.0) && trusted.size() > 0)
  {
    const double top = std::abs(trusted[trusted.size() - 1]);
    for (Eigen::Index i = 0; i < trusted.size(); ++i)
    {
      if (!IsZeroEigenvalue(std::abs(trusted[i]), top))
      {
        this->Reference = std::abs(trusted[i]);
        break;
      }
    }
  }
}

//------------------------------------------------------------------------------
// After an inertia count disagrees: forget what is not proven and retry with more effort.
void BandLoop::RollBack(const std::string& what)
{
  if (++this->Attempt > 3)
  {
    throw SolverFailure(what, this->AcceptedPairs.CountBelow(this->Proven));
  }
  ++this->Result.Retries;
  this->AcceptedPairs.Values.resize(
    std::max(this->AcceptedPairs.Fixed, this->AcceptedPairs.CountBelow(this->Proven)));
  this->Complete = this->Proven;
  this->Sigma = std::isfinite(this->Proven) ? this->Proven + 0.5 * this->Radius : this->FirstShift;
}

//------------------------------------------------------------------------------
void BandLoop::Report(double fraction)
{
  this->Reported = std::max(this->Reported, std::min(1.0, fraction));
  this->Watch.Report(this->Reported);
}

//------------------------------------------------------------------------------
// A shift that could not be used: at most 8 in a row before the solve fails with `what`.
void BandLoop::CountFailure(const std::string& what)
{
  if (++this->Gaps > 8)
  {
    throw SolverFailure(what, this->AcceptedPairs.CountBelow(this->Proven));
  }
}
} // namespace

//------------------------------------------------------------------------------
EigenResult BandEigenpairs(const SparseMatrix& L,
  const MassMatrix& M,
  double area,
  const EigenOptions& options,
  const Monitor& monitor,
  const RetirePairs& retire)
{
  return BandLoop(L, M, area, options, monitor, retire).Run();
}
} // namespace detail
} // namespace spectral
