#!/usr/bin/python3
"""Reference eigensolver for the benchmark: scipy.sparse.linalg.eigsh in shift-invert mode.

Usage: scipy_reference.py L.mtx M.mtx m out.txt
Writes the wall time of eigsh (seconds) and the m smallest eigenvalues, one per line.
This is what LaPy and pyFM do: eigsh(L, k=m, M=M, sigma=-0.01), eigenvalues and
eigenvectors (the benchmark's solver returns both too).
"""
import sys
import time

import numpy as np
import scipy.io
import scipy.sparse.linalg


def main():
    L = scipy.io.mmread(sys.argv[1]).tocsc()
    M = scipy.io.mmread(sys.argv[2]).tocsc()
    m = int(sys.argv[3])
    start = time.perf_counter()
    values, _ = scipy.sparse.linalg.eigsh(L, k=m, M=M, sigma=-0.01, which="LM")
    seconds = time.perf_counter() - start
    with open(sys.argv[4], "w") as out:
        out.write("%.6f\n" % seconds)
        for value in np.sort(values):
            out.write("%.17g\n" % value)


if __name__ == "__main__":
    main()
