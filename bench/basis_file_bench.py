# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""The basis of a torus in memory or in a file (vtkManifoldHarmonicBasis Storage), one case a
process so that the peak resident sizes are its own:

    . build/env.sh
    /usr/bin/python3 bench/basis_file_bench.py --points 200000 --harmonics 500 --storage file

Prints the seconds of the basis, of a first transform + low-pass and of a changed filter (the
read-back of the basis), the peak resident size (VmHWM) and the anonymous and file-backed
resident sizes (RssAnon, RssFile of /proc/self/status) after each stage, in MiB above the
process's baseline before the basis. Documentation/large-meshes.md reports its figures.
"""
import argparse
import math
import os
import time

from vtkmodules.vtkFiltersSources import vtkParametricFunctionSource
from vtkmodules.vtkCommonComputationalGeometry import vtkParametricTorus
from vtkmodules.vtkFiltersCore import vtkCleanPolyData
import manifoldharmonics as mh


def status():
    fields = {}
    with open("/proc/self/status") as f:
        for line in f:
            key, _, value = line.partition(":")
            if key in ("VmHWM", "RssAnon", "RssFile"):
                fields[key] = int(value.split()[0]) / 1024.0
    return fields


def torus(points):
    side = int(math.sqrt(points))
    surface = vtkParametricTorus()
    surface.SetRingRadius(1.0)
    surface.SetCrossSectionRadius(0.4)
    source = vtkParametricFunctionSource()
    source.SetParametricFunction(surface)
    source.SetUResolution(side)
    source.SetVResolution(side)
    source.SetScalarModeToNone()
    source.GenerateTextureCoordinatesOff()
    source.GenerateNormalsOff()
    clean = vtkCleanPolyData()
    clean.SetInputConnection(source.GetOutputPort())
    clean.Update()
    return clean.GetOutput()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--points", type=int, default=200000)
    parser.add_argument("--harmonics", type=int, default=500)
    parser.add_argument("--storage", choices=["memory", "file"], default="memory")
    parser.add_argument("--file", default="")
    parser.add_argument("--float", action="store_true")
    parser.add_argument("--band-size", type=int, default=0)
    args = parser.parse_args()
    mesh = torus(args.points)
    base = status()
    basis = mh.vtkManifoldHarmonicBasis()
    basis.SetInputData(mesh)
    basis.SetNumberOfHarmonics(args.harmonics)
    basis.SetStorage(basis.FILE if args.storage == "file" else basis.IN_MEMORY)
    if args.float:
        basis.SetBasisPrecisionToFloat()
    basis.SetBandSize(args.band_size)
    if args.file:
        basis.SetBasisFileName(args.file)
    start = time.time()
    basis.Update()
    seconds = {"basis": time.time() - start}
    after = {"basis": status()}
    transform = mh.vtkManifoldHarmonicTransform()
    transform.SetInputConnection(basis.GetOutputPort())
    spectral = mh.vtkSpectralFilter()
    spectral.SetInputConnection(transform.GetOutputPort())
    start = time.time()
    spectral.Update()
    seconds["transform+filter"] = time.time() - start
    after["transform+filter"] = status()
    spectral.SetCutoff(0.25)
    start = time.time()
    spectral.Update()
    seconds["changed filter"] = time.time() - start
    after["changed filter"] = status()
    print("%d points x %d harmonics, %s%s, band size %d: %s" % (
        mesh.GetNumberOfPoints(), args.harmonics, args.storage, " float" if args.float else "",
        args.band_size, basis.GetStorageReason()))
    for stage in seconds:
        s = after[stage]
        print("  %-17s %7.1f s  peak %7.0f MiB  RssAnon %7.0f MiB  RssFile %7.0f MiB (above baseline)"
              % (stage, seconds[stage], s["VmHWM"] - base["VmHWM"], s["RssAnon"] - base["RssAnon"],
                 s["RssFile"] - base["RssFile"]))


if __name__ == "__main__":
    main()
