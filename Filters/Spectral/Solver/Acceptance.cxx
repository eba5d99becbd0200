// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/Acceptance.h"
#include "Common/Constants.h"
#include "Solver/Diagnostics.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace spectral
{
//------------------------------------------------------------------------------
double AchievableResidual(double top, double diameter, double& ratio)
{
  ratio = top * diameter * diameter / (Pi * Pi);
  return 10.0 * std::numeric_limits<double>::epsilon() * ratio;
}

//------------------------------------------------------------------------------
std::string BadConditioning(double ratio)
{
  std::ostringstream why;
  why << "the operators are badly conditioned (largest / lowest eigenvalue about " << ratio
      << ", from needle, sliver or tiny triangles)";
  return why.str();
}

//------------------------------------------------------------------------------
std::string RelaxedResidualWarning(double achievable, double tolerance, double ratio)
{
  std::ostringstream text;
  text << "Eigenpairs verified to a relative residual of " << achievable << " instead of "
       << tolerance << ": " << BadConditioning(ratio)
       << ". Laplacian = Intrinsic Delaunay or remeshing improves this.";
  return text.str();
}

//------------------------------------------------------------------------------
std::string UnresolvableResidual(double ratio)
{
  return BadConditioning(ratio) +
    " beyond what double precision resolves: remove them (merge close points, e.g. with "
    "vtkCleanPolyData and a tolerance) or remesh";
}

//------------------------------------------------------------------------------
int FirstFailingPair(const Vector& relative, const Vector& backward, const PairTolerances& tolerances)
{
  for (Eigen::Index k = 0; k < relative.size(); ++k)
  {
    const bool residualMissed = !(relative[k] <= tolerances.Residual);
    const bool backwardMissed = k >= backward.size() || !(backward[k] <= tolerances.Backward);
    if (residualMissed && backwardMissed)
    {
      return static_cast<int>(k);
    }
  }
  return -1;
}

//------------------------------------------------------------------------------
std::string PairFailure(int index,
  double lambda,
  double relative,
  double backward,
  const PairTolerances& tolerances)
{
  using detail::Str;
  return "eigenpair " + std::to_string(index) + " (lambda = " + Str(lambda) +
    ") has relative residual " + Str(relative) + " and backward error " + Str(backward) +
    ", above the tolerances " + Str(tolerances.Residual) + " and " + Str(tolerances.Backward);
}

//------------------------------------------------------------------------------
Decision Relaxation(double tolerance, double achievable, double ratio)
{
  Decision decision;
  decision.ResidualTolerance = tolerance;
  if (!(achievable > tolerance))
  {
    decision.Outcome = Verdict::Fail;
  }
  else if (achievable > MeaningfulResidual)
  {
    decision.Outcome = Verdict::Fail;
    decision.Resolvable = false;
    decision.Error = UnresolvableResidual(ratio);
  }
  else
  {
    decision.Outcome = Verdict::Relax;
    decision.ResidualTolerance = achievable;
    decision.Warning = RelaxedResidualWarning(achievable, tolerance, ratio);
  }
  return decision;
}

//------------------------------------------------------------------------------
Decision AcceptPairs(const Vector& lambda,
  const Vector& relative,
  const Vector& backward,
  const PairTolerances& tolerances,
  double achievable,
  double ratio,
  int first)
{
  const auto failure = [&](int k, const PairTolerances& used)
  { return PairFailure(first + k, lambda[k], relative[k], backward[k], used); };
  Decision decision;
  decision.ResidualTolerance = tolerances.Residual;
  decision.FailingPair = FirstFailingPair(relative, backward, tolerances);
  if (decision.FailingPair < 0)
  {
    return decision;
  }
  const int failing = decision.FailingPair;
  Decision relaxed = Relaxation(tolerances.Residual, achievable, ratio);
  if (relaxed.Outcome == Verdict::Fail)
  {
    relaxed.FailingPair = failing;
    relaxed.Error =
      failure(failing, tolerances) + (relaxed.Error.empty() ? std::string() : "; " + relaxed.Error);
    return relaxed;
  }
  const PairTolerances loose = { relaxed.ResidualTolerance, tolerances.Backward };
  relaxed.FailingPair = FirstFailingPair(relative, backward, loose);
  if (relaxed.FailingPair >= 0)
  {
    relaxed.Outcome = Verdict::Fail;
    relaxed.Error = failure(relaxed.FailingPair, loose);
  }
  return relaxed;
}

//------------------------------------------------------------------------------
void NormalizeSigns(DenseMatrix& Phi)
{
  for (Eigen::Index k = 0; k < Phi.cols(); ++k)
  {
    if (Phi.rows() > 0 && FlipsSign(Phi.col(k).maxCoeff(), Phi.col(k).minCoeff()))
    {
      Phi.col(k) *= -1.0;
    }
  }
}

//------------------------------------------------------------------------------
double GramError(const DenseMatrix& gram)
{
  if (gram.size() == 0)
  {
    return 0.0;
  }
  return (gram - DenseMatrix::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff();
}
} // namespace spectral
