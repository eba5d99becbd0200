// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Solve.h
 * @brief The distributed engine: the smallest eigenpairs of a mesh held in pieces by the
 *        processes of an MPI communicator, on SLEPc/PETSc, without VTK and without gathering.
 *
 * Built only with SLEPc (MANIFOLDHARMONICS_HAS_SLEPC); the VTK adapter is
 * vtkManifoldHarmonicsSlepc.cxx, the test without VTK Testing/Core/TestDistributed.cxx. The
 * stages (all collective over the communicator):
 *
 * 1. Piece. Each process keeps its cells of non-zero size (PrepareMesh); triangles on some
 *    processes and tetrahedra on others are refused on all; the global bounding box.
 * 2. Numbering (Numbering.h): the border points of all pieces merged by the one seam rule
 *    (Common/Seams.h), each point owned by the copy of the owner rule, numbered contiguously.
 * 3. Assembly (Assembly.h): each piece's stiffness and mass by the core's formulas, in units of
 *    UnitScale of the global diameter, added up into PETSc matrices by global number.
 * 4. Zero modes: the connected components (DistributedComponents) give the first harmonics, the
 *    constant 1 / sqrt(mass) on each, the largest components first, eigenvalue exactly 0.
 *    Spectrum slicing refuses a deflation space, so they are deflated from SLEPc's pairs: a pair
 *    whose vector lies more than half (D-norm) in their span is a zero eigenvalue as rounded and
 *    is left out, every other is projected onto their D-orthogonal complement. With m no more
 *    than the components, there is no eigensolve.
 * 5. Interval: [a, b], a = -lambda_1 / 2 and b = 1.2 lambda_(m+1) by Weyl's law
 *    (WeylEigenvalue), b widened until the inertia of Q - b D counts at least m eigenvalues.
 *    With a frequency window, its ends (a = -lambda_1 / 2 for a lower end 0), and m the
 *    difference of the inertia counts there.
 * 6. Eigensolve (Pairs.h): Krylov-Schur spectrum slicing of [a, b] in slices of about 200
 *    eigenvalues, ascending, until m pairs are found; between slices the cancel flag is polled
 *    (on every process: any cancels all) and progress reported. Each pair is D-normalized, given
 *    the sign of the sign rule (Acceptance.h), measured, and scattered to the rows of every
 *    process's points (copies of seam points owned elsewhere included): those rows are the only
 *    copy of the harmonics a process keeps.
 * 7. Verify: the pairs' figures decided by the acceptance module (accept / relax / fail, the
 *    Gram check of the written rows, Acceptance.h), as for the core's engine.
 * 8. Write: mass and ownership flags of the piece's points; components that no harmonic
 *    represents get zero mass, as in the core (Basis.cxx, LeaveOutUnrepresented).
 */
#ifndef spectral_Distributed_Solve_h
#define spectral_Distributed_Solve_h

#include "Common/Defaults.h"
#include "Common/Mesh.h"
#include "Common/Monitor.h"
#include "Common/Seams.h"
#include "Filtering/Transfer.h"
#include "Solver/EigenSolver.h"

#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

namespace spectral
{
/// What the distributed engine computes and how.
struct DistributedOptions
{
  /// m, the number of smallest eigenpairs (clamped, with a warning, to the number of points).
  int NumberOfHarmonics = DefaultNumberOfHarmonics;
  /// The consistent (Galerkin) mass instead of the lumped one.
  bool ConsistentMass = false;
  /// SLEPc's npart: sub-intervals solved at once by groups of processes (clamped, with a
  /// warning, to the number of processes).
  int Partitions = 1;
  /// Options for PETSc's options database (PetscOptionsInsertString syntax), applied after the
  /// solver's own, for this solve only.
  std::string Options;
  /// Convergence tolerance and iteration limit of Krylov-Schur (the core's defaults).
  double Tolerance = EigenOptions().Tolerance;
  int MaxIterations = EigenOptions().MaxIterations;
  /// The seam rule (Common/Seams.h) on the pieces' border points: points within SeamTolerance
  /// of the bounding box diagonal are one point. With WeldSeams off, a run on one process keeps
  /// every point apart; several processes always merge (the pieces must be joined).
  bool WeldSeams = true;
  double SeamTolerance = DefaultSeamTolerance;
  /**
   * The frequency window [LowerFrequency, UpperFrequency): when IsFrequencyWindow (Basis.h), the
   * harmonics whose frequency omega = sqrt(lambda) lies in it instead of the NumberOfHarmonics
   * smallest, as BasisOptions's (the same rule, Problem.h WindowEigenvalues): their number is the
   * difference of the inertia counts at its ends, and the spectrum slicing starts at its lower end
   * (the constants are among them when it starts at 0).
   */
  double LowerFrequency = 0.0;
  double UpperFrequency = 0.0;
  /// One flag per point of the piece: nonzero for its own points, zero for ghost copies of
  /// another piece's points (the owner rule of Seams.h); empty: all its own.
  std::vector<unsigned char> OwnedPoints;
  /**
   * Where the harmonics go: called once with the number of rows (the piece's points) and m,
   * returns row-major storage for rows * m values (the caller's output array), which the solve
   * fills (zeros on unused points). Without it, DistributedResult::Harmonics holds them.
   */
  std::function<double*(Eigen::Index rows, int m)> HarmonicsStorage;
};

/// The result on one process: the rows of its points, and the figures of the whole solve.
struct DistributedResult
{
  /// The harmonics of the piece's points (n_r by m), unless DistributedOptions::HarmonicsStorage
  /// took them.
  RowMatrix Harmonics;
  /// The m eigenvalues (on every process), ascending.
  Vector Eigenvalues;
  /// The lumped mass of the piece's points (n_r).
  Vector Mass;
  /// Whether each point of the piece is a copy of a point owned elsewhere (n_r).
  std::vector<unsigned char> Duplicate;
  /// Largest componentwise backward error and relative residual of the m pairs.
  double MaxBackwardError = 0.0;
  double MaxResidual = 0.0;
  /// max |H^T M H - I| over all entries (GramError).
  double OrthonormalityError = 0.0;
  /// Eigenvalues in the slices solved (MUMPS inertia at their ends, zero eigenvalues in them
  /// included), the number SLEPc computed there, and the upper end (in the units of the mesh);
  /// all 0 when the constants of the components are all the harmonics asked for.
  int InertiaCount = 0;
  int Computed = 0;
  double UpperEnd = 0.0;
  /// With a frequency window: the number of eigenvalues below its lower end (the index of the
  /// first returned pair among all); otherwise 0.
  int FirstIndex = 0;
  /// Points of the whole mesh (after merging seams) and owned by this process.
  long long GlobalPoints = 0;
  long long OwnedPoints = 0;
  /// Number of shifts (factorizations) of the spectrum slicing.
  int Shifts = 0;
};

/**
 * The m smallest eigenpairs of the mesh whose piece `piece` this process holds (its points, its
 * triangles or tetrahedra, ghost cells already left out), collective over `comm`, which must be
 * PETSC_COMM_WORLD's processes. Initializes SLEPc on first use. Warnings go to the monitor of
 * process 0 only. \throws std::runtime_error with a message for the user (alike on every
 * process), spectral::Cancelled when the monitor of any process cancels.
 */
DistributedResult SolveDistributed(MPI_Comm comm,
  const TriangleMesh& piece,
  const DistributedOptions& options,
  const Monitor& monitor = Monitor());
} // namespace spectral

#endif
