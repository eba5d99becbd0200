// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file vtkManifoldHarmonicsSlepc.h
 * @brief Private helper of vtkManifoldHarmonicBasis: the VTK adapter of the distributed engine
 *        on SLEPc/PETSc (Solver SLEPC), built only when CMake finds SLEPc
 *        (MANIFOLDHARMONICS_HAS_SLEPC).
 *
 * Every process of the run passes its own piece of the mesh, a surface (triangles) or a volume
 * (tetrahedra); nothing is gathered on one process. The numerics are the core's, without VTK:
 * Spectral/Distributed/Solve.h (its stages: numbering with the one seam and owner rule of
 * Spectral/Common/Seams.h, assembly, zero modes, interval, spectrum slicing, the acceptance
 * module's checks, rows). This adapter checks that the controller has every process of
 * PETSC_COMM_WORLD, writes the harmonics straight into the output array, and turns the rows
 * into VTK arrays (DUPLICATEPOINT on the copies of points owned elsewhere, as in the gather
 * path).
 */
#ifndef vtkManifoldHarmonicsSlepc_h
#define vtkManifoldHarmonicsSlepc_h

#include "vtkManifoldHarmonicsParallel.h"

#include "Spectral/Distributed/Solve.h"

class vtkMultiProcessController;

namespace vtkManifoldHarmonicsSlepc
{
/// What the filter asks of the solve (the engine's options) and its progress, cancel flag and
/// warnings (the core's Monitor: the cancel flag is polled between slices on every process, and
/// every process stops when one is cancelled).
struct Settings
  : spectral::DistributedOptions
  , spectral::Monitor
{
};

/// The result on one process: the rows of its points as VTK arrays, and the figures of the
/// whole solve (spectral::DistributedResult; its Harmonics are in Rows instead).
struct Result : spectral::DistributedResult
{
  /// Harmonics (n_r by m), lumped mass (n_r) and DUPLICATEPOINT flags (n_r) of the piece's
  /// points, and the m eigenvalues (on every process).
  vtkManifoldHarmonicsParallel::PieceBasis Rows;
};

/// Thrown when the user cancelled (on every process).
using Cancelled = spectral::Cancelled;

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
