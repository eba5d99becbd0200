#!/usr/bin/python3
# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""Reference eigensolver for the benchmark: SLEPc (slepc4py, Debian's python3-slepc4py), serial,
Krylov-Schur in shift-and-invert with a MUMPS Cholesky factor, two ways.

Usage: slepc_reference.py L.mtx M.mtx m upper out-target.txt out-slicing.txt

- target: the m eigenvalues nearest the target -0.01 (EPS_TARGET_MAGNITUDE), the shift of
  scipy's eigsh in scipy_reference.py and of LaPy;
- slicing: every eigenvalue of the interval [-0.01, upper] (EPS_ALL with an interval: spectrum
  slicing, which factors at several shifts and counts eigenvalues by the inertia of the
  factors; its lower end is below 0 because the stiffness matrix is singular). The benchmark
  passes the midpoint between its own lambda_{m-1} and lambda_m ("the exact interval"), or
  lambda_{m-1} enlarged by 1e-6 where it has no lambda_m.

Each way writes the wall time (seconds, from EPSSetUp, which factors, to the end of EPSSolve; the
matrices are read and built before the clock starts, as scipy_reference.py does) and the
converged eigenvalues in ascending order, one per line; eigenvectors are computed as well, as
the benchmark's solver and scipy compute them. SLEPc's default tolerance (1e-8 on the relative
residual) is the acceptance threshold of the benchmark's solver too. A way that fails writes
nothing.
"""
import sys
import time

import numpy as np
import scipy.io
import scipy.sparse

import petsc4py

petsc4py.init(sys.argv[:1])
from petsc4py import PETSc  # noqa: E402
from slepc4py import SLEPc  # noqa: E402

TARGET = -0.01


def petsc_matrix(path):
    """The symmetric Matrix Market file as a PETSc AIJ matrix holding both triangles."""
    A = scipy.io.mmread(path).tocsr()
    A.sort_indices()
    matrix = PETSc.Mat().createAIJ(
        size=A.shape, csr=(A.indptr.astype(PETSc.IntType), A.indices.astype(PETSc.IntType),
                           A.data))
    matrix.setOption(PETSc.Mat.Option.SYMMETRIC, True)
    matrix.assemble()
    return matrix


def solver(L, M):
    """Krylov-Schur, generalized Hermitian problem, shift-and-invert, MUMPS Cholesky. The
    spectral transformation is set through the options database: spectrum slicing factors in
    EPS objects of its own, which take it from there (set on this EPS's ST alone, slicing
    factored with PETSc's own Cholesky, which has no inertia)."""
    options = PETSc.Options()
    for key, value in (("st_type", "sinvert"), ("st_matstructure", "subset"),
                       ("st_ksp_type", "preonly"), ("st_pc_type", "cholesky"),
                       ("st_pc_factor_mat_solver_type", "mumps")):
        options.setValue(key, value)
    eps = SLEPc.EPS().create()
    eps.setOperators(L, M)
    eps.setProblemType(SLEPc.EPS.ProblemType.GHEP)
    eps.setType(SLEPc.EPS.Type.KRYLOVSCHUR)
    return eps


def solve(eps):
    """Wall time of setup and solve, and the converged eigenvalues (eigenvectors computed)."""
    start = time.perf_counter()
    eps.setUp()
    eps.solve()
    vector = eps.getOperators()[0].createVecRight()
    values = []
    for i in range(eps.getConverged()):
        values.append(eps.getEigenpair(i, vector).real)
    return time.perf_counter() - start, np.sort(np.array(values))


def write(path, seconds, values):
    with open(path, "w") as out:
        out.write("%.6f\n" % seconds)
        for value in values:
            out.write("%.17g\n" % value)


def main():
    L = petsc_matrix(sys.argv[1])
    M = petsc_matrix(sys.argv[2])
    m = int(sys.argv[3])
    upper = float(sys.argv[4])

    eps = solver(L, M)
    eps.setDimensions(nev=m)
    eps.setTarget(TARGET)
    eps.setWhichEigenpairs(SLEPc.EPS.Which.TARGET_MAGNITUDE)
    eps.setFromOptions()
    try:
        seconds, values = solve(eps)
        write(sys.argv[5], seconds, values[:m])
    except PETSc.Error as error:
        print("slepc_reference.py: target: %s" % error, file=sys.stderr)
    eps.destroy()

    eps = solver(L, M)
    eps.setWhichEigenpairs(SLEPc.EPS.Which.ALL)
    eps.setInterval(TARGET, upper)
    eps.setFromOptions()
    try:
        seconds, values = solve(eps)
        write(sys.argv[6], seconds, values)
    except PETSc.Error as error:
        print("slepc_reference.py: slicing: %s" % error, file=sys.stderr)
    eps.destroy()


if __name__ == "__main__":
    main()
