#!/usr/bin/python3
# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""Reference factorization for the benchmark: MUMPS's LDL^T (through PETSc, Debian's
python3-petsc4py), serial, of L - sigma M at the shifts the benchmark gives.

Usage: mumps_reference.py L.mtx M.mtx columns out.txt sigma...

For each shift, in the order given, writes one line: sigma, the seconds of the factorization
(PCSetUp: the first shift runs the analysis and the numerical factorization, the next ones reuse
the analysis of the same pattern and factor again), the number of negative pivots (the inertia
count, MatGetInertia), and the seconds of solving `columns` random right-hand sides at once
(MatMatSolve). MUMPS is asked for the inertia (ICNTL(13) = 1, which the parallel factorization
needs; serially it changes nothing) and for null pivot detection (ICNTL(24) = 1, which PETSc's
MatGetInertia requires), and keeps its own ordering choice, as a SLEPc user gets it.
"""
import sys
import time

import numpy as np

# The matrices as the SLEPc reference reads them (it initializes PETSc).
from slepc_reference import PETSc, petsc_matrix


def main():
    L = petsc_matrix(sys.argv[1])
    M = petsc_matrix(sys.argv[2])
    columns = int(sys.argv[3])
    n = L.getSize()[0]
    rng = np.random.default_rng(20080415)
    # PETSc wraps the array without copying it: it must outlive B.
    values = np.asfortranarray(rng.standard_normal((n, columns)))
    B = PETSc.Mat().createDense((n, columns), array=values)
    B.assemble()
    X = B.duplicate()
    PETSc.Options().setValue("mat_mumps_icntl_13", 1)
    # PETSc's MatGetInertia of a MUMPS factor needs null pivot detection on.
    PETSc.Options().setValue("mat_mumps_icntl_24", 1)
    A = L.duplicate(copy=True)
    pc = PETSc.PC().create()
    pc.setType(PETSc.PC.Type.CHOLESKY)
    pc.setFactorSolverType("mumps")
    pc.setFromOptions()
    with open(sys.argv[4], "w") as out:
        for sigma in (float(s) for s in sys.argv[5:]):
            # L - sigma M in place: M's pattern lies within L's.
            L.copy(A, PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
            A.axpy(-sigma, M, PETSc.Mat.Structure.SUBSET_NONZERO_PATTERN)
            start = time.perf_counter()
            pc.setOperators(A)
            pc.setUp()
            seconds = time.perf_counter() - start
            factored = pc.getFactorMatrix()
            negative = factored.getInertia()[0]
            start = time.perf_counter()
            factored.matSolve(B, X)
            solve = time.perf_counter() - start
            out.write("%.17g %.6f %d %.6f\n" % (sigma, seconds, negative, solve))


if __name__ == "__main__":
    main()
