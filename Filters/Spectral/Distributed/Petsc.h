// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Petsc.h
 * @brief What every part of the distributed engine needs of PETSc and SLEPc: errors turned into
 *        exceptions with what to change, objects destroyed at the end of their scope, the
 *        options of one solve, and initialization once per process.
 *
 * Errors of SLEPc, PETSc and MUMPS are thrown as std::runtime_error carrying their message and
 * what to change; they arise on every process alike (the calls are collective). Built only with
 * SLEPc (MANIFOLDHARMONICS_HAS_SLEPC).
 */
#ifndef spectral_Distributed_Petsc_h
#define spectral_Distributed_Petsc_h

#include <slepceps.h>

#include <string>

namespace spectral
{
namespace distributed
{
/// Throws the recorded PETSc error of `call` (code `code`) with advice.
[[noreturn]] void Fail(PetscErrorCode code, const char* call);

/// Checks a PETSc call: a nonzero code becomes an exception (Fail).
#define MH_PETSC(call)                                                                             \
  do                                                                                               \
  {                                                                                                \
    const PetscErrorCode mhCode = (call);                                                          \
    if (mhCode != 0)                                                                               \
    {                                                                                              \
      ::spectral::distributed::Fail(mhCode, #call);                                                \
    }                                                                                              \
  } while (false)

/// A PETSc object destroyed at the end of its scope.
template<typename T, PetscErrorCode (*Destroy)(T*)>
struct Owned
{
  T Object = nullptr;
  Owned() = default;
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  ~Owned()
  {
    if (this->Object)
    {
      Destroy(&this->Object);
    }
  }
};
using OwnedMat = Owned<Mat, MatDestroy>;
using OwnedVec = Owned<Vec, VecDestroy>;
using OwnedKSP = Owned<KSP, KSPDestroy>;
using OwnedEPS = Owned<EPS, EPSDestroy>;
using OwnedIS = Owned<IS, ISDestroy>;
using OwnedScatter = Owned<VecScatter, VecScatterDestroy>;

/**
 * For the duration of a solve: our error handler (no tracebacks printed, the message kept) and
 * an options database of our own (the solver's settings and the user's `options`), so that
 * nothing leaks into later solves or other PETSc users of the process.
 */
class Session
{
public:
  explicit Session(const std::string& options);
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session();

private:
  PetscOptions Options = nullptr;
};

/**
 * SLEPc (and PETSc, and MPI when nobody initialized it) once per process. When SLEPc
 * initializes MPI it finalizes both at exit; when the application did, SLEPc stays initialized
 * to the end.
 */
void Initialize();

/// The communicator of a PETSc object.
template<typename T>
MPI_Comm CommOf(T object)
{
  return PetscObjectComm(reinterpret_cast<PetscObject>(object));
}

/// Tells PETSc (and so MUMPS) that a matrix is symmetric, for good.
void MarkSymmetric(Mat matrix);

/// Makes `ksp` one solve with a MUMPS Cholesky factorization (its inertia is then known), failing
/// with an error rather than a diverged flag.
void UseMumpsCholesky(KSP ksp);
} // namespace distributed
} // namespace spectral

#endif
