// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Assembly.h
 * @brief The distributed operators: stiffness and mass of each piece's cells (the core's
 *        formulas, Operators.h) added up by global number into PETSc matrices; the inertia of
 *        the shifted pencil; the constant harmonics of the components and their deflation.
 */
#ifndef spectral_Distributed_Assembly_h
#define spectral_Distributed_Assembly_h

#include "Distributed/Numbering.h"
#include "Distributed/Petsc.h"

namespace spectral
{
namespace distributed
{
/// The pencil Q h = lambda D h of the whole mesh, distributed by rows (owned points).
struct Operators
{
  OwnedMat Q;
  OwnedMat D;
  /// The row sums of D (the lumped mass), distributed as Q's rows.
  OwnedVec Lumped;
};

/**
 * Assembles the cotan (P1 for tetrahedra) stiffness and the lumped or consistent mass of this
 * piece's cells (in the units of `mesh`) and adds them up by global number (MatSetValues
 * ADD_VALUES, exactly preallocated; PETSc sends the rows of other processes at assembly).
 * Collective.
 */
void Assemble(MPI_Comm comm,
  const TriangleMesh& mesh,
  const Numbering& numbering,
  bool consistentMass,
  Operators& out);

/**
 * The number of eigenvalues below `shift`: the negative inertia of an LDL^T factorization of
 * Q - shift D by MUMPS, with the options of the ST's factorization (prefix st_). Collective.
 */
PetscInt CountBelow(Mat Q, Mat D, double shift);

/**
 * The constant harmonic of each connected component, 1_j / sqrt(mass_j), an exact null vector of
 * Q (its rows sum to zero), and the deflation of distributed vectors from their span, on the
 * owned rows: D 1_j is the lumped mass on component j (for the consistent mass too), so
 * c_j^T D x = sum_{i in j} lumped_i x_i / sqrt(mass_j).
 */
class Constants
{
public:
  /// `label`: the component of each owned row; `lumped`: the lumped mass (Operators::Lumped).
  Constants(const Components& components, std::vector<int> label, Vec lumped);

  /// x = c_j, the constant harmonic of component j.
  void Set(Vec x, int j) const;

  /**
   * Deflates x (collective): returns the share of its squared norm (in the lumped mass) that
   * lies in the span of the constants, and unless that is above `keepBelow`, removes its
   * components along every c_j and sets it to zero on the components that hold a negligible
   * share of its squared norm (the operators do not couple components: what a Krylov vector
   * holds there is round-off, which on debris rows would dominate its residual).
   */
  double Deflate(Vec x, double keepBelow) const;

private:
  const Components& Parts;
  std::vector<int> Label;
  std::vector<double> Lumped;
  MPI_Comm Comm = MPI_COMM_NULL;
};

/// The sign rule of harmonics (Acceptance.h, FlipsSign) on a distributed vector. Collective.
void NormalizeSign(Vec x);
} // namespace distributed
} // namespace spectral

#endif
