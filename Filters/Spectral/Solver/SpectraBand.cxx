// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/SpectraBand.h"
#include "Solver/Diagnostics.h"

#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace spectral
{
namespace detail
{
namespace
{
/// Spectra operation y = (L - sigma M)^-1 x on a ShiftedFactor, M-orthogonal to the null vectors
/// of M.Deflation; polls for cancellation.
class ShiftInvertOp
{
public:
  using Scalar = double;

  ShiftInvertOp(const ShiftedFactor& factor,
    const MassMatrix& M,
    const Monitor& monitor,
    Eigen::Index n)
    : Factor(factor)
    , Mass(M)
    , Watch(monitor)
    , Size(n)
    , In(n, 1)
  {
  }
  Eigen::Index rows() const { return this->Size; }
  Eigen::Index cols() const { return this->Size; }
  /// The factorization is made before the solver starts; nothing to do here.
  void set_shift(const Scalar&) {}
  void perform_op(const Scalar* xIn, Scalar* yOut) const
  {
    this->Watch.ThrowIfCancelled();
    this->In = Eigen::Map<const Vector>(xIn, this->Size);
    this->In = this->Factor.SolveBlock(this->In);
    this->Mass.Deflate(this->In);
    Eigen::Map<Vector>(yOut, this->Size) = this->In.col(0);
  }

private:
  const ShiftedFactor& Factor;
  const MassMatrix& Mass;
  const Monitor& Watch;
  Eigen::Index Size;
  mutable DenseMatrix In;
};

/// Spectra operation y = M x.
class MassOp
{
public:
  using Scalar = double;

  explicit MassOp(const SparseMatrix& M)
    : Mass(M)
  {
  }
  Eigen::Index rows() const { return this->Mass.rows(); }
  Eigen::Index cols() const { return this->Mass.cols(); }
  void perform_op(const Scalar* xIn, Scalar* yOut) const
  {
    Eigen::Map<Vector>(yOut, this->Mass.rows()) =
      this->Mass * Eigen::Map<const Vector>(xIn, this->Mass.cols());
  }

private:
  const SparseMatrix& Mass;
};

using ShiftInvertSolver =
  Spectra::SymGEigsShiftSolver<ShiftInvertOp, MassOp, Spectra::GEigsMode::ShiftInvert>;

/// Start attempt 0 from Spectra's default vector, later attempts (and every attempt with null
/// vectors, which the start must be M-orthogonal to) from other random vectors.
void StartSolver(ShiftInvertSolver& eigs, const MassMatrix& M, Eigen::Index n, int attempt)
{
  if (attempt == 0 && !M.Deflation)
  {
    eigs.init();
    return;
  }
  std::mt19937 generator(12345u + static_cast<unsigned>(attempt));
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  DenseMatrix start(n, 1);
  for (Eigen::Index i = 0; i < n; ++i)
  {
    start(i, 0) = uniform(generator);
  }
  M.Deflate(start);
  eigs.init(start.data());
}

/// The converged pairs of `eigs`, ascending: values returned, vectors into work.Basis.
Band SortedPairs(const ShiftInvertSolver& eigs, Eigen::Index n, Workspace& work)
{
  const Vector values = eigs.eigenvalues();
  const DenseMatrix vectors = eigs.eigenvectors();
  std::vector<int> order(values.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    order[i] = static_cast<int>(i);
  }
  std::sort(order.begin(), order.end(), [&values](int a, int b) { return values[a] < values[b]; });
  Band sorted{ Vector(values.size()) };
  auto out = Workspace::Columns(work.Basis, n, values.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    sorted.Values[i] = values[order[i]];
    out.col(i) = vectors.col(order[i]);
  }
  return sorted;
}
} // namespace

//------------------------------------------------------------------------------
Band RunSpectraBand(const ShiftedFactor& factor,
  const MassMatrix& M,
  const BandRequest& request,
  const EigenOptions& options,
  const Monitor& monitor,
  Workspace& work)
{
  const Eigen::Index n = M.Matrix.rows();
  const int nev = request.Pairs;
  // The subspace of the loop's band (BandRequest::SubspacePairs) at every attempt: a retry asks
  // for fewer pairs in it.
  const int sized = std::max(nev, request.SubspacePairs);
  const int ncv = static_cast<int>(std::min<Eigen::Index>(n, std::max(2 * sized + 1, sized + 20)));
  ShiftInvertOp op(factor, M, monitor, n);
  MassOp mass(M.Matrix);
  ShiftInvertSolver eigs(op, mass, nev, ncv, request.Sigma);
  StartSolver(eigs, M, n, request.Attempt);
  const Eigen::Index converged = eigs.compute(Spectra::SortRule::LargestMagn,
    options.MaxIterations,
    options.Tolerance,
    Spectra::SortRule::SmallestAlge);
  if (eigs.info() != Spectra::CompInfo::Successful || converged < nev)
  {
    throw SolverFailure("the Lanczos iteration of the band at shift " + Str(request.Sigma) +
        " converged for " + std::to_string(converged) + " of " + std::to_string(nev) +
        " eigenpairs in " + std::to_string(options.MaxIterations) +
        " restarts; raise MaxIterations or loosen Tolerance",
      static_cast<int>(converged));
  }
  return SortedPairs(eigs, n, work);
}
} // namespace detail
} // namespace spectral
