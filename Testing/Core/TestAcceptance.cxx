// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The decisions of the acceptance module (Filters/Spectral/Solver/Acceptance.h) on constructed
// figures: accept, relax or fail; the sign rule; the Gram check. Both engines (the core and the
// SLEPc solver) decide through these functions, so these are the verdicts of both.
#include "Checks.h"
#include "Solver/Acceptance.h"

#include <limits>
#include <string>

using namespace spectral;
using namespace spectral::testing;

namespace
{
const PairTolerances Tolerances = { 1e-8, 1e-10 };

Vector Values(std::initializer_list<double> values)
{
  Vector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double x : values)
  {
    v[i++] = x;
  }
  return v;
}

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

//------------------------------------------------------------------------------
// A pair is accepted when either figure meets its tolerance: residual alone, backward error
// alone, or both.
void AcceptsWithinEitherTolerance()
{
  const Vector lambda = Values({ 0.0, 1.0, 2.0 });
  const Vector relative = Values({ 1e-9, 1e-3, 1e-12 });
  const Vector backward = Values({ 1e-3, 1e-12, 1e-12 });
  const Decision d = AcceptPairs(lambda, relative, backward, Tolerances, 1e-12, 1.0);
  Check(d.Outcome == Verdict::Accept, "residual or backward error within tolerance: accepted");
  Check(d.FailingPair == -1 && d.Error.empty() && d.Warning.empty(), "no failing pair, no text");
  CheckNear(d.ResidualTolerance, Tolerances.Residual, 0.0, "verified to the requested tolerance");
}

//------------------------------------------------------------------------------
// A pair above both tolerances fails when the operators achieve the tolerance (no relaxing):
// the message names the pair (numbered from `first`), its eigenvalue and figures.
void FailsWhenTheToleranceIsAchievable()
{
  const Vector lambda = Values({ 0.0, 4.5 });
  const Vector relative = Values({ 1e-12, 1e-6 });
  const Vector backward = Values({ 1e-12, 1e-6 });
  const Decision d = AcceptPairs(lambda, relative, backward, Tolerances, 1e-9, 1.0, 10);
  Check(d.Outcome == Verdict::Fail, "pair above both tolerances, achievable below: fails");
  Check(d.FailingPair == 1, "the failing pair is the second");
  Check(d.Resolvable, "a lower solver tolerance could help");
  Check(d.Warning.empty(), "no relaxation announced");
  Check(Contains(d.Error, "eigenpair 11 ") && Contains(d.Error, "lambda = 4.5"),
    "the message names pair first + 1 and its eigenvalue: " + d.Error);
  Check(Relaxation(1e-8, 1e-8, 1.0).Outcome == Verdict::Fail &&
      Relaxation(1e-8, 1e-8, 1.0).Error.empty(),
    "achievable equal to the tolerance: the failure stands as reported");
}

//------------------------------------------------------------------------------
// Between the tolerance and MeaningfulResidual the tolerance is relaxed to the achievable
// residual, with the warning, and the pairs are checked against it.
void RelaxesToTheAchievableResidual()
{
  const Vector lambda = Values({ 0.0, 1.0 });
  const Vector relative = Values({ 1e-12, 3e-7 });
  const Vector backward = Values({ 1e-12, 1e-6 });
  const Decision d = AcceptPairs(lambda, relative, backward, Tolerances, 5e-7, 2e7);
  Check(d.Outcome == Verdict::Relax, "a pair within the achievable residual: relaxed");
  CheckNear(d.ResidualTolerance, 5e-7, 0.0, "verified to the achievable residual");
  Check(d.Error.empty() && d.FailingPair == -1, "no failure after relaxing");
  Check(Contains(d.Warning, "instead of") && Contains(d.Warning, "badly conditioned"),
    "the warning says the tolerance and why: " + d.Warning);
  const Decision alone = Relaxation(1e-8, 5e-7, 2e7);
  Check(alone.Outcome == Verdict::Relax && alone.ResidualTolerance == 5e-7 &&
      alone.Warning == d.Warning,
    "Relaxation (the core's retry) decides and words it the same way");
}

//------------------------------------------------------------------------------
// A pair above the relaxed tolerance too fails, naming the relaxed tolerance; the relaxation
// is still announced.
void FailsAboveTheRelaxedTolerance()
{
  const Vector lambda = Values({ 1.0, 2.0 });
  const Vector relative = Values({ 1e-7, 1e-5 });
  const Vector backward = Values({ 1e-6, 1e-6 });
  const Decision d = AcceptPairs(lambda, relative, backward, Tolerances, 5e-7, 2e7);
  Check(d.Outcome == Verdict::Fail && d.FailingPair == 1, "the second pair fails relaxed too");
  Check(d.Resolvable, "resolvable: a lower solver tolerance could help");
  Check(Contains(d.Error, "5e-07"), "the message names the relaxed tolerance: " + d.Error);
  Check(!d.Warning.empty(), "the relaxation is announced");
}

