// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsSlepc.h
 * @brief Private helper of vtkManifoldHarmonicBasis: the distributed eigensolve on SLEPc/PETSc
 *        (Solver SLEPC), built only when CMake finds SLEPc (MANIFOLDHARMONICS_HAS_SLEPC).
 *
 * Every process of the run passes its own piece of the mesh, a surface (triangles) or a volume
 * (tetrahedra); nothing is gathered on one process. The steps (all collective over
 * PETSC_COMM_WORLD, which is MPI_COMM_WORLD, the communicator of ParaView's global controller):
 *
 * 1. Global point numbers. Each process keeps its cells of non-zero size
 *    (spectral::PrepareMesh; the caller leaves ghost cells out) and the points they use. The
 *    points on the border of its piece (on a facet, an edge of a triangle or a face of a
 *    tetrahedron, that fewer or more than two of its cells share) are the only ones another
 *    piece can hold: every process receives these seam points of all processes (O(sqrt n) per
 *    piece on a surface, O(n^(2/3)) in a volume, not the mesh) and merges them with the seam
 *    rule of every path, vtkManifoldHarmonicsParallel::WeldPoints (within SeamTolerance of the
 *    bounding box diagonal, in rank order, so every process finds the same merge). A point is
 *    owned by the lowest rank that holds it; each process numbers its owned points contiguously
 *    after those of the lower ranks.
 * 2. Assembly. Each process computes the stiffness (cotan, or P1 for tetrahedra) and the mass
 *    (lumped or consistent) of its own cells with the core's formulas (Operators.h), in units
 *    of spectral::UnitScale
 *    of the global diameter, and adds them into distributed PETSc AIJ matrices by global number
 *    (MatSetValues ADD_VALUES; PETSc sends the rows of other processes at assembly).
 * 3. Zero modes, then the eigensolve. The connected components (DistributedComponents: each
 *    process's own, joined across processes through the border points' global numbers) give
 *    the first harmonics: the constant 1/sqrt(mass of the component) on each, the largest
 *    components (most points) first, with eigenvalue exactly 0 (Q 1 = 0). Spectrum slicing
 *    refuses a deflation space (EPSSetDeflationSpace), so the constants are deflated from
 *    SLEPc's pairs: a pair whose vector lies more than half (D-norm) in their span is a zero
 *    eigenvalue as rounded (on debris with near-coincident points as large as 1e-5 of its
 *    largest eigenvalue, or negative) and is left out; every other is projected onto their
 *    D-orthogonal complement. Each harmonic's entry of largest magnitude is made positive, as
 *    by the built-in solver. With m no more than the components, there is no eigensolve.
 *    The interval [a, b] with a = -lambda_1 / 2 and b = 1.2 lambda_(m+1) by Weyl's
 *    law (spectral::WeylEigenvalue of the area or volume; a is below the zero eigenvalue of the
 *    singular stiffness), b widened until the inertia of a MUMPS LDL^T factorization of
 *    Q - b D counts at least m eigenvalues below b (the zero ones among them). SLEPc's Krylov-Schur computes every
 *    eigenpair of [a, b] by spectrum slicing (shift-and-invert, MUMPS Cholesky with inertia,
 *    ICNTL(13) = 1 and ICNTL(24) = 1; npart sub-intervals solved by groups of processes at
 *    once), in slices of about 200 eigenvalues, ascending, until m pairs are found: between
 *    slices the abort flag is polled (on every process) and progress reported, since spectrum
 *    slicing calls no monitor. In each slice the inertia at its ends must count the pairs SLEPc
 *    returned (zero eigenvalues included). The m - C smallest non-zero pairs are kept (C the
 *    constants written) and D-normalized.
 * 4. Rows and checks. Each pair is checked on the distributed vectors (relative residual and
 *    componentwise backward error, the core's definitions and tolerances, Verification.h; a
 *    pair above both is an error) and a VecScatter writes its values into the rows of every
 *    process's points, copies of seam points owned elsewhere included (flagged
 *    DUPLICATEPOINT, as in the gather path). Those rows are the only copy of the harmonics a
 *    process keeps: the D-orthonormality is measured against them, 32 pairs at a time.
 *
 * Errors of SLEPc, PETSc and MUMPS are thrown as std::runtime_error carrying their message and
 * what to change; they arise on every process alike (the calls are collective).
 */
