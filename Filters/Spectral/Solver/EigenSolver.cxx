// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/EigenSolver.h"
#include "Common/Threads.h"
#include "Solver/Bands.h"
#include "Solver/BlockProducts.h"
#include "Solver/Diagnostics.h"
#include "Solver/Factorization.h"
#include "Solver/Verification.h"

#include <Eigen/Dense>
#include <Spectra/SymGEigsShiftSolver.h>

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
using detail::Clock;
using detail::SecondsSince;
using detail::ShiftedFactor;
using detail::Str;
using detail::Verify;

/// Spectra operation y = (L - sigma M)^-1 x on a ShiftedFactor; polls for cancellation.
class ShiftInvertOp
{
public:
  using Scalar = double;

  ShiftInvertOp(const ShiftedFactor& factor, const Monitor& monitor, Eigen::Index n)
    : Factor(factor)
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
    Eigen::Map<Vector>(yOut, this->Size) = this->Factor.SolveBlock(this->In);
  }

private:
  const ShiftedFactor& Factor;
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

/// Thrown by a band whose shift lies too close to an eigenvalue; holds a better shift.
struct ShiftTooClose
{
  double Suggested;
};

/**
 * The mass matrix of the pencil in the products of the block iteration. A positive diagonal mass
 * (the lumped one) is scaled away before the iteration (SmallestEigenpairs): the pencil becomes
 * (D^-1/2 L D^-1/2, I), and Identity skips every product with it.
 */
struct MassMatrix
{
  const SparseMatrix& Matrix;
  bool Identity;

  /// M W in `out`; W itself (no copy) for the identity.
  const DenseMatrix& Times(const DenseMatrix& W, DenseMatrix& out) const
  {
    if (this->Identity)
    {
      return W;
    }
    out.noalias() = this->Matrix * W;
    return out;
  }

  /// Not for blocks or expressions: they would bind to a temporary copy, which the identity
  /// case would return.
  template<typename Other>
  const DenseMatrix& Times(const Other& W, DenseMatrix& out) const = delete;
};

/// Eigenvalues of one band, sorted ascending; the vectors are the first columns of
/// Workspace::Basis.
struct Band
{
  Vector Values;
};

/**
 * Tall matrices kept from band to band. A fresh n-row matrix costs a page fault and the clearing
 * of a page for every 4 KB it touches first: with a new basis, Ritz vectors and merge products
 * for every band, a tenth of the run time on a 100,000-point mesh.
 */
struct Workspace
{
  DenseMatrix Basis; ///< the Lanczos basis of a band, then the band's vectors in its first columns
  DenseMatrix Image; ///< (L - sigma M) X for Ritz vectors X, or L Y in the band merge

  /// The first `cols` columns of A, resized to `rows` x `cols` only when it is too small.
  static Eigen::Block<DenseMatrix, Eigen::Dynamic, Eigen::Dynamic, true> Columns(DenseMatrix& A,
    Eigen::Index rows,
    Eigen::Index cols)
  {
    if (A.rows() != rows || A.cols() < cols)
    {
      A.resize(rows, cols);
    }
    return A.leftCols(cols);
  }
};

/**
 * The nev eigenpairs nearest sigma with Spectra's shift-invert Lanczos in the M inner product.
 * Attempt 0 starts from Spectra's default vector, later attempts from other random vectors and
 * with a larger subspace. \throws SolverFailure if the band does not converge.
 */
