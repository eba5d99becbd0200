# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""The basis filter as a ParaView user meets it: seconds of ManifoldHarmonicBasis in pvpython.

Run with pvpython after `. build/env.sh` (which makes the plugin discoverable):

    pvpython bench/paraview_filter_bench.py --resolution 100 --harmonics 100 --repeat 5

The surface is ParaView's Superquadric source as a torus (Toroidal, Thickness 0.35) of
resolution x resolution cells, triangulated and cleaned (its seam points merged): about
resolution^2 points. Each repeat makes a new ManifoldHarmonicBasis on it with default settings
but NumberOfHarmonics and times UpdatePipeline (the whole filter: assembly, eigensolve, checks and
the output arrays). Prints the points and the seconds of each repeat.
"""

import argparse
import time

from paraview.simple import Clean, Delete, ManifoldHarmonicBasis, Superquadric, Triangulate


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--resolution", type=int, default=100)
    parser.add_argument("--harmonics", type=int, default=100)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()

    torus = Superquadric(Toroidal=1, ThetaResolution=args.resolution,
                         PhiResolution=args.resolution, Thickness=0.35)
    surface = Clean(Input=Triangulate(Input=torus))
    surface.UpdatePipeline()
    points = surface.GetDataInformation().GetNumberOfPoints()
    seconds = []
    for _ in range(args.repeat):
        basis = ManifoldHarmonicBasis(Input=surface)
        basis.NumberOfHarmonics = args.harmonics
        start = time.perf_counter()
        basis.UpdatePipeline()
        seconds.append(time.perf_counter() - start)
        Delete(basis)
    print("points=%d harmonics=%d seconds=%s" %
          (points, args.harmonics, " ".join("%.3f" % s for s in seconds)))


if __name__ == "__main__":
    main()
