// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SpectraBand.h
 * @brief One shift-invert band with Spectra's implicitly restarted Lanczos
 *        (LanczosMethod::Spectra): SymGEigsShiftSolver on (L - sigma M)^-1 M in the M inner
 *        product, one vector at a time.
 *
 * The alternative to BlockLanczos.h, kept as a reference. Used by Bands; tested by
 * Testing/Core/TestEigenSolver.cxx (MethodsAgree).
 */
#ifndef spectral_SpectraBand_h
#define spectral_SpectraBand_h

#include "Common/Monitor.h"
#include "Solver/BandWorkspace.h"
#include "Solver/EigenSolver.h"
#include "Solver/Factorization.h"
#include "Solver/MassMatrix.h"

namespace spectral
{
namespace detail
{
/**
 * The request.Pairs eigenpairs nearest request.Sigma with Spectra's shift-invert Lanczos in the
 * M inner product, on `factor` (already factored at the shift). Attempt 0 starts from Spectra's
 * default vector, later attempts (fewer pairs, RetryPairs in Bands.h) from other random vectors
 * in the subspace of the first (BandRequest::SubspacePairs).
 * \param M the mass matrix of the pencil (the identity after a diagonal mass is scaled) and the
 *        null vectors the iteration stays M-orthogonal to.
 * \param monitor polled for cancellation before every operator application.
 * \param work the band's vectors, ascending, go into the first columns of work.Basis.
 * \throws SolverFailure if the band does not converge.
 */
Band RunSpectraBand(const ShiftedFactor& factor,
  const MassMatrix& M,
  const BandRequest& request,
  const EigenOptions& options,
  const Monitor& monitor,
  Workspace& work);
} // namespace detail
} // namespace spectral

#endif
