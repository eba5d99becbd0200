// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/EigenSolver.h"
#include "Common/Threads.h"
#include "Solver/Bands.h"
#include "Solver/BandWorkspace.h"
#include "Solver/BlockLanczos.h"
#include "Solver/BlockProducts.h"
#include "Solver/Diagnostics.h"
#include "Solver/Factorization.h"
#include "Solver/LanczosKernels.h"
#include "Solver/MassMatrix.h"
#include "Solver/SpectraBand.h"
#include "Solver/Verification.h"

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace spectral
{
namespace
{
using detail::Band;
using detail::BandRequest;
using detail::Clock;
using detail::MassMatrix;
using detail::MultiplyInPlace;
using detail::SecondsSince;
using detail::ShiftedFactor;
using detail::Str;
using detail::Workspace;

/// Eigenpairs accepted so far, ascending: columns [0, Count) of Vectors.
struct Accepted
{
  DenseMatrix Vectors;
  std::vector<double> Values;

  int Count() const { return static_cast<int>(this->Values.size()); }
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
  const int first = accepted.CountBelow(windowLow);
  const int fromAccepted = accepted.Count() - first;
  const Eigen::Index p = fromAccepted + values.size();
  if (p == 0)
  {
    return;
  }
  // The joint span in place: the band's vectors right after the accepted ones.
  if (accepted.Vectors.cols() < accepted.Count() + values.size())
  {
    accepted.Vectors.conservativeResize(Eigen::NoChange, accepted.Count() + 2 * values.size());
  }
  accepted.Vectors.middleCols(accepted.Count(), values.size()) = vectors;
  auto Y = accepted.Vectors.middleCols(first, p);

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

/// All eigenpairs of the dense pencil, then the m smallest.
EigenResult DenseEigenpairs(const SparseMatrix& L, const SparseMatrix& M, int m)
{
  const DenseMatrix Ld(L);
  const DenseMatrix Md(M);
  Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> solver(Ld, Md);
  if (solver.info() != Eigen::Success)
  {
    throw SolverFailure("the dense generalized eigensolver failed (is the mass matrix positive "
                        "definite?)");
  }
  EigenResult result;
  result.Eigenvalues = solver.eigenvalues().head(m);
  result.Eigenvectors = solver.eigenvectors().leftCols(m);
  return result;
}

/**
 * The band-by-band shift-invert Lanczos iteration (see the file documentation) on the pencil
 * (L, M); `area` is the surface area (the sum of the entries of the mass matrix before any
 * scaling).
 */
EigenResult BandEigenpairs(const SparseMatrix& L,
  const MassMatrix& M,
  double area,
  const EigenOptions& options,
  const Monitor& monitor)
{
  const Eigen::Index n = L.rows();
  const int m = options.NumberOfEigenpairs;
  const int bandSize = EffectiveBandSize(m, options.BandSize);
  const int nev =
    static_cast<int>(std::min<Eigen::Index>(std::min(bandSize, SingleBandSize(m)), n / 2));

  EigenResult result;
  Clock::time_point start = Clock::now();
  ShiftedFactor factor(L, M.Matrix, options.Factorization);
  result.Seconds.Factorization += SecondsSince(start);

  // A shift below zero keeps L - sigma M positive definite for the first band. Too near zero it
  // would make the null space dominate the operator by orders of magnitude and cost accuracy
  // elsewhere; 1 / area is below the first non-zero eigenvalue of most shapes (8 pi / area on
  // a sphere) and keeps the two of similar size.
  const double scale = L.diagonal().sum() / M.Matrix.diagonal().sum();
  const double firstShift = -1.0 / area;
  double sigma = firstShift;
  // Every eigenvalue below `proven` is accepted: an inertia count says so. The bands claim the
  // same up to `complete`; the part above `proven` is proven by the next inertia count.
  double proven = -std::numeric_limits<double>::infinity();
  double complete = proven;
  double radius = 0.0;
  double reference = 0.0; // the first non-zero eigenvalue, once known
  Accepted accepted;
  accepted.Vectors.resize(n, m + 2 * nev);
  Workspace work;
  // Progress never moves backwards, whatever a band turns out to add.
  double reported = 0.0;
  const auto report = [&reported, &monitor](double fraction)
  {
    reported = std::max(reported, std::min(1.0, fraction));
    monitor.Report(reported);
  };
  int attempt = 0;
  int gaps = 0;
  int shortBands = 0;   // bands in a row that did not reach down to `complete`
  double meanGap = 0.0; // between eigenvalues, from the last band; 0 before the first

  // After an inertia count disagrees: forget what is not proven and retry with more effort.
  auto rollBack = [&](const std::string& what) {
    if (++attempt > 3)
    {
      throw SolverFailure(what, accepted.CountBelow(proven));
    }
    accepted.Values.resize(accepted.CountBelow(proven));
    complete = proven;
    sigma = std::isfinite(proven) ? proven + 0.5 * radius : firstShift;
  };

  while (true)
  {
    monitor.ThrowIfCancelled();
    start = Clock::now();
    if (accepted.CountBelow(complete) > m)
    {
      // Inertia just above the m-th eigenvalue (past any multiplet) proves the top.
      int j = m;
      while (j < accepted.CountBelow(complete) &&
        !(accepted.Values[j] - accepted.Values[j - 1] > 1e-9 * std::abs(accepted.Values[j])))
      {
        ++j;
      }
      if (j < accepted.CountBelow(complete))
      {
        const double tau = 0.5 * (accepted.Values[j - 1] + accepted.Values[j]);
        if (tau <= proven)
        {
          break;
        }
        if (factor.Factor(tau))
        {
          ++result.Factorizations;
          if (factor.NegativePivots() == j)
          {
            result.Seconds.Verification += SecondsSince(start);
            break;
          }
          rollBack("the inertia of L - sigma M at " + Str(tau) + " counts " +
            std::to_string(factor.NegativePivots()) + " eigenvalues below it, the bands found " +
            std::to_string(j));
          result.Seconds.Verification += SecondsSince(start);
          continue;
        }
        if (++gaps > 8)
        {
          throw SolverFailure("the LDL^T factorization of L - sigma M failed at " + Str(tau),
            accepted.CountBelow(proven));
        }
      }
    }

    if (!factor.Factor(sigma))
    {
      // sigma hit an eigenvalue to working precision: nudge it.
      sigma += 1e-7 * std::max(std::abs(sigma), scale / static_cast<double>(n));
      if (++gaps > 8)
      {
        throw SolverFailure("the LDL^T factorization of L - sigma M failed at shift " + Str(sigma),
          accepted.CountBelow(proven));
      }
      continue;
    }
    ++result.Factorizations;
    result.Seconds.Factorization += SecondsSince(start);

    start = Clock::now();
    Band band;
    if (options.Method == LanczosMethod::Spectra)
    {
      band = detail::RunSpectraBand(
        factor, M.Matrix, BandRequest{ sigma, nev, attempt, reference, meanGap }, options, monitor, work);
      result.Seconds.Solve += SecondsSince(start);
    }
    else
    {
      // Within the band, progress moves across the pairs the band is expected to add.
      const double done = std::min<double>(accepted.CountBelow(complete), m);
      const double share = std::min<double>(0.8 * nev, m - done);
      Monitor bandMonitor;
      bandMonitor.Cancelled = monitor.Cancelled;
      bandMonitor.Progress = [&report, done, share, m](double f)
      { report((done + f * share) / m); };
      try
      {
        band = detail::RunBlockBand(factor, M, BandRequest{ sigma, nev, attempt, reference, meanGap },
          options, bandMonitor, work, result);
      }
      catch (const SolverFailure&)
      {
        // The band stalled: once more from another start vector with a larger subspace.
        if (++attempt > 3)
        {
          throw;
        }
        continue;
      }
      catch (const detail::ShiftTooClose& moved)
      {
        sigma = moved.Suggested;
        if (++gaps > 8)
        {
          throw SolverFailure("no shift near " + Str(sigma) + " is far enough from an eigenvalue",
            accepted.CountBelow(proven));
        }
        continue;
      }
    }
    ++result.Bands;

    start = Clock::now();
    radius = std::max(std::abs(band.Values[0] - sigma),
      std::abs(band.Values[band.Values.size() - 1] - sigma));
    const double slack = 1e-8 * std::max(std::abs(sigma), radius);
    const double low = sigma - radius + slack;
    const double high = sigma + radius - slack;
    if (low >= complete && std::isfinite(complete))
    {
      // The band does not reach down to what is known: move the shift closer and try again.
      // Twice in a row, a cluster of eigenvalues at the seam holds the band's lower edge
      // (eigenvalues at the edge of a band are trusted by neither band): a shift below the
      // seam makes the band reach across it.
      sigma = ++shortBands < 2 ? complete + 0.5 * (sigma - complete) : complete - 0.5 * meanGap;
      if (++gaps > 8)
      {
        throw SolverFailure(
          "the bands do not overlap near " + Str(complete), accepted.CountBelow(proven));
      }
      continue;
    }

    // The trusted pairs, inside (low, high): a range of the ascending band.
    Eigen::Index firstTrusted = 0;
    while (firstTrusted < band.Values.size() && !(band.Values[firstTrusted] > low))
    {
      ++firstTrusted;
    }
    Eigen::Index endTrusted = firstTrusted;
    while (endTrusted < band.Values.size() && band.Values[endTrusted] < high)
    {
      ++endTrusted;
    }
    const Vector trusted = band.Values.segment(firstTrusted, endTrusted - firstTrusted);
    int belowShift = accepted.CountBelow(low);
    for (Eigen::Index i = 0; i < trusted.size(); ++i)
    {
      belowShift += (trusted[i] < sigma) ? 1 : 0;
    }
    if (belowShift != factor.NegativePivots())
    {
      // Sylvester's inertia: this band, or the unproven top of the one before, missed or invented
      // eigenvalues below the shift.
      rollBack("the band at shift " + Str(sigma) + " found " + std::to_string(belowShift) +
        " eigenvalues below the shift, but the inertia of L - sigma M counts " +
        std::to_string(factor.NegativePivots()));
      result.Seconds.Verification += SecondsSince(start);
      continue;
    }
    // Only a band that proves more than before resets the retry counters: a shift moved below
    // the seam may repeat what is proven, and must not keep the bands going round forever.
    if (sigma > proven)
    {
      proven = sigma;
      attempt = 0;
      gaps = 0;
      shortBands = 0;
    }
    if (!(reference > 0.0) && trusted.size() > 0)
    {
      const double top = std::abs(trusted[trusted.size() - 1]);
      for (Eigen::Index i = 0; i < trusted.size(); ++i)
      {
        if (std::abs(trusted[i]) > 1e-6 * top)
        {
          reference = std::abs(trusted[i]);
          break;
        }
      }
    }
    Merge(accepted,
      trusted,
      work.Basis.middleCols(firstTrusted, trusted.size()),
      low - 0.25 * radius,
      L,
      M,
      work);
    complete = std::max(complete, high);
    result.Seconds.RayleighRitz += SecondsSince(start);
    report(static_cast<double>(accepted.CountBelow(complete)) / m);

    // Weyl's law makes the eigenvalue density nearly constant: size the next band from this one.
    const double spread = band.Values[band.Values.size() - 1] - std::max(0.0, band.Values[0]);
    const double density = static_cast<double>(band.Values.size()) / std::max(spread, slack);
    meanGap = 1.0 / density;
    sigma = complete + 0.75 * static_cast<double>(band.Values.size()) / (2.0 * density);
  }

  result.Eigenvalues = Eigen::Map<const Vector>(accepted.Values.data(), m);
  // Hand the accepted block over without a second n x m copy (gigabytes for large meshes).
  accepted.Vectors.conservativeResize(Eigen::NoChange, m);
  result.Eigenvectors = std::move(accepted.Vectors);
  return result;
}

/// Whether M is diagonal with positive finite entries (a lumped mass).
bool IsPositiveDiagonal(const SparseMatrix& M)
{
  Eigen::Index diagonal = 0;
  for (Eigen::Index j = 0; j < M.outerSize(); ++j)
  {
    for (SparseMatrix::InnerIterator it(M, j); it; ++it)
    {
      if (it.row() != it.col())
      {
        if (it.value() != 0.0)
        {
          return false;
        }
      }
      else if (it.value() > 0.0 && std::isfinite(it.value()))
      {
        ++diagonal;
      }
      else
      {
        return false;
      }
    }
  }
  return diagonal == M.rows();
}

/// Phi <- diag(scaling) Phi, a row range per thread.
void ScaleRows(DenseMatrix& Phi, const Vector& scaling)
{
  ForEachRowRange(Phi.rows(),
    BlockThreads(Phi.rows()),
    [&](int, Eigen::Index first, Eigen::Index count)
    {
      for (Eigen::Index k = 0; k < Phi.cols(); ++k)
      {
        Phi.col(k).segment(first, count).array() *= scaling.segment(first, count).array();
      }
    });
}

/// Make the entry of largest magnitude of every column positive.
void NormalizeSigns(DenseMatrix& Phi)
{
  for (Eigen::Index k = 0; k < Phi.cols(); ++k)
  {
    Eigen::Index row = 0;
    Phi.col(k).cwiseAbs().maxCoeff(&row);
    if (Phi(row, k) < 0.0)
    {
      Phi.col(k) *= -1.0;
    }
  }
}
} // namespace

//------------------------------------------------------------------------------
EigenResult SmallestEigenpairs(
  const SparseMatrix& L, const SparseMatrix& M, const EigenOptions& options, const Monitor& monitor)
{
  const Eigen::Index n = L.rows();
  const int m = options.NumberOfEigenpairs;
  if (L.cols() != n || M.rows() != n || M.cols() != n)
  {
    throw InvalidInput("the stiffness and mass matrices must be square and of the same size");
  }
  if (m < 1 || m > n)
  {
    throw InvalidInput("cannot compute " + std::to_string(m) + " eigenpairs of a problem with " +
      std::to_string(n) + " unknowns: ask for 1 to " + std::to_string(n));
  }
  monitor.Report(0.0);
  EigenResult result;
  if (n <= options.DenseThreshold || 3 * static_cast<Eigen::Index>(m) > n)
  {
    if (n > 20000)
    {
      throw InvalidInput("asking for " + std::to_string(m) + " eigenpairs of " +
        std::to_string(n) + " unknowns needs a dense solve; ask for at most n/3");
    }
    monitor.ThrowIfCancelled();
    const Clock::time_point start = Clock::now();
    result = DenseEigenpairs(L, M, m);
    result.Seconds.RayleighRitz = SecondsSince(start);
  }
  else
  {
    const double area = M.sum();
    if (IsPositiveDiagonal(M))
    {
      // Q h = lambda D h with a diagonal D is the standard problem S y = lambda y with
      // S = D^-1/2 Q D^-1/2 and y = D^1/2 h: the same eigenvalues, the same inertia of every
      // shifted matrix (a congruence), and the D inner product of the iteration becomes the
      // Euclidean one, which saves a sparse product with D for every product of the iteration.
      const Vector scaling = M.diagonal().cwiseSqrt().cwiseInverse();
      const SparseMatrix S = scaling.asDiagonal() * L * scaling.asDiagonal();
      SparseMatrix identity(n, n);
      identity.setIdentity();
      result = BandEigenpairs(S, MassMatrix{ identity, true }, area, options, monitor);
      ScaleRows(result.Eigenvectors, scaling);
    }
    else
    {
      result = BandEigenpairs(L, MassMatrix{ M, false }, area, options, monitor);
    }
  }
  NormalizeSigns(result.Eigenvectors);
  detail::CheckResiduals(L, M, options.ResidualTolerance, result);
  monitor.Report(1.0);
  return result;
}
} // namespace spectral