#ifndef vtkManifoldHarmonicsSlepc_h
#define vtkManifoldHarmonicsSlepc_h

#include "vtkManifoldHarmonicsParallel.h"

#include <functional>
#include <stdexcept>
#include <string>

class vtkMultiProcessController;
namespace spectral
{
struct TriangleMesh;
}

namespace vtkManifoldHarmonicsSlepc
{
/// What the filter asks of the solve.
struct Settings
{
  /// m, the number of smallest eigenpairs.
  int NumberOfHarmonics = 0;
  /// The consistent (Galerkin) mass instead of the lumped one.
  bool ConsistentMass = false;
  /// SLEPc's npart: sub-intervals solved at once by groups of processes (clamped to the number
  /// of processes).
  int Partitions = 1;
  /// Options for PETSc's options database (PetscOptionsInsertString syntax), applied after the
  /// solver's own, for this solve only.
  std::string Options;
  /// Convergence tolerance and iteration limit of Krylov-Schur.
  double Tolerance = 1e-11;
  int MaxIterations = 1000;
  /// The seam rule (vtkManifoldHarmonicsParallel::WeldPoints on the pieces' border points):
  /// points within SeamTolerance of the bounding box diagonal are one point. With WeldSeams off,
  /// a run on one process keeps every point apart; several processes always merge (the pieces
  /// must be joined).
  bool WeldSeams = true;
  double SeamTolerance = vtkManifoldHarmonicsParallel::SeamTolerance;
  /// Progress in [0, 1], a stage name, and the abort flag (polled between Krylov-Schur
  /// iterations; every process stops when one is cancelled).
  std::function<void(double)> Progress;
  std::function<void(const char*)> Stage;
  std::function<bool()> Cancelled;
  std::function<void(const std::string&)> Warning;
};

/// The result on one process: the rows of its points, and the figures of the whole solve.
struct Result
{
  /// Harmonics (n_r by m), lumped mass (n_r) and DUPLICATEPOINT flags (n_r) of the piece's
  /// points, and the m eigenvalues (on every process).
  vtkManifoldHarmonicsParallel::PieceBasis Rows;
  /// Largest componentwise backward error and relative residual of the m pairs.
  double MaxBackwardError = 0.0;
  double MaxResidual = 0.0;
  /// max |H^T M H - I| over all entries.
  double OrthonormalityError = 0.0;
  /// Eigenvalues in the slices solved (MUMPS inertia at their ends, zero eigenvalues in them
  /// included), the number SLEPc computed there, and the upper end (in the units of the mesh);
  /// all 0 when the constants of the components are all the harmonics asked for.
  int InertiaCount = 0;
  int Computed = 0;
  double UpperEnd = 0.0;
  /// Points of the whole surface (after merging seams) and owned by this process.
  long long GlobalPoints = 0;
  long long OwnedPoints = 0;
  /// Number of shifts (factorizations) of the spectrum slicing.
  int Shifts = 0;
};

/// Thrown when the user cancelled (on every process).
class Cancelled : public std::runtime_error
{
public:
  Cancelled()
    : std::runtime_error("cancelled")
  {
  }
};

/**
 * The m smallest eigenpairs of the mesh whose piece `piece` this process holds: every point of
 * the piece (its rows in the result are in this order) and its triangles or tetrahedra, ghost
 * cells already left out (vtkManifoldHarmonicsArrays::ToCoreMesh). Collective over all processes of
 * `controller` (nullptr or one process: a serial run), which must be those of MPI_COMM_WORLD.
 * Initializes SLEPc on first use (after MPI, which ParaView initializes; SLEPc initializes MPI
 * itself when nobody did and then finalizes both at exit). \throws std::runtime_error with a
 * message for the user, vtkManifoldHarmonicsSlepc::Cancelled.
 */
Result Solve(vtkMultiProcessController* controller,
  const spectral::TriangleMesh& piece,
  const Settings& settings);
} // namespace vtkManifoldHarmonicsSlepc

#endif
