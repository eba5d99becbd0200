# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""The basis of a torus in memory or in a file (vtkManifoldHarmonicBasis Storage), or a
streamed smoothing that never holds it (vtkManifoldHarmonicSmoothing Storage Streamed), one case
a process so that the peak resident sizes are its own:

    . build/env.sh
    /usr/bin/python3 bench/basis_file_bench.py --points 200000 --harmonics 500 --storage file

Prints the seconds of the basis, of a first transform + low-pass, of a changed cutoff and of
another filter kind (enhancement), which read the basis back (streamed: the smoothing alone,
since one with another cutoff solves again), the peak resident size (VmHWM), the anonymous and
file-backed resident sizes (RssAnon, RssFile of /proc/self/status) after each stage, in MiB
above the process's baseline before the basis, and the bytes the process read from and wrote
to the disk in that stage (read_bytes, write_bytes of /proc/self/io).
Documentation/large-meshes.md reports its figures.
"""
import argparse
import math
import os
import sys
import time

import numpy
from vtkmodules.util import numpy_support
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
import manifoldharmonics as mh


def status():
    fields = {}
    with open("/proc/self/status") as f:
        for line in f:
            key, _, value = line.partition(":")
            if key in ("VmHWM", "RssAnon", "RssFile"):
                fields[key] = int(value.split()[0]) / 1024.0
    return fields


def io():
    fields = {}
    with open("/proc/self/io") as f:
        for line in f:
            key, _, value = line.partition(":")
            if key in ("read_bytes", "write_bytes"):
                fields[key] = int(value) / 1048576.0
    return fields


def streamed(mesh, args, base):
    smoothing = mh.vtkManifoldHarmonicSmoothing()
    smoothing.SetInputData(mesh)
    smoothing.SetNumberOfHarmonics(args.harmonics)
    smoothing.SetStorageToStreamed()
    smoothing.SetMemoryLimit(args.memory_limit)
    if args.progress:
        watch_progress(smoothing)
    if args.float:
        smoothing.SetBasisPrecisionToFloat()
    seconds, after, disk = {}, {}, {}
    # One smoothing: a changed cutoff solves again, the same work.
    for stage, cutoff in (("smoothing", 0.5),):
        smoothing.SetCutoffFraction(cutoff)
        before = io()
        start = time.time()
        smoothing.Update()
        seconds[stage] = time.time() - start
        after[stage] = status()
        disk[stage] = {k: io()[k] - before[k] for k in before}
    return seconds, after, disk, "streamed smoothing"


def watch_progress(algorithm):
    """Prints the progress to the standard error at every whole per cent, with the seconds since
    the start and RssAnon, so that a run of hours shows where it is."""
    start = time.time()
    last = [-1]

    def report(caller, event):
        percent = int(100 * caller.GetProgress())
        if percent != last[0]:
            last[0] = percent
            print("  %5.0f s  %3d %%  %s  RssAnon %.0f MiB" % (
                time.time() - start, percent, caller.GetProgressText() or "",
                status()["RssAnon"]), file=sys.stderr, flush=True)

    algorithm.AddObserver("ProgressEvent", report)


def torus(points):
    """A closed torus (ring radius 1, cross-section 0.4) of about `points` points: a periodic
    grid of side sqrt(points), two triangles a cell. (vtkParametricFunctionSource's joined torus
    has degenerate triangles and non-manifold edges along its seams.)"""
    side = int(math.sqrt(points))
    u = 2.0 * numpy.pi * numpy.arange(side) / side
    uu, vv = numpy.meshgrid(u, u, indexing="ij")
    ring = 1.0 + 0.4 * numpy.cos(vv)
    xyz = numpy.stack([ring * numpy.cos(uu), ring * numpy.sin(uu), 0.4 * numpy.sin(vv)], axis=-1)
    points = vtkPoints()
    points.SetData(numpy_support.numpy_to_vtk(xyz.reshape(-1, 3), deep=True))
    i, j = numpy.meshgrid(numpy.arange(side), numpy.arange(side), indexing="ij")
    a = i * side + j
    b = ((i + 1) % side) * side + j
    c = ((i + 1) % side) * side + (j + 1) % side
    d = i * side + (j + 1) % side
    triangles = numpy.concatenate([numpy.stack([a, b, c], -1).reshape(-1, 3),
                                   numpy.stack([a, c, d], -1).reshape(-1, 3)])
    offsets = numpy.arange(0, 3 * len(triangles) + 1, 3, dtype=numpy.int64)
    cells = vtkCellArray()
    cells.SetData(numpy_support.numpy_to_vtkIdTypeArray(offsets, deep=True),
                  numpy_support.numpy_to_vtkIdTypeArray(triangles.reshape(-1).astype(numpy.int64),
                                                        deep=True))
    mesh = vtkPolyData()
    mesh.SetPoints(points)
    mesh.SetPolys(cells)
    return mesh


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--points", type=int, default=200000)
    parser.add_argument("--harmonics", type=int, default=500)
    parser.add_argument("--storage", choices=["memory", "file", "streamed"], default="memory")
    parser.add_argument("--file", default="")
    parser.add_argument("--float", action="store_true")
    parser.add_argument("--band-size", type=int, default=0)
    parser.add_argument("--memory-limit", type=float, default=0.0,
                        help="MemoryLimit of the filter in MiB (default 0: what is available)")
    parser.add_argument("--progress", action="store_true",
                        help="print the progress to the standard error")
    args = parser.parse_args()
    mesh = torus(args.points)
    base = status()
    if args.storage == "streamed":
        report(mesh, args, base, *streamed(mesh, args, base))
        return
    basis = mh.vtkManifoldHarmonicBasis()
    basis.SetInputData(mesh)
    basis.SetNumberOfHarmonics(args.harmonics)
    basis.SetStorage(basis.FILE if args.storage == "file" else basis.IN_MEMORY)
    if args.float:
        basis.SetBasisPrecisionToFloat()
    basis.SetBandSize(args.band_size)
    basis.SetMemoryLimit(args.memory_limit)
    if args.progress:
        watch_progress(basis)
    if args.file:
        basis.SetBasisFileName(args.file)
    transform = mh.vtkManifoldHarmonicTransform()
    transform.SetInputConnection(basis.GetOutputPort())
    spectral = mh.vtkSpectralFilter()
    spectral.SetInputConnection(transform.GetOutputPort())
    seconds, after, disk = {}, {}, {}
    for stage, run in (("basis", basis.Update), ("transform+filter", spectral.Update),
                       ("changed filter", lambda: (spectral.SetCutoff(0.25), spectral.Update())),
                       ("enhancement", lambda: (spectral.SetFilterKindToEnhancement(),
                                                spectral.Update()))):
        before = io()
        start = time.time()
        run()
        seconds[stage] = time.time() - start
        after[stage] = status()
        disk[stage] = {k: io()[k] - before[k] for k in before}
    report(mesh, args, base, seconds, after, disk, basis.GetStorageReason())


def report(mesh, args, base, seconds, after, disk, reason):
    print("%d points x %d harmonics, %s%s, band size %d: %s" % (
        mesh.GetNumberOfPoints(), args.harmonics, args.storage, " float" if args.float else "",
        args.band_size, reason))
    for stage in seconds:
        s = after[stage]
        print("  %-17s %7.1f s  peak %7.0f MiB  RssAnon %7.0f MiB  RssFile %7.0f MiB (above "
              "baseline)  disk read %7.0f MiB  written %7.0f MiB"
              % (stage, seconds[stage], s["VmHWM"] - base["VmHWM"], s["RssAnon"] - base["RssAnon"],
                 s["RssFile"] - base["RssFile"], disk[stage]["read_bytes"],
                 disk[stage]["write_bytes"]))


if __name__ == "__main__":
    main()