Band RunBand(const ShiftInvertOp& op,
  const MassOp& mass,
  double sigma,
  int nev,
  int attempt,
  const EigenOptions& options,
  Workspace& work)
{
  const Eigen::Index n = op.rows();
  const int ncv = static_cast<int>(
    std::min<Eigen::Index>(n, std::max(2 * nev + 1, nev + 20) + attempt * nev));
  ShiftInvertOp opCopy = op;
  MassOp massCopy = mass;
  Spectra::SymGEigsShiftSolver<ShiftInvertOp, MassOp, Spectra::GEigsMode::ShiftInvert> eigs(
    opCopy, massCopy, nev, ncv, sigma);
  if (attempt == 0)
  {
    eigs.init();
  }
  else
  {
    std::mt19937 generator(12345u + static_cast<unsigned>(attempt));
    std::uniform_real_distribution<double> uniform(-0.5, 0.5);
    Vector start(n);
    for (Eigen::Index i = 0; i < n; ++i)
    {
      start[i] = uniform(generator);
    }
    eigs.init(start.data());
  }
  const Eigen::Index converged = eigs.compute(Spectra::SortRule::LargestMagn,
    options.MaxIterations, options.Tolerance, Spectra::SortRule::SmallestAlge);
  if (eigs.info() != Spectra::CompInfo::Successful || converged < nev)
  {
    throw SolverFailure("the Lanczos iteration of the band at shift " + Str(sigma) +
        " converged for " + std::to_string(converged) + " of " + std::to_string(nev) +
        " eigenpairs in " + std::to_string(options.MaxIterations) +
        " restarts; raise MaxIterations or loosen Tolerance",
      static_cast<int>(converged));
  }
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

/**
 * X.leftCols(Z.cols()) = X.leftCols(Z.rows()) Z in place (Z.cols() <= Z.rows()), a few hundred
 * rows at a time through a small buffer: rotating or compressing a tall basis needs no second
 * n-row matrix. With `gram`, also its Gram matrix Y^T Y of the result Y, summed while the rows
 * are in cache (no second pass over Y).
 */
void MultiplyInPlace(Eigen::Ref<DenseMatrix> X, const DenseMatrix& Z, DenseMatrix* gram = nullptr)
{
  const Eigen::Index chunk = 256;
  DenseMatrix partial[2];
  ForEachRowRange(X.rows(),
    BlockThreads(X.rows()),
    [&](int part, Eigen::Index first, Eigen::Index count)
    {
      DenseMatrix rows(std::min(chunk, count), Z.cols());
      if (gram)
      {
        partial[part] = DenseMatrix::Zero(Z.cols(), Z.cols());
      }
      for (Eigen::Index r = first; r < first + count; r += chunk)
      {
        const Eigen::Index h = std::min(chunk, first + count - r);
        rows.topRows(h).noalias() = X.block(r, 0, h, Z.rows()) * Z;
        X.block(r, 0, h, Z.cols()) = rows.topRows(h);
        if (gram)
        {
          partial[part].noalias() += rows.topRows(h).transpose() * rows.topRows(h);
        }
      }
    });
  if (gram)
  {
    *gram = partial[1].size() ? (partial[0] + partial[1]).eval() : partial[0];
  }
}

/// out = X Z for a tall X, rows on two threads; out does not overlap X.
void MultiplyInto(Eigen::Ref<DenseMatrix> out,
  const Eigen::Ref<const DenseMatrix>& X,
  const DenseMatrix& Z)
{
  ForEachRowRange(X.rows(),
    BlockThreads(X.rows()),
    [&](int, Eigen::Index first, Eigen::Index count)
    { out.middleRows(first, count).noalias() = X.middleRows(first, count) * Z; });
}

/// W -= B (B^T M W) for a tall n-row B; returns B^T M W.
DenseMatrix Project(DenseMatrix& W, const Eigen::Ref<const DenseMatrix>& B, const MassMatrix& M)
{
  DenseMatrix scratch;
  const DenseMatrix C = TransposeProduct(B, M.Times(W, scratch));
  SubtractProduct(W, B, C);
  return C;
}

/// The Gram matrix W^T M W.
DenseMatrix MassGram(const DenseMatrix& W, const MassMatrix& M)
{
  DenseMatrix scratch;
  return TransposeProduct(W, M.Times(W, scratch));
}

/// The squared M-norm of every column of W.
Vector MassNorms(const DenseMatrix& W, const MassMatrix& M)
{
  if (M.Identity)
  {
    return W.colwise().squaredNorm().transpose();
  }
  return W.cwiseProduct(M.Matrix * W).colwise().sum().transpose();
}

/**
 * M-orthonormalize the columns of W (two passes of SVQB: eigen-decomposition of the Gram matrix)
 * and return R with W_in = W_out R. Directions whose norm fell below `floor` (the block is nearly
 * inside the span of Basis) are replaced by random vectors M-orthogonal to Basis and to the other
 * columns; their rows of R are zero.
 * \param gram W^T M W if the caller has it, else empty.
 * \param out where the result goes: W itself (null), or other columns (then W is left as
 *        scratch). With the identity mass the second pass's Gram matrix is summed during the
 *        first pass's product and the second product writes `out` directly: W is read three
 *        times instead of five.
 */
DenseMatrix Orthonormalize(DenseMatrix& W,
  const MassMatrix& M,
  const Eigen::Ref<const DenseMatrix>& Basis,
  double floor,
  std::mt19937& generator,
  DenseMatrix gram = DenseMatrix(),
  Eigen::Ref<DenseMatrix>* out = nullptr)
{
  const Eigen::Index b = W.cols();
  DenseMatrix R = DenseMatrix::Identity(b, b);
  for (int pass = 0; pass < 2; ++pass)
  {
    DenseMatrix G = gram.size() ? gram : MassGram(W, M);
    gram.resize(0, 0);
    G = 0.5 * (G + G.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<DenseMatrix> decomposition(G);
    const Vector& g = decomposition.eigenvalues();
    const DenseMatrix& U = decomposition.eigenvectors();
    DenseMatrix S = DenseMatrix::Zero(b, b);
    DenseMatrix Rpass = DenseMatrix::Zero(b, b);
    std::vector<Eigen::Index> deficient;
    for (Eigen::Index i = 0; i < b; ++i)
    {
      if (g[i] > floor)
      {
        S.col(i) = U.col(i) / std::sqrt(g[i]);
        Rpass.row(i) = std::sqrt(g[i]) * U.col(i).transpose();
      }
      else
      {
        deficient.push_back(i);
      }
    }
    R = (Rpass * R).eval();
    if (deficient.empty() && pass == 1 && out)
    {
      MultiplyInto(*out, W, S);
      return R;
    }
    MultiplyInPlace(W, S, deficient.empty() && pass == 0 && M.Identity ? &gram : nullptr);
    std::uniform_real_distribution<double> uniform(-0.5, 0.5);
    for (const Eigen::Index i : deficient)
    {
      Vector v(W.rows());
      for (Eigen::Index r = 0; r < v.size(); ++r)
      {
        v[r] = uniform(generator);
      }
      for (int again = 0; again < 2; ++again)
      {
        v -= Basis * (Basis.transpose() * (M.Matrix * v));
        v -= W * (W.transpose() * (M.Matrix * v));
      }
      W.col(i) = v / std::sqrt(v.dot(M.Matrix * v));
    }
  }
  if (out)
  {
    *out = W;
  }
  return R;
}

/**
 * Rayleigh-Ritz on the pencil (L - sigma M, M) within the span of the columns of X, given
 * AX = (L - sigma M) X and MX = M X (null for the identity M): rotates X, AX and MX in place to
 * the Ritz vectors (M-orthonormal) and returns the Ritz values lambda - sigma: the Rayleigh
 * quotients of the pencil itself, where the Ritz values of the Lanczos projection T carry the
 * rounding of every solve and Gram-Schmidt coefficient that built it.
 */
Vector RayleighRitz(Eigen::Ref<DenseMatrix> X, Eigen::Ref<DenseMatrix> AX, DenseMatrix* MX)
{
  DenseMatrix S = TransposeProduct(X, AX);
  DenseMatrix G = MX ? TransposeProduct(X, *MX) : TransposeProduct(X, X);
  S = 0.5 * (S + S.transpose()).eval();
  G = 0.5 * (G + G.transpose()).eval();
  Eigen::GeneralizedSelfAdjointEigenSolver<DenseMatrix> pencil(S, G);
  if (pencil.info() != Eigen::Success)
  {
    throw SolverFailure("the Ritz vectors of a band are not linearly independent");
  }
  const DenseMatrix& Z = pencil.eigenvectors();
  MultiplyInPlace(X, Z);
  MultiplyInPlace(AX, Z);
  if (MX)
  {
    MultiplyInPlace(*MX, Z);
  }
  return pencil.eigenvalues();
}

/**
 * The Rayleigh quotient x^T A x / x^T M x of every column x of X, given AX = A X and MX = M X.
 */
Vector RayleighQuotients(const Eigen::Ref<const DenseMatrix>& X,
  const Eigen::Ref<const DenseMatrix>& AX,
  const Eigen::Ref<const DenseMatrix>& MX)
{
  Vector out(X.cols());
  for (Eigen::Index k = 0; k < X.cols(); ++k)
  {
    out[k] = X.col(k).dot(AX.col(k)) / X.col(k).dot(MX.col(k));
  }
  return out;
}

/**
 * An eigenvalue within a small fraction of the mean gap from the shift makes the norm of
 * Op = (L - sigma M)^-1 M dwarf the rest of the band; rounding then costs every other pair of
 * the band up to an order of magnitude of residual. That eigenvalue dominates the first few
 * Lanczos blocks, so the largest Ritz value of their projection T finds it early.
 * \throws ShiftTooClose with a shift half a mean gap away from it.
 */
void CheckShift(const DenseMatrix& T, double sigma, double meanGap)
{
  const DenseMatrix symmetric = 0.5 * (T + T.transpose());
  const Vector theta = Eigen::SelfAdjointEigenSolver<DenseMatrix>(symmetric, Eigen::EigenvaluesOnly)
                         .eigenvalues();
  const double dominant =
    std::abs(theta[0]) > std::abs(theta[theta.size() - 1]) ? theta[0] : theta[theta.size() - 1];
  const double nearest = 1.0 / dominant;
  if (std::abs(nearest) < 0.025 * meanGap)
  {
    throw ShiftTooClose{ sigma + nearest - std::copysign(0.5 * meanGap, nearest) };
  }
}

/**
 * The nev eigenpairs nearest sigma by block Lanczos on Op = (L - sigma M)^-1 M in the M inner
 * product, with full block reorthogonalization (the block recurrence, then classical
 * Gram-Schmidt against the whole basis, repeated only where it cancels; matrix-matrix products
 * only) and thick restarts that keep the best Ritz vectors. The projected matrix
 * T = V^T M Op V is assembled from the Gram-Schmidt coefficients. A block of b vectors finds
 * eigenvalues of multiplicity up to b directly. A pair counts as converged when its Ritz estimate
 * is below Tolerance and its residual below ResidualTolerance / 20 (relaxed up to / 2 when the
 * iteration stalls), relative to max(|lambda|, lambdaReference) (lambdaReference <= 0: the
 * band's first non-zero eigenvalue).
 * The monitor is polled for cancellation before every block and told the band's progress
 * (its applications against those a band usually takes, at most 0.95) after every block.
 * \throws SolverFailure without convergence; ShiftTooClose (meanGap > 0: the spacing of the
 *         eigenvalues near sigma) when an eigenvalue lies within meanGap / 40 of sigma.
 */
Band RunBlockBand(const ShiftedFactor& factor,
  const MassMatrix& M,
  double sigma,
  int nev,
  int attempt,
  double lambdaReference,
  double meanGap,
  const EigenOptions& options,
  const Monitor& monitor,
  Workspace& work,
  EigenResult& stats)
{
  const Vector inverseMass = (M.Matrix * Vector::Ones(M.Matrix.cols())).cwiseInverse();
  Clock::time_point start = Clock::now();
  const Eigen::Index n = M.Matrix.rows();
  // Small blocks raise the polynomial degree per application (faster convergence); too small
  // blocks make the block solves and products slow. nev / 8 measured best for nev ~ 100.
  const Eigen::Index b = std::min<Eigen::Index>(std::max(8, std::min(16, nev / 8)), n / 4 + 1);
  Eigen::Index maxDim = std::max<Eigen::Index>(3 * nev + 2 * b, nev + 6 * b) * (attempt + 2) / 2;
  maxDim = std::min<Eigen::Index>(maxDim, n - b);
  if (maxDim < nev + b)
  {
    throw SolverFailure("the band of " + std::to_string(nev) + " eigenpairs does not fit a problem "
                        "of " + std::to_string(n) + " unknowns");
  }
  std::mt19937 generator(20080415u + 7919u * static_cast<unsigned>(attempt));
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);

  auto V = Workspace::Columns(work.Basis, n, maxDim + b);
  DenseMatrix T = DenseMatrix::Zero(maxDim + b, maxDim + b);
  DenseMatrix W(n, b);
  for (Eigen::Index j = 0; j < b; ++j)
  {
    for (Eigen::Index i = 0; i < n; ++i)
    {
      W(i, j) = uniform(generator);
    }
  }
  Orthonormalize(W, M, V.leftCols(0), 0.0, generator);
  V.leftCols(b) = W;
  // A band of nev pairs took 4.3 nev to 4.6 nev applications on the benchmark meshes: the
  // progress within the band, up to 0.95 until it returns.
  long long bandApplications = 0;
  Eigen::Index applied = 0; // columns whose image under Op is in T
  Eigen::Index filled = b;  // columns of V in use
  // The first block applied after a (re)start: its image couples to every column before it.
  Eigen::Index recurrenceStart = 0;

  // A pair converges when its residual is below margin * ResidualTolerance: a margin for the
  // merging of bands and the final check. The Ritz estimate's Tolerance is relaxed with it.
  const double initialMargin = 0.05;
  double margin = initialMargin;
  int mostConverged = -1;
  int stalled = 0;
  int settledRestarts = 0; // restarts in a row at which at least `wanted` pairs had settled
  bool givenUp = false;
  for (int restart = 0; restart <= options.MaxIterations; ++restart)
  {
    while (filled <= maxDim)
    {
      monitor.ThrowIfCancelled();
      start = Clock::now();
      const auto block = V.middleCols(applied, b);
      W = M.Identity ? factor.SolveBlock(block) : factor.SolveBlock(M.Matrix * block);
      stats.OperatorApplications += b;
      stats.Seconds.Solve += SecondsSince(start);
      start = Clock::now();
      const double reference = W.cwiseAbs2().colwise().sum().maxCoeff();
      const auto basis = V.leftCols(filled);
      // The block recurrence first: in exact arithmetic Op V_j is M-orthogonal to all blocks
      // but V_{j-1}, V_j (and, right after a restart, the kept Ritz vectors), so these carry
      // its large components. One pass against the whole basis then removes what rounding and
      // the loss of orthogonality of Lanczos left along the others; a further pass only where
      // that pass cancelled a column by more than 1/sqrt(2) (Daniel, Gragg, Kaufman, Stewart).
      const Eigen::Index local = applied == recurrenceStart ? 0 : applied - b;
      DenseMatrix C = DenseMatrix::Zero(filled, b);
      C.bottomRows(filled - local) = Project(W, V.middleCols(local, filled - local), M);
      Vector before = MassNorms(W, M);
      DenseMatrix gram; // W^T M W after the last pass, the Gram matrix Orthonormalize starts from
      for (int pass = 0; pass < 3; ++pass)
      {
        C += Project(W, basis, M);
        gram = MassGram(W, M);
        const Vector after = gram.diagonal();
        if ((after.array() >= 0.5 * before.array()).all())
        {
          break;
        }
        before = after;
      }
      Eigen::Ref<DenseMatrix> next = V.middleCols(filled, b);
      const DenseMatrix R =
        Orthonormalize(W, M, basis, 1e-26 * reference, generator, std::move(gram), &next);
      T.block(0, applied, filled, b) = C;
      T.block(applied, 0, b, filled) = C.transpose();
      T.block(filled, applied, b, b) = R;
      T.block(applied, filled, b, b) = R.transpose();
      applied = filled;
      filled += b;
      stats.Seconds.Orthogonalization += SecondsSince(start);
      bandApplications += b;
      monitor.Report(std::min(0.95, static_cast<double>(bandApplications) / (4.5 * nev)));
      if (restart == 0 && applied == 4 * b && meanGap > 0.0)
      {
        CheckShift(T.topLeftCorner(applied, applied), sigma, meanGap);
      }
    }
    start = Clock::now();

    DenseMatrix Tk = T.topLeftCorner(applied, applied);
    Tk = 0.5 * (Tk + Tk.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<DenseMatrix> ritz(Tk);
    const Vector& theta = ritz.eigenvalues();
    std::vector<Eigen::Index> order(static_cast<std::size_t>(applied));
    for (Eigen::Index i = 0; i < applied; ++i)
    {
      order[static_cast<std::size_t>(i)] = i;
    }
    std::sort(order.begin(), order.end(), [&theta](Eigen::Index a, Eigen::Index c) {
      return std::abs(theta[a]) > std::abs(theta[c]);
    });
    // Pairs nearest the shift first; a band returns the converged pairs nearest its shift (at
    // least `wanted` of them). Whatever lies farther is left to the next band; the inertia
    // checks of the caller make sure nothing in between is missed.
    // A Ritz pair (theta, x = V y) leaves Op x - theta x = Q c with Q the next block and
    // c = coupling y, so its residual for the pencil is L x - lambda M x = -(L - sigma M) Q c / theta
    // with lambda = sigma + 1/theta: cheap through the Gram matrix of (L - sigma M) Q.
    const DenseMatrix coupling = T.block(applied, 0, b, applied) * ritz.eigenvectors();
    DenseMatrix Z(n, b);
    SymmetricSparseProduct(factor.ShiftedMatrix(), V.middleCols(applied, b), Z);
    const DenseMatrix residualGram = Z.transpose() * (inverseMass.asDiagonal() * Z);
    double reference = lambdaReference;
    if (!(reference > 0.0))
    {
      double top = 0.0;
      for (int i = 0; i < std::min<int>(nev, static_cast<int>(applied)); ++i)
      {
        top = std::max(top, std::abs(sigma + 1.0 / theta[order[static_cast<std::size_t>(i)]]));
      }
      reference = top;
      for (int i = 0; i < std::min<int>(nev, static_cast<int>(applied)); ++i)
      {
        const double lambda = std::abs(sigma + 1.0 / theta[order[static_cast<std::size_t>(i)]]);
        reference = lambda > 1e-6 * top ? std::min(reference, lambda) : reference;
      }
    }
    const int wanted = std::max(1, (4 * nev) / 5);
    // A pair has settled when it has converged for the operator the iteration applies (its
    // Ritz estimate alone); it has converged when its estimated residual passes as well.
    const auto hasSettled = [&](Eigen::Index k)
    {
      return !(
        coupling.col(k).norm() > (margin / initialMargin) * options.Tolerance * std::abs(theta[k]));
    };
    int converged = 0;
    while (converged < std::min<int>(nev, static_cast<int>(applied)))
    {
      const Eigen::Index k = order[static_cast<std::size_t>(converged)];
      const double lambda = sigma + 1.0 / theta[k];
      const double residual =
        std::sqrt(std::max(0.0, coupling.col(k).dot(residualGram * coupling.col(k)))) /
        std::abs(theta[k]);
      if (!hasSettled(k) ||
        residual > margin * options.ResidualTolerance * std::max(std::abs(lambda), reference))
      {
        break;
      }
      ++converged;
    }
    int settled = 0;
    while (settled < std::min<int>(nev, static_cast<int>(applied)) &&
      hasSettled(order[static_cast<std::size_t>(settled)]))
    {
      ++settled;
    }
    // When enough pairs have settled at two restarts in a row but too few pass their residual
    // test, the true residuals are held up by the solves' backward error (see the refinement
    // below): refine those pairs rather than iterate on. Otherwise, when two restarts bring no
    // new pair, rounding bounds the attainable residual (it grows with lambda_max / lambda_1,
    // i.e. with the mesh size): relax the margin, up to half the tolerance that the caller
    // verifies. A band that still stalls fails, and the caller starts it afresh with a larger
    // subspace.
    settledRestarts = settled >= wanted ? settledRestarts + 1 : 0;
    const bool refine = settledRestarts >= 2;
    if (converged > mostConverged)
    {
      mostConverged = converged;
      stalled = 0;
    }
    else if (++stalled >= 2)
    {
      givenUp = margin >= 0.5;
      margin = std::min(0.5, 2.0 * margin);
      stalled = 0;
    }
    if (converged >= wanted || refine || givenUp || restart == options.MaxIterations)
    {
      converged = refine ? std::max(converged, settled) : converged;
      if (converged < wanted)
      {
        throw SolverFailure("the block Lanczos iteration of the band at shift " + Str(sigma) +
            " converged for " + std::to_string(converged) + " of " + std::to_string(nev) +
            " eigenpairs in " + std::to_string(restart) + " restarts",
          converged);
      }
      DenseMatrix Y(applied, converged);
      for (int i = 0; i < converged; ++i)
      {
        Y.col(i) = ritz.eigenvectors().col(order[static_cast<std::size_t>(i)]);
      }
      // The Ritz vectors take the place of the basis they are made of.
      MultiplyInPlace(V.leftCols(applied), Y);
      auto X = V.leftCols(converged);
      auto AX = Workspace::Columns(work.Image, n, converged);
      SymmetricSparseProduct(factor.ShiftedMatrix(), X, AX);
      DenseMatrix MX; // M X; empty for the identity
      if (!M.Identity)
      {
        MX = M.Matrix * X;
      }
      // M X without a copy: MX, or X itself for the identity.
      const auto massX = [&]()
      { return M.Identity ? Eigen::Ref<const DenseMatrix>(X) : Eigen::Ref<const DenseMatrix>(MX); };
      // The Ritz vectors of T are those of the Krylov space; their Rayleigh quotients for the
      // pencil itself are more accurate than the Ritz values of T, which carry the rounding of
      // every solve and Gram-Schmidt coefficient that built it. (The merge of the bands makes
      // a Rayleigh-Ritz step on the joint span of the overlap.)
      Vector shifted = RayleighQuotients(X, AX, massX());
      // The residual estimate above trusts the Lanczos relation, that is, exact solves: check
      // the true residuals (L - sigma M) x - (lambda - sigma) M x, a sparse product, and keep
      // the pairs nearest the shift up to the first that fails. Too few left: the caller starts
      // the band afresh.
      std::vector<Eigen::Index> nearest;
      const auto verify = [&]()
      {
        return Verify(AX,
          massX(),
          shifted,
          inverseMass,
          sigma,
          reference,
          0.5 * options.ResidualTolerance,
          nearest);
      };
      int verified = verify();
      if (verified < converged)
      {
        // Unpivoted LDL^T of an indefinite L - sigma M has element growth: on the noisy tori of
        // the benchmark its solves have a backward error of 5e-14 to 3e-12 relative to
        // ||L - sigma M|| (1e-15 below the spectrum), and the Lanczos iteration converges to
        // the eigenpairs of that nearby operator, with residuals up to backward error *
        // lambda_max / lambda. One step of iterative refinement of the vectors,
        // x <- x - (L - sigma M)^-1 r with the true residual r, removes the error where
        // lambda_max lives (high frequencies); Rayleigh-Ritz sorts out the band's own
        // directions. Measured on the 100K torus with the step forced for every band: residuals
        // 1e-10 -> 1e-12.
        stats.Seconds.RayleighRitz += SecondsSince(start);
        start = Clock::now();
        X -= factor.SolveBlock(AX - massX() * shifted.asDiagonal());
        stats.OperatorApplications += converged;
        stats.Seconds.Solve += SecondsSince(start);
        start = Clock::now();
        SymmetricSparseProduct(factor.ShiftedMatrix(), X, AX);
        if (!M.Identity)
        {
          MX = M.Matrix * X;
        }
        shifted = RayleighRitz(X, AX, M.Identity ? nullptr : &MX);
        verified = verify();
      }
      if (verified < std::max(1, wanted / 2))
      {
        throw SolverFailure("the band at shift " + Str(sigma) + " verified " +
            std::to_string(verified) + " of " + std::to_string(converged) +
            " converged eigenpairs by their residuals",
          verified);
      }
      std::vector<std::pair<double, Eigen::Index>> values;
      for (int i = 0; i < verified; ++i)
      {
        const Eigen::Index k = nearest[static_cast<std::size_t>(i)];
        values.emplace_back(sigma + shifted[k], k);
      }
      std::sort(values.begin(), values.end());
      // Ascending in the first columns of the basis, through the image, which is no longer needed.
      Band band{ Vector(verified) };
      for (int i = 0; i < verified; ++i)
      {
        band.Values[i] = values[static_cast<std::size_t>(i)].first;
        AX.col(i) = X.col(values[static_cast<std::size_t>(i)].second);
      }
      V.leftCols(verified) = AX.leftCols(verified);
      stats.Seconds.RayleighRitz += SecondsSince(start);
      return band;
    }

    // Thick restart: keep the best Ritz vectors and the last block, and leave room for two
    // more blocks (one where the subspace is too small for two: maxDim >= nev + b).
    const Eigen::Index room =
      std::max<Eigen::Index>(maxDim - 2 * b, std::min<Eigen::Index>(nev, maxDim - b));
    const Eigen::Index keep = std::max<Eigen::Index>(1,
      std::min<Eigen::Index>(
        { std::max<Eigen::Index>(nev + b, (applied + nev) / 2), room, applied }));
    DenseMatrix Y(applied, keep);
    Vector kept(keep);
    for (Eigen::Index i = 0; i < keep; ++i)
    {
      const Eigen::Index k = order[static_cast<std::size_t>(i)];
      Y.col(i) = ritz.eigenvectors().col(k);
      kept[i] = theta[k];
    }
    const DenseMatrix last = V.middleCols(applied, b);
    const DenseMatrix link = T.block(applied, 0, b, applied) * Y;
    MultiplyInPlace(V.leftCols(applied), Y);
    V.middleCols(keep, b) = last;
    T.setZero();
    T.topLeftCorner(keep, keep) = kept.asDiagonal();
    T.block(keep, 0, b, keep) = link;
    T.block(0, keep, keep, b) = link.transpose();
    applied = keep;
    filled = keep + b;
    recurrenceStart = keep;
    stats.Seconds.RayleighRitz += SecondsSince(start);
  }
  throw SolverFailure("the block Lanczos iteration did not converge");
}

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
  const ShiftInvertOp op(factor, monitor, n);
  const MassOp mass(M.Matrix);

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
      band = RunBand(op, mass, sigma, nev, attempt, options, work);
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
        band = RunBlockBand(
          factor, M, sigma, nev, attempt, reference, meanGap, options, bandMonitor, work, result);
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
      catch (const ShiftTooClose& moved)
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