//------------------------------------------------------------------------------
// Beyond MeaningfulResidual the pairs are meaningless: a failure that says what to change.
void FailsBeyondMeaningfulResidual()
{
  const Vector lambda = Values({ 1.0 });
  const Vector relative = Values({ 1e-5 });
  const Vector backward = Values({ 1e-5 });
  const Decision d = AcceptPairs(lambda, relative, backward, Tolerances, 2.0 * MeaningfulResidual, 1e16);
  Check(d.Outcome == Verdict::Fail && !d.Resolvable, "achievable beyond meaningful: fails");
  Check(Contains(d.Error, "eigenpair 0") && Contains(d.Error, "beyond what double precision"),
    "the message names the pair and the remedy: " + d.Error);
  Check(d.Warning.empty(), "no relaxation announced");
}

//------------------------------------------------------------------------------
// A figure that is NaN meets no tolerance; an achievable residual that is NaN relaxes nothing.
void NaNFiguresFail()
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vector lambda = Values({ 1.0 });
  const Decision d = AcceptPairs(lambda, Values({ nan }), Values({ nan }), Tolerances, 1e-6, 1.0);
  Check(d.Outcome == Verdict::Fail, "NaN figures fail");
  Check(Relaxation(1e-8, nan, 1.0).Outcome == Verdict::Fail, "a NaN achievable residual fails");
  Check(FirstFailingPair(Values({ 1.0 }), Vector(), Tolerances) == 0,
    "without backward errors the residual alone decides");
}

//------------------------------------------------------------------------------
// The entry of largest magnitude becomes positive; an exact tie keeps the sign, whatever the
// order of the rows (a vector distributed over processes gets the sign it gets whole).
void SignsFromValuesNotOrder()
{
  DenseMatrix Phi(4, 2);
  Phi << 0.1, -1.0, //
    -3.0, 2.0,      //
    2.0, 1.0,       //
    0.5, -2.0;
  NormalizeSigns(Phi);
  Check(Phi(1, 0) == 3.0 && Phi(0, 0) == -0.1, "largest magnitude negative: column flipped");
  Check(Phi(1, 1) == 2.0 && Phi(3, 1) == -2.0, "a tie keeps the sign");
  DenseMatrix reversed = Phi.colwise().reverse();
  DenseMatrix tie(2, 1);
  tie << -1.0, 1.0;
  DenseMatrix swapped(2, 1);
  swapped << 1.0, -1.0;
  NormalizeSigns(tie);
  NormalizeSigns(swapped);
  Check(tie(0, 0) == -1.0 && swapped(0, 0) == 1.0,
    "(-1, 1) and (1, -1) both keep their signs: the rule does not depend on the row order");
  NormalizeSigns(reversed);
  Check(reversed == DenseMatrix(Phi.colwise().reverse()), "reversed rows: the same signs");
  Check(FlipsSign(1.0, -2.0) && !FlipsSign(2.0, -1.0) && !FlipsSign(1.0, -1.0),
    "FlipsSign: flip when -smallest > largest only");
}

//------------------------------------------------------------------------------
// The Gram check: max |G - I|, within GramFactor times the residual tolerance.
void GramCheck()
{
  DenseMatrix G = DenseMatrix::Identity(3, 3);
  CheckNear(GramError(G), 0.0, 0.0, "identity: no error");
  G(0, 2) = G(2, 0) = -3e-9;
  G(1, 1) = 1.0 + 1e-9;
  CheckNear(GramError(G), 3e-9, 1e-24, "largest |G - I| of any entry, off-diagonal and signed");
  Check(Orthonormal(GramError(G), 1e-10) && !Orthonormal(GramError(G), 1e-11),
    "within 100 times the residual tolerance, not 10");
  Check(!Orthonormal(std::numeric_limits<double>::quiet_NaN(), 1.0), "NaN is not orthonormal");
  CheckNear(GramError(DenseMatrix()), 0.0, 0.0, "no pairs: no error");
}

const Case Cases[] = {
  { "AcceptsWithinEitherTolerance", AcceptsWithinEitherTolerance },
  { "FailsWhenTheToleranceIsAchievable", FailsWhenTheToleranceIsAchievable },
  { "RelaxesToTheAchievableResidual", RelaxesToTheAchievableResidual },
  { "FailsAboveTheRelaxedTolerance", FailsAboveTheRelaxedTolerance },
  { "FailsBeyondMeaningfulResidual", FailsBeyondMeaningfulResidual },
  { "NaNFiguresFail", NaNFiguresFail },
  { "SignsFromValuesNotOrder", SignsFromValuesNotOrder },
  { "GramCheck", GramCheck },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
