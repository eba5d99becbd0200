// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/BlockLanczos.h"
#include "Common/Eigenvalues.h"
#include "Solver/Bands.h"
#include "Solver/BlockProducts.h"
#include "Solver/Diagnostics.h"
#include "Solver/LanczosKernels.h"
#include "Solver/Verification.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace spectral
{
namespace detail
{
namespace
{
/**
 * An eigenvalue within a small fraction of the mean gap from the shift makes the norm of
 * Op = (L - sigma M)^-1 M dwarf the rest of the band; rounding then costs every other pair of
 * the band up to an order of magnitude of residual. That eigenvalue dominates the first few
 * Lanczos blocks, so the largest Ritz value of their projection T finds it early.
 * \throws ShiftTooClose with the eigenvalue sigma + 1 / theta it found.
 */
void CheckShift(const DenseMatrix& T, double sigma, double meanGap)
{
  const DenseMatrix symmetric = 0.5 * (T + T.transpose());
  const Vector theta =
    Eigen::SelfAdjointEigenSolver<DenseMatrix>(symmetric, Eigen::EigenvaluesOnly).eigenvalues();
  const double dominant =
    std::abs(theta[0]) > std::abs(theta[theta.size() - 1]) ? theta[0] : theta[theta.size() - 1];
  const double nearest = 1.0 / dominant;
  if (std::abs(nearest) < 0.025 * meanGap)
  {
    throw ShiftTooClose{ sigma + nearest, std::copysign(1.0, -nearest) };
  }
}

/// Columns of the Krylov basis a band of nev pairs may use, sized for `sized` pairs (at least
/// nev; BandRequest::SubspacePairs): throws if the band does not fit n unknowns.
Eigen::Index SubspaceSize(Eigen::Index n, Eigen::Index b, int nev, int sized)
{
  const Eigen::Index k = std::max(nev, sized);
  Eigen::Index maxDim = std::max<Eigen::Index>(3 * k + 2 * b, k + 6 * b);
  maxDim = std::min<Eigen::Index>(maxDim, n - b);
  if (maxDim < nev + b)
  {
    throw SolverFailure("the band of " + std::to_string(nev) +
      " eigenpairs does not fit a problem "
      "of " +
      std::to_string(n) + " unknowns");
  }
  return maxDim;
}

/// The Ritz pairs of the projection T at a restart.
struct RitzPairs
{
  /// Eigenpairs (theta, y) of T; lambda = sigma + 1 / theta.
  Eigen::SelfAdjointEigenSolver<DenseMatrix> OfT;
  /// Indices of the pairs nearest the shift first (largest |theta|).
  std::vector<Eigen::Index> Order;
  /// The next block's coefficients in Op x - theta x for each Ritz vector x = V y.
  DenseMatrix Coupling;
  /// The Gram matrix of (L - sigma M) Q in the D^-1 norm, Q the next block.
  DenseMatrix ResidualGram;
  /// The scale of relative residuals.
  double Reference = 0.0;

  const Vector& Theta() const { return this->OfT.eigenvalues(); }
};

/// The state of one band of block Lanczos: its Krylov basis V, its projection T, its restarts.
class BlockLanczosBand
{
public:
  BlockLanczosBand(const ShiftedFactor& factor,
    const MassMatrix& M,
    const BandRequest& request,
    const EigenOptions& options,
    const Monitor& monitor,
    Workspace& work,
    EigenResult& stats);

  /// Iterate until enough pairs converge; \return the band.
  Band Run();

private:
  struct Counts
  {
    int Converged;
    int Settled;
  };

  void FillBasis(int restart);
  void ApplyOperator();
  DenseMatrix ProjectOutBasis(DenseMatrix& gram);
  void ExtendBasis();
  void ComputeRitzPairs(RitzPairs& ritz) const;
  double ResidualReference(const RitzPairs& ritz) const;
  bool HasSettled(const RitzPairs& ritz, Eigen::Index k) const;
  Counts CountConverged(const RitzPairs& ritz) const;
  void TrackStall(int converged);
  Band Finish(const RitzPairs& ritz, int converged, int restart);
  Eigen::Ref<const DenseMatrix> MassX(const Eigen::Ref<const DenseMatrix>& X,
    const DenseMatrix& MX) const;
  int Verified(const Eigen::Ref<const DenseMatrix>& X,
    const Eigen::Ref<const DenseMatrix>& AX,
    const DenseMatrix& MX,
    const Vector& shifted,
    double reference,
    std::vector<Eigen::Index>& nearest) const;
  void Refine(Eigen::Ref<DenseMatrix> X,
    Eigen::Ref<DenseMatrix> AX,
    DenseMatrix& MX,
    Vector& shifted);
  Band AscendingBand(const Eigen::Ref<const DenseMatrix>& X,
    Eigen::Ref<DenseMatrix> AX,
    const Vector& shifted,
    const std::vector<Eigen::Index>& nearest,
    int verified);
  void ThickRestart(const RitzPairs& ritz);

  const ShiftedFactor& Factor;
  const MassMatrix& M;
  const double Sigma;
  const int Nev;
  const double LambdaReference;
  const double MeanGap;
  const EigenOptions& Options;
  const Monitor& Watch;
  Workspace& Work;
  EigenResult& Stats;

  const Vector InverseMass;
  Clock::time_point Start;
  const Eigen::Index N;
  /// Block size (BandBlockColumns, the band policy of Bands.h), at most a quarter of the
  /// unknowns.
  const Eigen::Index B;
  const Eigen::Index MaxDim;
  /// Pairs a band must return (request.ReturnPairs, the band policy of Bands.h).
  const int Wanted;
  std::mt19937 Generator;
  Eigen::Block<DenseMatrix, Eigen::Dynamic, Eigen::Dynamic, true> V;
  DenseMatrix T;
  DenseMatrix W;

  // A band of nev pairs took 4.3 nev to 4.6 nev applications on the benchmark meshes: the
  // progress within the band, up to 0.95 until it returns.
  long long BandApplications = 0;
  Eigen::Index Applied = 0; ///< columns whose image under Op is in T
  Eigen::Index Filled;      ///< columns of V in use
  /// The first block applied after a (re)start: its image couples to every column before it.
  Eigen::Index RecurrenceStart = 0;

  // A pair converges when its residual is below margin * ResidualTolerance: a margin for the
  // merging of bands and the final check. The Ritz estimate's Tolerance is relaxed with it.
  static constexpr double InitialMargin = 0.05;
  double Margin = InitialMargin;
  int MostConverged = -1;
  int Stalled = 0;
  bool GivenUp = false;
};

//------------------------------------------------------------------------------
BlockLanczosBand::BlockLanczosBand(const ShiftedFactor& factor,
  const MassMatrix& M,
  const BandRequest& request,
  const EigenOptions& options,
  const Monitor& monitor,
  Workspace& work,
  EigenResult& stats)
  : Factor(factor)
  , M(M)
  , Sigma(request.Sigma)
  , Nev(request.Pairs)
  , LambdaReference(request.LambdaReference)
  , MeanGap(request.MeanGap)
  , Options(options)
  , Watch(monitor)
  , Work(work)
  , Stats(stats)
  , InverseMass((M.Matrix * Vector::Ones(M.Matrix.cols())).cwiseInverse())
  , Start(Clock::now())
  , N(M.Matrix.rows())
  , B(std::min<Eigen::Index>(BandBlockColumns, this->N / 4 + 1))
  , MaxDim(SubspaceSize(this->N, this->B, request.Pairs, request.SubspacePairs))
  , Wanted(std::max(1, request.ReturnPairs))
  , Generator(20080415u + 7919u * static_cast<unsigned>(request.Attempt))
  , V(Workspace::Columns(work.Basis, this->N, this->MaxDim + this->B))
  , T(DenseMatrix::Zero(this->MaxDim + this->B, this->MaxDim + this->B))
  , W(this->N, this->B)
  , Filled(this->B)
{
  stats.MostKrylovColumns =
    std::max(stats.MostKrylovColumns, static_cast<int>(this->MaxDim + this->B));
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  for (Eigen::Index j = 0; j < this->B; ++j)
  {
    for (Eigen::Index i = 0; i < this->N; ++i)
    {
      this->W(i, j) = uniform(this->Generator);
    }
  }
  M.Deflate(this->W);
  Orthonormalize(this->W, M, this->V.leftCols(0), 0.0, this->Generator);
  this->V.leftCols(this->B) = this->W;
}

//------------------------------------------------------------------------------
Band BlockLanczosBand::Run()
{
  for (int restart = 0; restart <= this->Options.MaxIterations; ++restart)
  {
    this->FillBasis(restart);
    this->Start = Clock::now();
    RitzPairs ritz;
    this->ComputeRitzPairs(ritz);
    const Counts counts = this->CountConverged(ritz);
    // When enough pairs have settled (by their Ritz estimates) but too few pass the residual
    // estimate, further restarts do not lower that estimate: it is held up by the solves'
    // backward error (see Refine) or, on a scan, by the rows of tiny mass that the D^-1 norm
    // weighs by 1 / D_ii. Refine those pairs and let Verified judge them by their true
    // residuals and backward errors. (Waiting for a second restart cost a scan a quarter to a
    // third more applications: bench/README.md, Range scans.)
    const bool refine = counts.Settled >= this->Wanted;
    this->TrackStall(counts.Converged);
    if (counts.Converged >= this->Wanted || refine || this->GivenUp ||
      restart == this->Options.MaxIterations)
    {
      return this->Finish(
        ritz, refine ? std::max(counts.Converged, counts.Settled) : counts.Converged, restart);
    }
    this->ThickRestart(ritz);
  }
  throw SolverFailure("the block Lanczos iteration did not converge");
}

//------------------------------------------------------------------------------
void BlockLanczosBand::FillBasis(int restart)
{
  while (this->Filled <= this->MaxDim)
  {
    this->Watch.ThrowIfCancelled();
    this->ApplyOperator();
    this->ExtendBasis();
    this->BandApplications += this->B;
    this->Watch.Report(
      std::min(0.95, static_cast<double>(this->BandApplications) / (4.5 * this->Nev)));
    if (restart == 0 && this->Applied == 4 * this->B && this->MeanGap > 0.0)
    {
      CheckShift(this->T.topLeftCorner(this->Applied, this->Applied), this->Sigma, this->MeanGap);
    }
  }
}

//------------------------------------------------------------------------------
// W = Op V_j for the last block V_j of the basis.
void BlockLanczosBand::ApplyOperator()
{
  this->Start = Clock::now();
  const auto block = this->V.middleCols(this->Applied, this->B);
  this->W = this->M.Identity ? this->Factor.SolveBlock(block)
                             : this->Factor.SolveBlock(this->M.Matrix * block);
  // Op keeps the complement of the null vectors in exact arithmetic; rounding would let their
  // direction grow back.
  this->M.Deflate(this->W);
  this->Stats.OperatorApplications += this->B;
  this->Stats.Seconds.Solve += SecondsSince(this->Start);
}

//------------------------------------------------------------------------------
// Remove the basis from W; returns the coefficients (a block column of T) and sets `gram` to
// W^T M W after the last pass.
DenseMatrix BlockLanczosBand::ProjectOutBasis(DenseMatrix& gram)
{
  const auto basis = this->V.leftCols(this->Filled);
  // The block recurrence first: in exact arithmetic Op V_j is M-orthogonal to all blocks
  // but V_{j-1}, V_j (and, right after a restart, the kept Ritz vectors), so these carry
  // its large components. One pass against the whole basis then removes what rounding and
  // the loss of orthogonality of Lanczos left along the others; a further pass only where
  // that pass cancelled a column by more than 1/sqrt(2) (Daniel, Gragg, Kaufman, Stewart).
  const Eigen::Index local = this->Applied == this->RecurrenceStart ? 0 : this->Applied - this->B;
  DenseMatrix C = DenseMatrix::Zero(this->Filled, this->B);
  C.bottomRows(this->Filled - local) =
    Project(this->W, this->V.middleCols(local, this->Filled - local), this->M);
  Vector before = MassNorms(this->W, this->M);
  for (int pass = 0; pass < 3; ++pass)
  {
    C += Project(this->W, basis, this->M);
    gram = MassGram(this->W, this->M);
    const Vector after = gram.diagonal();
    if ((after.array() >= 0.5 * before.array()).all())
    {
      break;
    }
    before = after;
  }
  return C;
}

//------------------------------------------------------------------------------
// Orthogonalize W = Op V_j against the basis, append it as the next block, extend T.
void BlockLanczosBand::ExtendBasis()
{
  this->Start = Clock::now();
  const double reference = this->W.cwiseAbs2().colwise().sum().maxCoeff();
  DenseMatrix gram; // W^T M W after the last pass, the Gram matrix Orthonormalize starts from
  const DenseMatrix C = this->ProjectOutBasis(gram);
  Eigen::Ref<DenseMatrix> next = this->V.middleCols(this->Filled, this->B);
  const DenseMatrix R = Orthonormalize(this->W,
    this->M,
    this->V.leftCols(this->Filled),
    1e-26 * reference,
    this->Generator,
    std::move(gram),
    &next);
  this->T.block(0, this->Applied, this->Filled, this->B) = C;
  this->T.block(this->Applied, 0, this->B, this->Filled) = C.transpose();
  this->T.block(this->Filled, this->Applied, this->B, this->B) = R;
  this->T.block(this->Applied, this->Filled, this->B, this->B) = R.transpose();
  this->Applied = this->Filled;
  this->Filled += this->B;
  this->Stats.Seconds.Orthogonalization += SecondsSince(this->Start);
}

//------------------------------------------------------------------------------
void BlockLanczosBand::ComputeRitzPairs(RitzPairs& ritz) const
{
  const Eigen::Index applied = this->Applied;
  DenseMatrix Tk = this->T.topLeftCorner(applied, applied);
  Tk = 0.5 * (Tk + Tk.transpose()).eval();
  ritz.OfT.compute(Tk);
  const Vector& theta = ritz.Theta();
  ritz.Order.resize(static_cast<std::size_t>(applied));
  for (Eigen::Index i = 0; i < applied; ++i)
  {
    ritz.Order[static_cast<std::size_t>(i)] = i;
  }
  std::sort(ritz.Order.begin(),
    ritz.Order.end(),
    [&theta](Eigen::Index a, Eigen::Index c) { return std::abs(theta[a]) > std::abs(theta[c]); });
  // Pairs nearest the shift first; a band returns the converged pairs nearest its shift (at
  // least Wanted of them). Whatever lies farther is left to the next band; the inertia
  // checks of the caller make sure nothing in between is missed.
  // A Ritz pair (theta, x = V y) leaves Op x - theta x = Q c with Q the next block and
  // c = coupling y, so its residual for the pencil is L x - lambda M x = -(L - sigma M) Q c / theta
  // with lambda = sigma + 1/theta: cheap through the Gram matrix of (L - sigma M) Q.
  ritz.Coupling = this->T.block(applied, 0, this->B, applied) * ritz.OfT.eigenvectors();
  DenseMatrix Z(this->N, this->B);
  SymmetricSparseProduct(this->Factor.ShiftedMatrix(), this->V.middleCols(applied, this->B), Z);
  ritz.ResidualGram = Z.transpose() * (this->InverseMass.asDiagonal() * Z);
  ritz.Reference = this->ResidualReference(ritz);
}

//------------------------------------------------------------------------------
// LambdaReference if known, else the smallest non-zero |lambda| (IsZeroEigenvalue, scaled by the
// largest) among the nev pairs nearest the shift.
double BlockLanczosBand::ResidualReference(const RitzPairs& ritz) const
{
  double reference = this->LambdaReference;
  if (!(reference > 0.0))
  {
    const Vector& theta = ritz.Theta();
    const int count = std::min<int>(this->Nev, static_cast<int>(this->Applied));
    double top = 0.0;
    for (int i = 0; i < count; ++i)
    {
      top =
        std::max(top, std::abs(this->Sigma + 1.0 / theta[ritz.Order[static_cast<std::size_t>(i)]]));
    }
    reference = top;
    for (int i = 0; i < count; ++i)
    {
      const double lambda =
        std::abs(this->Sigma + 1.0 / theta[ritz.Order[static_cast<std::size_t>(i)]]);
      reference = !IsZeroEigenvalue(lambda, top) ? std::min(reference, lambda) : reference;
    }
  }
  return reference;
}

//------------------------------------------------------------------------------
// A pair has settled when it has converged for the operator the iteration applies (its Ritz
// estimate alone); it has converged when its estimated residual passes as well.
bool BlockLanczosBand::HasSettled(const RitzPairs& ritz, Eigen::Index k) const
{
  return !(ritz.Coupling.col(k).norm() >
    (this->Margin / InitialMargin) * this->Options.Tolerance * std::abs(ritz.Theta()[k]));
}

//------------------------------------------------------------------------------
BlockLanczosBand::Counts BlockLanczosBand::CountConverged(const RitzPairs& ritz) const
{
  const Vector& theta = ritz.Theta();
  const int count = std::min<int>(this->Nev, static_cast<int>(this->Applied));
  int converged = 0;
  while (converged < count)
  {
    const Eigen::Index k = ritz.Order[static_cast<std::size_t>(converged)];
    const double lambda = this->Sigma + 1.0 / theta[k];
    const double residual =
      std::sqrt(std::max(0.0, ritz.Coupling.col(k).dot(ritz.ResidualGram * ritz.Coupling.col(k)))) /
      std::abs(theta[k]);
    if (!this->HasSettled(ritz, k) ||
      residual >
        this->Margin * this->Options.ResidualTolerance * std::max(std::abs(lambda), ritz.Reference))
    {
      break;
    }
    ++converged;
  }
  int settled = 0;
  while (settled < count && this->HasSettled(ritz, ritz.Order[static_cast<std::size_t>(settled)]))
  {
    ++settled;
  }
  return { converged, settled };
}

//------------------------------------------------------------------------------
// When two restarts bring no new pair, rounding bounds the attainable residual (it grows with
// lambda_max / lambda_1, i.e. with the mesh size): relax the margin, up to half the tolerance
// that the caller verifies. A band that still stalls gives up (fails unless enough pairs
// converged), and the caller starts it afresh, with fewer pairs in the same subspace (RetryPairs).
void BlockLanczosBand::TrackStall(int converged)
{
  if (converged > this->MostConverged)
  {
    this->MostConverged = converged;
    this->Stalled = 0;
  }
  else if (++this->Stalled >= 2)
  {
    this->GivenUp = this->Margin >= 0.5;
    this->Margin = std::min(0.5, 2.0 * this->Margin);
    this->Stalled = 0;
  }
}

//------------------------------------------------------------------------------
// The `converged` pairs nearest the shift become the band: Ritz vectors, their Rayleigh
// quotients, the true residual test and, where it fails, one refinement step.
Band BlockLanczosBand::Finish(const RitzPairs& ritz, int converged, int restart)
{
  if (converged < this->Wanted)
  {
    throw SolverFailure("the block Lanczos iteration of the band at shift " + Str(this->Sigma) +
        " converged for " + std::to_string(converged) + " of " + std::to_string(this->Nev) +
        " eigenpairs in " + std::to_string(restart) + " restarts",
      converged);
  }
  DenseMatrix Y(this->Applied, converged);
  for (int i = 0; i < converged; ++i)
  {
    Y.col(i) = ritz.OfT.eigenvectors().col(ritz.Order[static_cast<std::size_t>(i)]);
  }
  // The Ritz vectors take the place of the basis they are made of.
  MultiplyInPlace(this->V.leftCols(this->Applied), Y);
  Eigen::Ref<DenseMatrix> X = this->V.leftCols(converged);
  Eigen::Ref<DenseMatrix> AX = Workspace::Columns(this->Work.Image, this->N, converged);
  SymmetricSparseProduct(this->Factor.ShiftedMatrix(), X, AX);
  DenseMatrix MX; // M X; empty for the identity
  if (!this->M.Identity)
  {
    MX = this->M.Matrix * X;
  }
  // The Ritz vectors of T are those of the Krylov space; their Rayleigh quotients for the
  // pencil itself are more accurate than the Ritz values of T, which carry the rounding of
  // every solve and Gram-Schmidt coefficient that built it. (The merge of the bands makes
  // a Rayleigh-Ritz step on the joint span of the overlap.)
  Vector shifted = RayleighQuotients(X, AX, this->MassX(X, MX));
  // The residual estimate of CountConverged trusts the Lanczos relation, that is, exact solves:
  // check the true residuals (L - sigma M) x - (lambda - sigma) M x, a sparse product, and keep
  // the pairs nearest the shift up to the first that fails. Too few left: the caller starts
  // the band afresh.
  std::vector<Eigen::Index> nearest;
  int verified = this->Verified(X, AX, MX, shifted, ritz.Reference, nearest);
  if (verified < converged)
  {
    this->Refine(X, AX, MX, shifted);
    verified = this->Verified(X, AX, MX, shifted, ritz.Reference, nearest);
  }
  if (verified < std::max(1, this->Wanted / 2))
  {
    throw SolverFailure("the band at shift " + Str(this->Sigma) + " verified " +
        std::to_string(verified) + " of " + std::to_string(converged) +
        " converged eigenpairs by their residuals",
      verified);
  }
  return this->AscendingBand(X, AX, shifted, nearest, verified);
}

//------------------------------------------------------------------------------
// M X without a copy: MX, or X itself for the identity.
Eigen::Ref<const DenseMatrix> BlockLanczosBand::MassX(const Eigen::Ref<const DenseMatrix>& X,
  const DenseMatrix& MX) const
{
  return this->M.Identity ? X : Eigen::Ref<const DenseMatrix>(MX);
}

//------------------------------------------------------------------------------
int BlockLanczosBand::Verified(const Eigen::Ref<const DenseMatrix>& X,
  const Eigen::Ref<const DenseMatrix>& AX,
  const DenseMatrix& MX,
  const Vector& shifted,
  double reference,
  std::vector<Eigen::Index>& nearest) const
{
  // The backward errors of the pairs whose residual alone fails (|L| |x| and |M| |x|, a column
  // at a time), with L the band's stiffness (L - sigma M) + sigma M.
  BackwardScale backward;
  backward.Tolerance = 0.5 * this->Options.BackwardErrorTolerance;
  const SparseMatrix absL =
    SparseMatrix(this->Factor.ShiftedMatrix() + this->Sigma * this->M.Matrix).cwiseAbs();
  const SparseMatrix absM =
    this->M.Identity ? SparseMatrix() : SparseMatrix(this->M.Matrix.cwiseAbs());
  backward.AbsL = &absL;
  backward.AbsM = this->M.Identity ? nullptr : &absM;
  backward.X = &X;
  return Verify(AX,
    this->MassX(X, MX),
    shifted,
    this->InverseMass,
    this->Sigma,
    reference,
    0.5 * this->Options.ResidualTolerance,
    nearest,
    backward);
}

//------------------------------------------------------------------------------
// Unpivoted LDL^T of an indefinite L - sigma M has element growth: on the noisy tori of the
// benchmark its solves have a backward error of 5e-14 to 3e-12 relative to ||L - sigma M||
// (1e-15 below the spectrum), and the Lanczos iteration converges to the eigenpairs of that
// nearby operator, with residuals up to backward error * lambda_max / lambda. One step of
// iterative refinement of the vectors, x <- x - (L - sigma M)^-1 r with the true residual r,
// removes the error where lambda_max lives (high frequencies); Rayleigh-Ritz sorts out the
// band's own directions. Measured on the 100K torus with the step forced for every band:
// residuals 1e-10 -> 1e-12.
void BlockLanczosBand::Refine(Eigen::Ref<DenseMatrix> X,
  Eigen::Ref<DenseMatrix> AX,
  DenseMatrix& MX,
  Vector& shifted)
{
  this->Stats.Seconds.RayleighRitz += SecondsSince(this->Start);
  this->Start = Clock::now();
  // A block of B columns at a time: the residuals and the solve's own copies of all k at once
  // held two more n x k blocks at the end of every band (heaptrack: 340 MB of a 200K-point
  // streamed solve's 1.9 GB peak).
  const Eigen::Ref<const DenseMatrix> massX = this->MassX(X, MX);
  for (Eigen::Index first = 0; first < X.cols(); first += this->B)
  {
    const Eigen::Index count = std::min(this->B, X.cols() - first);
    const DenseMatrix residual = AX.middleCols(first, count) -
      massX.middleCols(first, count) * shifted.segment(first, count).asDiagonal();
    X.middleCols(first, count) -= this->Factor.SolveBlock(residual);
  }
  this->M.Deflate(X);
  this->Stats.OperatorApplications += X.cols();
  this->Stats.Seconds.Solve += SecondsSince(this->Start);
  this->Start = Clock::now();
  SymmetricSparseProduct(this->Factor.ShiftedMatrix(), X, AX);
  if (!this->M.Identity)
  {
    MX = this->M.Matrix * X;
  }
  shifted = RayleighRitz(X, AX, this->M.Identity ? nullptr : &MX);
}

//------------------------------------------------------------------------------
// The `verified` pairs nearest the shift, ascending, in the first columns of the basis (through
// AX, which is no longer needed).
Band BlockLanczosBand::AscendingBand(const Eigen::Ref<const DenseMatrix>& X,
  Eigen::Ref<DenseMatrix> AX,
  const Vector& shifted,
  const std::vector<Eigen::Index>& nearest,
  int verified)
{
  std::vector<std::pair<double, Eigen::Index>> values;
  for (int i = 0; i < verified; ++i)
  {
    const Eigen::Index k = nearest[static_cast<std::size_t>(i)];
    values.emplace_back(this->Sigma + shifted[k], k);
  }
  std::sort(values.begin(), values.end());
  Band band{ Vector(verified) };
  for (int i = 0; i < verified; ++i)
  {
    band.Values[i] = values[static_cast<std::size_t>(i)].first;
    AX.col(i) = X.col(values[static_cast<std::size_t>(i)].second);
  }
  this->V.leftCols(verified) = AX.leftCols(verified);
  this->Stats.Seconds.RayleighRitz += SecondsSince(this->Start);
  return band;
}

//------------------------------------------------------------------------------
// Thick restart: keep the best Ritz vectors and the last block, and leave room for two more
// blocks (one where the subspace is too small for two: MaxDim >= nev + b).
void BlockLanczosBand::ThickRestart(const RitzPairs& ritz)
{
  const Eigen::Index b = this->B;
  const Eigen::Index applied = this->Applied;
  const Eigen::Index room = std::max<Eigen::Index>(
    this->MaxDim - 2 * b, std::min<Eigen::Index>(this->Nev, this->MaxDim - b));
  const Eigen::Index keep = std::max<Eigen::Index>(1,
    std::min<Eigen::Index>(
      { std::max<Eigen::Index>(this->Nev + b, (applied + this->Nev) / 2), room, applied }));
  DenseMatrix Y(applied, keep);
  Vector kept(keep);
  for (Eigen::Index i = 0; i < keep; ++i)
  {
    const Eigen::Index k = ritz.Order[static_cast<std::size_t>(i)];
    Y.col(i) = ritz.OfT.eigenvectors().col(k);
    kept[i] = ritz.Theta()[k];
  }
  const DenseMatrix last = this->V.middleCols(applied, b);
  const DenseMatrix link = this->T.block(applied, 0, b, applied) * Y;
  MultiplyInPlace(this->V.leftCols(applied), Y);
  this->V.middleCols(keep, b) = last;
  this->T.setZero();
  this->T.topLeftCorner(keep, keep) = kept.asDiagonal();
  this->T.block(keep, 0, b, keep) = link;
  this->T.block(0, keep, keep, b) = link.transpose();
  this->Applied = keep;
  this->Filled = keep + b;
  this->RecurrenceStart = keep;
  this->Stats.Seconds.RayleighRitz += SecondsSince(this->Start);
}
} // namespace

//------------------------------------------------------------------------------
Band RunBlockBand(const ShiftedFactor& factor,
  const MassMatrix& M,
  const BandRequest& request,
  const EigenOptions& options,
  const Monitor& monitor,
  Workspace& work,
  EigenResult& stats)
{
  return BlockLanczosBand(factor, M, request, options, monitor, work, stats).Run();
}
} // namespace detail
} // namespace spectral
