// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Acceptance.h
 * @brief The one home of what makes computed eigenpairs a basis: accept, relax or fail from
 *        per-pair figures, the sign of each harmonic, the D-orthonormality (Gram) check.
 *
 * Both engines decide through it: the core's (Basis.cxx, SolveWithFallbacks; Verification.cxx,
 * CheckSomeResiduals; EigenSolver.cxx, the signs) and the distributed SLEPc one
 * (Distributed/Solve.cxx, Distributed/Assembly.cxx), which measures its figures on distributed
 * vectors and hands them here. The figures themselves (relative residual in the D^-1 norm,
 * componentwise backward error) are defined in Verification.h.
 *
 * The rule: a pair is accepted when its relative residual is within the residual tolerance or
 * its backward error within the backward tolerance. When a pair misses both, the operators'
 * achievable residual (AchievableResidual: what double precision resolves on them) decides:
 * not above the tolerance, the failure stands; above MeaningfulResidual, the pairs would be
 * meaningless (a failure that says why); in between, the tolerance is relaxed to it, with
 * RelaxedResidualWarning.
 *
 * Tested by Testing/Core/TestAcceptance.cxx.
 */
#ifndef spectral_Acceptance_h
#define spectral_Acceptance_h

#include "Common/Mesh.h"

#include <string>

namespace spectral
{
/**
 * The relative residual eigenpairs can meet in double precision: round-off in L h is about
 * eps lambda_max, measured against the lowest frequencies, (pi / d)^2 for a mesh of diameter d;
 * 10 eps lambda_max / (pi / d)^2. Solvers that miss ResidualTolerance on a badly conditioned
 * mesh (needles, slivers, tiny triangles) accept this instead, with RelaxedResidualWarning,
 * up to MeaningfulResidual.
 * \param top lambda_max from Gershgorin's bound on D^-1 L: max_i sum_j |L_ij| / D_i (D the row
 *        sums of M).
 * \param diameter The mesh's diameter, in the units of L and M.
 * \param ratio Set to lambda_max / (pi / d)^2.
 */
double AchievableResidual(double top, double diameter, double& ratio);

/// Beyond this relative residual the eigenpairs would be meaningless: an error, not a warning.
constexpr double MeaningfulResidual = 1e-4;

/// Why a mesh cannot reach the tolerance, for messages: its conditioning `ratio`.
std::string BadConditioning(double ratio);

/// The warning of a solve verified to `achievable` instead of `tolerance`.
std::string RelaxedResidualWarning(double achievable, double tolerance, double ratio);

/// What a failure beyond MeaningfulResidual adds to the solver's message.
std::string UnresolvableResidual(double ratio);

/// What to do with a set of eigenpairs.
enum class Verdict
{
  /// Every pair meets the tolerances.
  Accept,
  /// Every pair meets the tolerances with the residual tolerance relaxed to the achievable one.
  Relax,
  /// A pair misses them (Decision::Error says which and why).
  Fail
};

/// The decision on a set of pairs (AcceptPairs) or on a relaxation (Relaxation).
struct Decision
{
  Verdict Outcome = Verdict::Accept;
  /// The residual tolerance the pairs are verified to: the requested one, or the achievable
  /// one when relaxed.
  double ResidualTolerance = 0.0;
  /// The first pair above both tolerances (of the pairs given; -1 if none).
  int FailingPair = -1;
  /// RelaxedResidualWarning whenever the residual tolerance was relaxed (also when a pair then
  /// misses the relaxed one); otherwise empty.
  std::string Warning;
  /// Why the pairs fail (Fail); empty otherwise, and for a Fail of Relaxation whose failure
  /// stands as the solver reported it.
  std::string Error;
  /// False when the failure is beyond MeaningfulResidual: a lower solver tolerance cannot help,
  /// only better operators (UnresolvableResidual says how).
  bool Resolvable = true;
};

/// The tolerances a pair is checked against (EigenOptions::ResidualTolerance and
/// EigenOptions::BackwardErrorTolerance).
struct PairTolerances
{
  double Residual = 0.0;
  double Backward = 0.0;
};

/**
 * The first pair whose relative residual exceeds tolerances.Residual and whose backward error
 * exceeds tolerances.Backward (a NaN exceeds every bound), or -1.
 */
int FirstFailingPair(const Vector& relative, const Vector& backward, const PairTolerances& tolerances);

/// The message of pair `index` (eigenvalue lambda, in the caller's units) above both tolerances.
std::string PairFailure(int index,
  double lambda,
  double relative,
  double backward,
  const PairTolerances& tolerances);

/**
 * Whether a solve that missed `tolerance` may be verified to `achievable` instead (see the file
 * documentation): Fail with an empty Error (the failure stands), Fail with Error
 * UnresolvableResidual (beyond MeaningfulResidual; not Resolvable), or Relax with Warning
 * RelaxedResidualWarning and ResidualTolerance = achievable.
 */
Decision Relaxation(double tolerance, double achievable, double ratio);

/**
 * The whole decision on pairs with figures `relative` and `backward` (one entry per pair) and
 * eigenvalues `lambda` (for the messages): Accept when every pair meets `tolerances`; otherwise
 * Relaxation, and when it relaxes, the pairs checked again against the achievable residual
 * (Fail with PairFailure when one still misses it). The first pair is pair `first` in messages.
 */
Decision AcceptPairs(const Vector& lambda,
  const Vector& relative,
  const Vector& backward,
  const PairTolerances& tolerances,
  double achievable,
  double ratio,
  int first = 0);

/**
 * The sign rule of harmonics: a vector whose largest entry is `largest` and smallest `smallest`
 * is flipped when its entry of largest magnitude is negative, -smallest > largest (a tie keeps
 * the sign). It depends on the entries' values only, not on their order, so that a vector
 * distributed over processes in any way gets the sign it gets whole.
 */
inline bool FlipsSign(double largest, double smallest)
{
  return -smallest > largest;
}

/// Applies FlipsSign to every column of Phi.
void NormalizeSigns(DenseMatrix& Phi);

/// max |G - I| over all entries of a Gram matrix G = H^T M H.
double GramError(const DenseMatrix& gram);

/// How far from orthonormal pairs verified to a residual tolerance may be: GramFactor times it.
constexpr double GramFactor = 100.0;

/// Whether a Gram error is within GramFactor times the residual tolerance (false for NaN).
inline bool Orthonormal(double gramError, double residualTolerance)
{
  return gramError <= GramFactor * residualTolerance;
}
} // namespace spectral

#endif
