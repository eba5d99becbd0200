// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Distributed/Pairs.h"
#include "Solver/Verification.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace spectral
{
namespace distributed
{
//------------------------------------------------------------------------------
Slice SolveSlice(OwnedEPS& eps, Mat Q, Mat D, double lower, double upper, const SliceSettings& settings)
{
  MH_PETSC(EPSCreate(CommOf(Q), &eps.Object));
  MH_PETSC(EPSSetOperators(eps.Object, Q, D));
  MH_PETSC(EPSSetProblemType(eps.Object, EPS_GHEP));
  MH_PETSC(EPSSetType(eps.Object, EPSKRYLOVSCHUR));
  MH_PETSC(EPSSetWhichEigenpairs(eps.Object, EPS_ALL));
  MH_PETSC(EPSSetInterval(eps.Object, lower, upper));
  MH_PETSC(EPSSetTolerances(eps.Object, settings.Tolerance, settings.MaxIterations));
  ST st;
  MH_PETSC(EPSGetST(eps.Object, &st));
  MH_PETSC(STSetType(st, STSINVERT));
  MH_PETSC(STSetMatStructure(st, SUBSET_NONZERO_PATTERN));
  KSP ksp;
  MH_PETSC(STGetKSP(st, &ksp));
  UseMumpsCholesky(ksp);
  MH_PETSC(EPSKrylovSchurSetPartitions(eps.Object, settings.Partitions));
  MH_PETSC(EPSSetFromOptions(eps.Object));
  MH_PETSC(EPSSolve(eps.Object));

  Slice slice;
  PetscInt converged = 0;
  MH_PETSC(EPSGetConverged(eps.Object, &converged));
  PetscReal* at = nullptr;
  PetscInt* inertias = nullptr;
  MH_PETSC(EPSKrylovSchurGetInertias(eps.Object, &slice.Shifts, &at, &inertias));
  PetscInt atLower = 0;
  PetscInt atUpper = 0;
  for (PetscInt k = 0; k < slice.Shifts; ++k)
  {
    if (at[k] <= lower)
    {
      atLower = inertias[k];
    }
    if (at[k] >= upper)
    {
      atUpper = inertias[k];
    }
  }
  PetscFree(at);
  PetscFree(inertias);
  slice.Count = atUpper - atLower;
  if (slice.Count != converged)
  {
    std::ostringstream text;
    text << "SLEPc computed " << converged << " eigenpairs in a slice where the inertia counts "
         << slice.Count << ": raise MaxIterations, or lower Tolerance";
    throw std::runtime_error(text.str());
  }
  slice.Order.resize(static_cast<std::size_t>(converged));
  for (PetscInt k = 0; k < converged; ++k)
  {
    PetscScalar real = 0.0;
    PetscScalar imaginary = 0.0;
    MH_PETSC(EPSGetEigenvalue(eps.Object, k, &real, &imaginary));
    slice.Order[k] = { PetscRealPart(real), k };
  }
  std::sort(slice.Order.begin(), slice.Order.end());
  return slice;
}

//------------------------------------------------------------------------------
PairChecks::PairChecks(Mat Q, Mat D)
  : Q(Q)
  , D(D)
{
  MH_PETSC(MatDuplicate(Q, MAT_COPY_VALUES, &this->AbsQ.Object));
  PetscInt first = 0;
  PetscInt end = 0;
  MH_PETSC(MatGetOwnershipRange(Q, &first, &end));
  std::vector<PetscScalar> values;
  for (PetscInt row = first; row < end; ++row)
  {
    PetscInt count = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* entries = nullptr;
    MH_PETSC(MatGetRow(Q, row, &count, &cols, &entries));
    values.assign(entries, entries + count);
    for (PetscScalar& value : values)
    {
      value = std::abs(value);
    }
    const PetscErrorCode set =
      MatSetValues(this->AbsQ.Object, 1, &row, count, cols, values.data(), INSERT_VALUES);
    MH_PETSC(MatRestoreRow(Q, row, &count, &cols, &entries));
    MH_PETSC(set);
  }
  MH_PETSC(MatAssemblyBegin(this->AbsQ.Object, MAT_FINAL_ASSEMBLY));
  MH_PETSC(MatAssemblyEnd(this->AbsQ.Object, MAT_FINAL_ASSEMBLY));
  MH_PETSC(MatCreateVecs(Q, &this->Qx.Object, &this->Dx.Object));
  MH_PETSC(MatCreateVecs(Q, &this->AbsX.Object, &this->Scale.Object));
  MH_PETSC(MatCreateVecs(Q, &this->AbsDx.Object, nullptr));
  // Row sums of D (the lumped weights of the residual norm) and trace(Q) / mass.
  MH_PETSC(VecSet(this->AbsX.Object, 1.0));
  MH_PETSC(MatMult(D, this->AbsX.Object, this->Scale.Object));
  this->RowSum.resize(static_cast<std::size_t>(end - first));
  const PetscScalar* sums = nullptr;
  MH_PETSC(VecGetArrayRead(this->Scale.Object, &sums));
  std::copy(sums, sums + (end - first), this->RowSum.begin());
  MH_PETSC(VecRestoreArrayRead(this->Scale.Object, &sums));
  PetscScalar mass = 0.0;
  PetscScalar trace = 0.0;
  MH_PETSC(VecSum(this->Scale.Object, &mass));
  MH_PETSC(MatGetDiagonal(Q, this->Qx.Object));
  MH_PETSC(VecSum(this->Qx.Object, &trace));
  this->TraceOverMass = trace / std::max(mass, 1e-300);
  // Gershgorin's bound on D^-1 Q: max_i sum_j |Q_ij| / D_i (for AchievableResidual).
  MH_PETSC(MatMult(this->AbsQ.Object, this->AbsX.Object, this->Qx.Object));
  const PetscScalar* absSums = nullptr;
  MH_PETSC(VecGetArrayRead(this->Qx.Object, &absSums));
  double top = 0.0;
  for (std::size_t i = 0; i < this->RowSum.size(); ++i)
  {
    top = std::max(top, this->RowSum[i] > 0.0 ? absSums[i] / this->RowSum[i] : 0.0);
  }
  MH_PETSC(VecRestoreArrayRead(this->Qx.Object, &absSums));
  MPI_Allreduce(&top,
    &this->GershgorinTop,
    1,
    MPI_DOUBLE,
    MPI_MAX,
    CommOf(Q));
}

//------------------------------------------------------------------------------
PairError PairChecks::NormalizeAndCheck(Vec x, double lambda, double* dx)
{
  MH_PETSC(MatMult(this->D, x, this->Dx.Object));
  PetscScalar norm2 = 0.0;
  MH_PETSC(VecDot(x, this->Dx.Object, &norm2));
  const double inverse = 1.0 / std::sqrt(PetscRealPart(norm2));
  MH_PETSC(VecScale(x, inverse));
  MH_PETSC(VecScale(this->Dx.Object, inverse));
  const PetscScalar* values = nullptr;
  MH_PETSC(VecGetArrayRead(this->Dx.Object, &values));
  std::copy(values, values + this->RowSum.size(), dx);
  MH_PETSC(VecRestoreArrayRead(this->Dx.Object, &values));
  MH_PETSC(MatMult(this->Q, x, this->Qx.Object));
  MH_PETSC(VecAXPY(this->Qx.Object, -lambda, this->Dx.Object));
  MH_PETSC(VecCopy(x, this->AbsX.Object));
  MH_PETSC(VecAbs(this->AbsX.Object));
  MH_PETSC(MatMult(this->AbsQ.Object, this->AbsX.Object, this->Scale.Object));
  MH_PETSC(MatMult(this->D, this->AbsX.Object, this->AbsDx.Object));
  MH_PETSC(VecAXPY(this->Scale.Object, std::abs(lambda), this->AbsDx.Object));
  PetscReal largest = 0.0;
  MH_PETSC(VecMax(this->Scale.Object, nullptr, &largest));
  const PetscScalar* r = nullptr;
  const PetscScalar* denominators = nullptr;
  MH_PETSC(VecGetArrayRead(this->Qx.Object, &r));
  MH_PETSC(VecGetArrayRead(this->Scale.Object, &denominators));
  const Eigen::Index rows = static_cast<Eigen::Index>(this->RowSum.size());
  const Eigen::Map<const Vector> residual(r, rows);
  // sum r^2 / d, and the largest backward ratio (the floor from the scale of all processes)
  double sums[2] = { residual.cwiseAbs2().dot(
                       Eigen::Map<const Vector>(this->RowSum.data(), rows).cwiseInverse()),
    detail::ScaledBackwardError(
      residual, Eigen::Map<const Vector>(denominators, rows), largest) };
  MH_PETSC(VecRestoreArrayRead(this->Qx.Object, &r));
  MH_PETSC(VecRestoreArrayRead(this->Scale.Object, &denominators));
  const MPI_Comm comm = CommOf(this->Q);
  double global[2];
  MPI_Allreduce(&sums[0], &global[0], 1, MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(&sums[1], &global[1], 1, MPI_DOUBLE, MPI_MAX, comm);
  return { std::sqrt(global[0]), global[1] };
}

//------------------------------------------------------------------------------
RowWriter::RowWriter(Vec layout, const std::vector<PetscInt>& global, const std::vector<int>& rows)
  : Rows(rows)
{
  OwnedIS from;
  MH_PETSC(ISCreateGeneral(PETSC_COMM_SELF,
    static_cast<PetscInt>(global.size()),
    global.data(),
    PETSC_COPY_VALUES,
    &from.Object));
  MH_PETSC(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(global.size()), &this->Local.Object));
  MH_PETSC(VecScatterCreate(layout, from.Object, this->Local.Object, nullptr, &this->Scatter.Object));
}

//------------------------------------------------------------------------------
void RowWriter::Write(Vec values, const std::function<void(Eigen::Index, double)>& store)
{
  MH_PETSC(VecScatterBegin(
    this->Scatter.Object, values, this->Local.Object, INSERT_VALUES, SCATTER_FORWARD));
  MH_PETSC(
    VecScatterEnd(this->Scatter.Object, values, this->Local.Object, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* local = nullptr;
  MH_PETSC(VecGetArrayRead(this->Local.Object, &local));
  for (std::size_t i = 0; i < this->Rows.size(); ++i)
  {
    store(this->Rows[i], local[i]);
  }
  MH_PETSC(VecRestoreArrayRead(this->Local.Object, &local));
}

//------------------------------------------------------------------------------
DenseMatrix WrittenTimes(const double* rows,
  int m,
  int columns,
  const std::vector<Eigen::Index>& ownedRows,
  const Eigen::Ref<const DenseMatrix>& Y)
{
  DenseMatrix product = DenseMatrix::Zero(columns, Y.cols());
  if (columns == 0)
  {
    return product;
  }
  const Eigen::Index block = 256;
  DenseMatrix gathered(block, columns);
  for (Eigen::Index r0 = 0; r0 < Y.rows(); r0 += block)
  {
    const Eigen::Index count = std::min(block, Y.rows() - r0);
    for (Eigen::Index t = 0; t < count; ++t)
    {
      gathered.row(t) = Eigen::Map<const Eigen::RowVectorXd>(rows + ownedRows[r0 + t] * m, columns);
    }
    product.noalias() += gathered.topRows(count).transpose() * Y.middleRows(r0, count);
  }
  return product;
}
} // namespace distributed
} // namespace spectral
