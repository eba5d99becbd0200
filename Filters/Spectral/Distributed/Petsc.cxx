// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Distributed/Petsc.h"

#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace spectral
{
namespace distributed
{
namespace
{
//------------------------------------------------------------------------------
// The first message of an error (where it arose), recorded by our handler.
std::string& FirstError()
{
  static thread_local std::string message;
  return message;
}

PetscErrorCode RecordError(MPI_Comm,
  int,
  const char* function,
  const char*,
  PetscErrorCode code,
  PetscErrorType type,
  const char* message,
  void*)
{
  if (type == PETSC_ERROR_INITIAL && FirstError().empty())
  {
    FirstError() =
      std::string(message ? message : "") + " (in " + (function ? function : "?") + ")";
  }
  return code;
}

//------------------------------------------------------------------------------
// What to change for the MUMPS errors a user can do something about (MUMPS users' guide,
// section "Error diagnostics").
std::string Advice(const std::string& message)
{
  for (const char* code : { "INFOG(1)=-8",
         "INFOG(1)=-9",
         "INFOG(1)=-11",
         "INFOG(1)=-14",
         "INFOG(1)=-15",
         "INFOG(1)=-17",
         "INFOG(1)=-20" })
  {
    if (message.find(code) != std::string::npos)
    {
      return " MUMPS's estimated workspace was too small: increase it with SlepcOptions "
             "\"-st_mat_mumps_icntl_14 100\" (percent of extra workspace; MUMPS's default is "
             "20, raise further if it fails again).";
    }
  }
  if (message.find("INFOG(1)=-13") != std::string::npos)
  {
    return " MUMPS could not allocate its factor: run on more nodes (more memory), or compute "
           "fewer harmonics.";
  }
  if (message.find("INFOG(1)=-38") != std::string::npos)
  {
    return " The parallel ordering of this MUMPS build failed: use the sequential one, "
           "SlepcOptions \"-st_mat_mumps_icntl_28 1\".";
  }
  if (message.find("INFOG(1)=-10") != std::string::npos)
  {
    return " A shift fell on an eigenvalue (singular factorization): change NumberOfHarmonics "
           "by one, or pass \"-eps_krylovschur_partitions\" differently.";
  }
  return "";
}
} // anonymous namespace

//------------------------------------------------------------------------------
void Fail(PetscErrorCode code, const char* call)
{
  std::string message = FirstError();
  FirstError().clear();
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  std::ostringstream out;
  out << "SLEPc/PETSc error " << code << " (" << (text ? text : "unknown") << ") in " << call;
  if (!message.empty())
  {
    out << ": " << message << ".";
  }
  out << Advice(message);
  throw std::runtime_error(out.str());
}

//------------------------------------------------------------------------------
Session::Session(const std::string& options)
{
  PetscPushErrorHandler(RecordError, nullptr);
  FirstError().clear();
  MH_PETSC(PetscOptionsCreate(&this->Options));
  // The inertia of MUMPS needs null pivot detection, ICNTL(24) = 1, and in parallel
  // ICNTL(13) = 1 (no ScaLAPACK root node). The prefix st_ is the one of the ST's
  // factorization and of our own inertia probes.
  MH_PETSC(
    PetscOptionsInsertString(this->Options, "-st_mat_mumps_icntl_13 1 -st_mat_mumps_icntl_24 1"));
  MH_PETSC(PetscOptionsInsertString(this->Options, options.c_str()));
  MH_PETSC(PetscOptionsPush(this->Options));
}

Session::~Session()
{
  PetscOptionsPop();
  PetscOptionsDestroy(&this->Options);
  PetscPopErrorHandler();
}

//------------------------------------------------------------------------------
void Initialize()
{
  PetscBool initialized = PETSC_FALSE;
  SlepcInitialized(&initialized);
  if (initialized)
  {
    return;
  }
  int mpi = 0;
  MPI_Initialized(&mpi);
  if (SlepcInitializeNoArguments() != 0)
  {
    throw std::runtime_error("SLEPc could not be initialized.");
  }
  // The host application (ParaView) handles signals itself.
  PetscPopSignalHandler();
  if (!mpi)
  {
    // SLEPc initialized MPI: finalize both at exit. When the application initialized MPI it
    // also finalizes it, and SLEPc stays initialized to the end (finalizing it after MPI fails).
    std::atexit([]() { SlepcFinalize(); });
  }
}

//------------------------------------------------------------------------------
void MarkSymmetric(Mat matrix)
{
  MH_PETSC(MatSetOption(matrix, MAT_SYMMETRIC, PETSC_TRUE));
  MH_PETSC(MatSetOption(matrix, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
}
//------------------------------------------------------------------------------
void UseMumpsCholesky(KSP ksp)
{
  MH_PETSC(KSPSetType(ksp, KSPPREONLY));
  PC pc;
  MH_PETSC(KSPGetPC(ksp, &pc));
  MH_PETSC(PCSetType(pc, PCCHOLESKY));
  MH_PETSC(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  MH_PETSC(PCSetErrorIfFailure(pc, PETSC_TRUE));
}
} // namespace distributed
} // namespace spectral
