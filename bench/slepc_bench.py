# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""The distributed SLEPc solve against the built-in one: wall time and peak memory per process.

Run with pvbatch, serially or under MPI (every process runs the script):

    . build/env.sh
    mpiexec --allow-run-as-root --oversubscribe -n 2 pvbatch --symmetric bench/slepc_bench.py \
        --points 100000 --harmonics 500 --solver slepc

Each process takes its piece of a Sphere source of about --points points (the source's own
pieces, ThetaResolution = 2 PhiResolution), computes the basis with vtkManifoldHarmonicBasis and
prints one row: solver, processes, rank, its points, global points, harmonics, wall seconds of
the basis (the same on every process: they wait for each other), the increase of the peak
resident memory (VmHWM of /proc/self/status) over the process's peak before the solve, the peak
itself, and lambda_{m-1}. With `--solver builtin` under MPI, process 0 gathers the surface and
solves alone (the built-in distributed path); run it serially for the built-in figures.
"""

import argparse
import math
import time

from paraview import servermanager
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersSources import vtkSphereSource

import manifoldharmonics as mh


def peak_kib():
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith("VmHWM:"):
                return int(line.split()[1])
    return 0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--points", type=int, default=100000)
    parser.add_argument("--harmonics", type=int, default=500)
    parser.add_argument("--solver", choices=("slepc", "builtin"), default="slepc")
    parser.add_argument("--partitions", type=int, default=1)
    parser.add_argument("--options", default="")
    args = parser.parse_args()

    controller = servermanager.vtkProcessModule.GetProcessModule().GetGlobalController()
    rank = controller.GetLocalProcessId()
    size = controller.GetNumberOfProcesses()
    # A UV sphere of T x P points with T = 2 P has about 2 P^2 points.
    phi = max(8, int(round(math.sqrt(args.points / 2.0))))
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(2 * phi)
    sphere.SetPhiResolution(phi)
    sphere.UpdatePiece(rank, size, 0)
    piece = vtkPolyData()
    piece.ShallowCopy(sphere.GetOutput())

    basis = mh.vtkManifoldHarmonicBasis()
    basis.SetInputData(piece)
    basis.SetNumberOfHarmonics(args.harmonics)
    if args.solver == "slepc":
        basis.SetSolverToSlepc()
        basis.SetSlepcPartitions(args.partitions)
        basis.SetSlepcOptions(args.options)
    before = peak_kib()
    controller.Barrier()
    start = time.perf_counter()
    basis.Update()
    controller.Barrier()
    wall = time.perf_counter() - start
    after = peak_kib()
    output = basis.GetOutput()
    eigenvalues = output.GetFieldData().GetArray("ManifoldHarmonicsEigenvalues")
    top = eigenvalues.GetValue(eigenvalues.GetNumberOfTuples() - 1) if eigenvalues else float("nan")
    total = 2 * phi * (phi - 2) + 2
    print("solver=%s processes=%d rank=%d points=%d global=%d harmonics=%d wall=%.2fs "
          "solve_peak_increase=%.0fMiB peak=%.0fMiB lambda_max=%.6g"
          % (args.solver, size, rank, piece.GetNumberOfPoints(), total, args.harmonics, wall,
             (after - before) / 1024.0, after / 1024.0, top), flush=True)


if __name__ == "__main__":
    main()
