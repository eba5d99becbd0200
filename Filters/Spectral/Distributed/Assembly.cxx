// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Distributed/Assembly.h"
#include "Operators/Operators.h"
#include "Solver/Acceptance.h"

#include <cmath>

namespace spectral
{
namespace distributed
{
namespace
{
// The share of an eigenvector's squared D-norm below which its part on a connected component is
// round-off of the Krylov vectors and set to zero (Constants::Deflate): a part of D-norm below
// 1e-8, the pair tolerance (Verification.h), changes none of the pair checks.
constexpr double NegligibleShare = 1e-16;

//------------------------------------------------------------------------------
// Adds `local` (a matrix on the piece's points) to `matrix` by global numbers.
void AddEntries(Mat matrix, const SparseMatrix& local, const std::vector<PetscInt>& ids)
{
  std::vector<PetscInt> rows;
  std::vector<PetscScalar> values;
  for (int j = 0; j < local.outerSize(); ++j)
  {
    rows.clear();
    values.clear();
    for (SparseMatrix::InnerIterator it(local, j); it; ++it)
    {
      rows.push_back(ids[it.row()]);
      values.push_back(it.value());
    }
    const PetscInt column = ids[j];
    MH_PETSC(MatSetValues(matrix,
      static_cast<PetscInt>(rows.size()),
      rows.data(),
      1,
      &column,
      values.data(),
      ADD_VALUES));
  }
}

//------------------------------------------------------------------------------
// An empty distributed matrix of the numbering's size and `type`.
void CreateEmpty(MPI_Comm comm, const Numbering& numbering, MatType type, OwnedMat& out)
{
  MH_PETSC(MatCreate(comm, &out.Object));
  MH_PETSC(MatSetSizes(
    out.Object, numbering.OwnedCount, numbering.OwnedCount, numbering.Total, numbering.Total));
  MH_PETSC(MatSetType(out.Object, type));
}

//------------------------------------------------------------------------------
// A distributed AIJ matrix of `local` added up by global numbers, exactly preallocated (a
// MATPREALLOCATOR pass over the same entries).
void CreateMatrix(MPI_Comm comm,
  const SparseMatrix& local,
  const Numbering& numbering,
  OwnedMat& out)
{
  OwnedMat preallocator;
  CreateEmpty(comm, numbering, MATPREALLOCATOR, preallocator);
  MH_PETSC(MatSetUp(preallocator.Object));
  AddEntries(preallocator.Object, local, numbering.Global);
  MH_PETSC(MatAssemblyBegin(preallocator.Object, MAT_FINAL_ASSEMBLY));
  MH_PETSC(MatAssemblyEnd(preallocator.Object, MAT_FINAL_ASSEMBLY));

  CreateEmpty(comm, numbering, MATAIJ, out);
  MH_PETSC(MatPreallocatorPreallocate(preallocator.Object, PETSC_TRUE, out.Object));
  AddEntries(out.Object, local, numbering.Global);
  MH_PETSC(MatAssemblyBegin(out.Object, MAT_FINAL_ASSEMBLY));
  MH_PETSC(MatAssemblyEnd(out.Object, MAT_FINAL_ASSEMBLY));
  MarkSymmetric(out.Object);
}
} // anonymous namespace

//------------------------------------------------------------------------------
void Assemble(MPI_Comm comm,
  const TriangleMesh& mesh,
  const Numbering& numbering,
  bool consistentMass,
  Operators& out)
{
  CreateMatrix(comm, CotanStiffness(mesh), numbering, out.Q);
  const Vector lumped = LumpedMass(mesh);
  MH_PETSC(MatCreateVecs(out.Q.Object, &out.Lumped.Object, nullptr));
  MH_PETSC(VecSet(out.Lumped.Object, 0.0));
  MH_PETSC(VecSetValues(out.Lumped.Object,
    static_cast<PetscInt>(lumped.size()),
    numbering.Global.data(),
    lumped.data(),
    ADD_VALUES));
  MH_PETSC(VecAssemblyBegin(out.Lumped.Object));
  MH_PETSC(VecAssemblyEnd(out.Lumped.Object));
  if (consistentMass)
  {
    CreateMatrix(comm, ConsistentMass(mesh), numbering, out.D);
    return;
  }
  MH_PETSC(MatCreateAIJ(comm,
    numbering.OwnedCount,
    numbering.OwnedCount,
    numbering.Total,
    numbering.Total,
    1,
    nullptr,
    0,
    nullptr,
    &out.D.Object));
  MH_PETSC(MatDiagonalSet(out.D.Object, out.Lumped.Object, INSERT_VALUES));
  MH_PETSC(MatAssemblyBegin(out.D.Object, MAT_FINAL_ASSEMBLY));
  MH_PETSC(MatAssemblyEnd(out.D.Object, MAT_FINAL_ASSEMBLY));
  MarkSymmetric(out.D.Object);
}

//------------------------------------------------------------------------------
PetscInt CountBelow(Mat Q, Mat D, double shift)
{
  OwnedMat shifted;
  MH_PETSC(MatDuplicate(Q, MAT_COPY_VALUES, &shifted.Object));
  MH_PETSC(MatAXPY(shifted.Object, -shift, D, SUBSET_NONZERO_PATTERN));
  MarkSymmetric(shifted.Object);
  OwnedKSP ksp;
  MH_PETSC(KSPCreate(CommOf(Q), &ksp.Object));
  MH_PETSC(KSPSetOptionsPrefix(ksp.Object, "st_"));
  MH_PETSC(KSPSetOperators(ksp.Object, shifted.Object, shifted.Object));
  UseMumpsCholesky(ksp.Object);
  MH_PETSC(KSPSetFromOptions(ksp.Object));
  MH_PETSC(KSPSetUp(ksp.Object));
  PC pc;
  MH_PETSC(KSPGetPC(ksp.Object, &pc));
  Mat factor;
  MH_PETSC(PCFactorGetMatrix(pc, &factor));
  PetscInt negative = 0;
  PetscInt zero = 0;
  PetscInt positive = 0;
  MH_PETSC(MatGetInertia(factor, &negative, &zero, &positive));
  return negative;
}

//------------------------------------------------------------------------------
Constants::Constants(const Components& components, std::vector<int> label, Vec lumped)
  : Parts(components)
  , Label(std::move(label))
{
  const PetscScalar* mass = nullptr;
  MH_PETSC(VecGetArrayRead(lumped, &mass));
  this->Lumped.assign(mass, mass + this->Label.size());
  MH_PETSC(VecRestoreArrayRead(lumped, &mass));
  this->Comm = CommOf(lumped);
}

//------------------------------------------------------------------------------
void Constants::Set(Vec x, int j) const
{
  PetscScalar* values = nullptr;
  MH_PETSC(VecGetArray(x, &values));
  const double value = 1.0 / std::sqrt(this->Parts.Mass[j]);
  for (std::size_t r = 0; r < this->Label.size(); ++r)
  {
    values[r] = this->Label[r] == j ? value : 0.0;
  }
  MH_PETSC(VecRestoreArray(x, &values));
}

//------------------------------------------------------------------------------
double Constants::Deflate(Vec x, double keepBelow) const
{
  const std::size_t count = static_cast<std::size_t>(this->Parts.Count);
  // Per component: sum lumped_i x_i, then sum lumped_i x_i^2.
  std::vector<double> sums(2 * count, 0.0);
  PetscScalar* values = nullptr;
  MH_PETSC(VecGetArray(x, &values));
  for (std::size_t r = 0; r < this->Label.size(); ++r)
  {
    const double weighted = this->Lumped[r] * values[r];
    sums[this->Label[r]] += weighted;
    sums[count + this->Label[r]] += weighted * values[r];
  }
  MPI_Allreduce(
    MPI_IN_PLACE, sums.data(), static_cast<int>(2 * count), MPI_DOUBLE, MPI_SUM, this->Comm);
  double removed = 0.0;
  double total = 0.0;
  for (std::size_t j = 0; j < count; ++j)
  {
    removed += sums[j] * sums[j] / this->Parts.Mass[j];
    total += sums[count + j];
  }
  const double share = total > 0.0 ? removed / total : 1.0;
  if (!(share > keepBelow))
  {
    for (std::size_t r = 0; r < this->Label.size(); ++r)
    {
      const int j = this->Label[r];
      values[r] = sums[count + j] > NegligibleShare * total
        ? values[r] - sums[j] / this->Parts.Mass[j]
        : 0.0;
    }
  }
  MH_PETSC(VecRestoreArray(x, &values));
  return share;
}

//------------------------------------------------------------------------------
void NormalizeSign(Vec x)
{
  PetscReal largest = 0.0;
  PetscReal smallest = 0.0;
  MH_PETSC(VecMax(x, nullptr, &largest));
  MH_PETSC(VecMin(x, nullptr, &smallest));
  if (FlipsSign(largest, smallest))
  {
    MH_PETSC(VecScale(x, -1.0));
  }
}
} // namespace distributed
} // namespace spectral
