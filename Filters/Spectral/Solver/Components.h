// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Components.h
 * @brief The smallest eigenpairs of a disconnected mesh, one component at a time.
 *
 * The operators of a mesh with several connected components are block diagonal, and their
 * eigenpairs are the union of the components' eigenpairs (each extended by zero). Solving each
 * component on its own gives exactly one zero eigenvalue per component, however many there are
 * (a single solve would need a band holding all of them, and scans carry hundreds of islands),
 * keeps the residual test of each component on its own scale, and solves tiny components
 * densely (SmallestEigenpairs does for any problem of at most EigenOptions::DenseThreshold
 * unknowns).
 *
 * How many pairs each component needs is not known in advance: component c is first asked for
 * k_c = its share of m by area (Weyl's law: the number of eigenvalues below lambda grows as
 * area lambda / 4 pi) with a margin. The m smallest of the union are then taken; a component
 * whose largest computed eigenvalue lies below the m-th smallest of the union, and which has
 * more eigenpairs than it was asked for, may hide eigenvalues below it: it is solved again with
 * twice as many pairs, until none is. Each component's solve proves (by inertia) that no
 * eigenvalue below its largest computed one is missing, so the union is proven too.
 *
 * Used by Basis.cxx; tested by Testing/Core/TestBasis.cxx (Components*).
 */
#ifndef spectral_Components_h
#define spectral_Components_h

#include "Common/Mesh.h"
#include "Common/Monitor.h"
#include "Solver/EigenSolver.h"

#include <functional>
#include <utility>
#include <vector>

namespace spectral
{
/// What a PairSolver is asked for: Count pairs from index StartIndex of the spectrum, the
/// first StartIndex eigenvalues lying below StartValue (as in EigenOptions).
struct PairRequest
{
  int Count = 0;
  int StartIndex = 0;
  double StartValue = 0.0;
};

/// Solves L h = lambda M h for the requested pairs (with whatever fallbacks the caller wants).
using PairSolver = std::function<EigenResult(const SparseMatrix& L,
  const SparseMatrix& M,
  const PairRequest& request,
  const Monitor& monitor)>;

/// How SmallestEigenpairsByComponent chose its pairs.
struct ComponentChoice
{
  /// For each component, the pairs its last solve was asked for (PairRequest::Count).
  std::vector<int> Asked;
  /// For each component, the residual tolerance its last solve verified to
  /// (EigenResult::ResidualTolerance).
  std::vector<double> Tolerance;
  /// For each returned pair, in the order returned: its component and its index among that
  /// component's pairs (the pairs of a component are a prefix of its spectrum).
  std::vector<std::pair<int, int>> Pairs;
};

/**
 * The m smallest eigenpairs of block-diagonal operators, component by component.
 * \param L, M The operators (n by n) of a mesh whose points are labelled by component.
 * \param weight The lumped mass of each point (the area share of each component).
 * \param label For each point, its component in [0, count).
 * \param count Number of components, >= 1.
 * \param m Number of pairs, 1 <= m <= n.
 * \param solve The solver of one component.
 * \param monitor Progress in [0, 1] over all components, and cancellation.
 * \return Eigenvalues ascending, eigenvectors n by m, each zero outside its component; the
 *         statistics summed (MaxResidual and MaxBackwardError: the largest). The zero eigenvalues
 * (the first of each component) come first, the largest components' first, so that when m is below
 * the number of components the basis describes the largest ones. \param constantHarmonics Whether
 * the first pair of each component is its constant harmonic of eigenvalue 0 (Neumann conditions);
 * false for Dirichlet conditions, where every pair is ordered by its eigenvalue alone.
 * \param choice If given, set to how the pairs were chosen (what ForEachChosenComponent repeats).
 */
EigenResult SmallestEigenpairsByComponent(const SparseMatrix& L,
  const SparseMatrix& M,
  const Vector& weight,
  const std::vector<int>& label,
  int count,
  int m,
  const PairSolver& solve,
  const Monitor& monitor = Monitor(),
  bool constantHarmonics = true,
  ComponentChoice* choice = nullptr);

/// The statistics of `part` added to those of `total` (MaxResidual and MaxBackwardError: the
/// largest).
void AddStatistics(EigenResult& total, const EigenResult& part);

/// Solves one component (`component`, whose points are `rows` of the whole operators).
using ComponentSolver = std::function<void(int component,
  const std::vector<int>& rows,
  const SparseMatrix& L,
  const SparseMatrix& M,
  const PairRequest& request,
  const Monitor& monitor)>;

/**
 * The solves of SmallestEigenpairsByComponent again, as `choice` records them: each component
 * that has a chosen pair, in component order, with the request of its last solve (the same
 * operators and request: the same pairs), for a caller that streams them (Basis.h, BasisSink).
 * \param L, M, label, count As SmallestEigenpairsByComponent (count <= 1: the whole operators).
 * \param monitor Progress over the components, and cancellation.
 */
void ForEachChosenComponent(const SparseMatrix& L,
  const SparseMatrix& M,
  const std::vector<int>& label,
  int count,
  const ComponentChoice& choice,
  const ComponentSolver& solve,
  const Monitor& monitor = Monitor());

/// Told the eigenvalues below a frequency window and in it, once they are counted.
using WindowCounted = std::function<void(int below, int inWindow)>;

/**
 * The eigenpairs with eigenvalues in [low, high) of block-diagonal operators, component by
 * component: the inertia of each component's L - low M and L - high M (Sylvester's law) counts
 * its eigenvalues below both ends, so each component is asked for exactly its pairs in the
 * window, starting there (PairRequest::StartIndex), and the union is proven.
 * \param low, high The window, 0 <= low < high; no eigenvalue may equal either end.
 * \param counted Called once the counts are known, before any solve, with the number of
 *        eigenvalues below low and in the window over all components (for memory checks and
 *        errors: it may throw); may be empty.
 * \param below Set to the number of eigenvalues below low, over all components.
 * \return The pairs ascending, eigenvectors (if the solver returns them) zero outside their
 *         component; statistics as SmallestEigenpairsByComponent.
 * \throws SolverFailure if an inertia count fails (an end is an eigenvalue).
 */
EigenResult EigenpairsInWindowByComponent(const SparseMatrix& L,
  const SparseMatrix& M,
  const std::vector<int>& label,
  int count,
  double low,
  double high,
  const PairSolver& solve,
  const WindowCounted& counted,
  int& below,
  const Monitor& monitor = Monitor());
} // namespace spectral

#endif
