# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""Spectral filtering of a surface mesh: basis -> transform -> filter -> .vtp.

Usage (pvpython, with the build tree's env.sh sourced):

    pvpython filter_mesh.py input.(ply|obj|stl|vtp) output.vtp [--harmonics M]
        [--kind lowpass|highpass|bandpass|bandstop|enhancement|exaggeration|heat|custom]
        [--cutoff W] [--upper W] [--gain G] [--time T] [--no-reinject] [--threads T]

The cutoff defaults to half the highest computed frequency; custom is a ramp from gain 1 at 0
to gain 0 at the cutoff; the heat time defaults to ln 2 / cutoff^2, where the heat kernel halves
the cutoff frequency. The Python twin of
Examples/Cxx/ManifoldHarmonicFilter.cxx; run by CTest on Testing/Data/bunny.ply.
"""

import argparse
import math
import os
import sys

from vtkmodules.vtkIOGeometry import vtkOBJReader, vtkSTLReader
from vtkmodules.vtkIOPLY import vtkPLYReader
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter

from manifoldharmonics import (
    vtkManifoldHarmonicBasis,
    vtkManifoldHarmonicTransform,
    vtkSpectralFilter,
)

READERS = {".ply": vtkPLYReader, ".obj": vtkOBJReader, ".stl": vtkSTLReader,
           ".vtp": vtkXMLPolyDataReader}

KINDS = {
    "lowpass": vtkSpectralFilter.LOW_PASS,
    "highpass": vtkSpectralFilter.HIGH_PASS,
    "bandpass": vtkSpectralFilter.BAND_PASS,
    "bandstop": vtkSpectralFilter.BAND_STOP,
    "enhancement": vtkSpectralFilter.ENHANCEMENT,
    "exaggeration": vtkSpectralFilter.BAND_EXAGGERATION,
    "heat": vtkSpectralFilter.HEAT_DIFFUSION,
    "custom": vtkSpectralFilter.CUSTOM,
}


def positive_int(text):
    value = int(text)
    if value < 1:
        raise argparse.ArgumentTypeError("must be at least 1, not %d" % value)
    return value


def non_negative_int(text):
    value = int(text)
    if value < 0:
        raise argparse.ArgumentTypeError("must be at least 0, not %d" % value)
    return value


def non_negative_float(text):
    value = float(text)
    if not value >= 0.0 or math.isinf(value):
        raise argparse.ArgumentTypeError("must be a finite number >= 0, not %s" % text)
    return value


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input", help="surface mesh: .ply, .obj, .stl or .vtp")
    parser.add_argument("output", help="filtered mesh, .vtp")
    default_harmonics = vtkManifoldHarmonicBasis.DEFAULT_NUMBER_OF_HARMONICS
    parser.add_argument("--harmonics", type=positive_int, default=default_harmonics,
                        help="number of harmonics, at least 1 (default %d)" % default_harmonics)
    parser.add_argument("--threads", type=non_negative_int, default=0,
                        help="threads of the eigensolve and the filter stage "
                             "(default 0: every core)")
    parser.add_argument("--kind", choices=sorted(KINDS), default="lowpass",
                        help="transfer function (default lowpass)")
    parser.add_argument("--cutoff", type=non_negative_float, default=None,
                        help="cutoff frequency (default: half the highest computed one)")
    parser.add_argument("--upper", type=non_negative_float, default=None,
                        help="upper band edge (default: twice the cutoff)")
    parser.add_argument("--gain", type=float, default=2.0,
                        help="gain of enhancement and exaggeration (default 2)")
    parser.add_argument("--time", type=non_negative_float, default=None,
                        help="heat diffusion time (default: ln 2 / cutoff^2, the gain at the "
                        "cutoff is 1/2)")
    parser.add_argument("--no-reinject", action="store_true",
                        help="drop the frequencies above the last harmonic")
    return parser.parse_args(argv)


def read_surface(file_name):
    extension = os.path.splitext(file_name)[1].lower()
    if extension not in READERS:
        raise SystemExit("unknown extension %r: use .ply, .obj, .stl or .vtp" % extension)
    reader = READERS[extension]()
    reader.SetFileName(file_name)
    reader.Update()
    return reader.GetOutput()


def main(argv):
    args = parse_arguments(argv)
    if not args.output.lower().endswith(".vtp"):
        raise SystemExit("the output is written as VTK XML polydata: name it .vtp, not %s"
                         % args.output)
    folder = os.path.dirname(os.path.abspath(args.output))
    if not os.path.isdir(folder):
        raise SystemExit("cannot write %s: no folder %s" % (args.output, folder))
    surface = read_surface(args.input)
    if surface.GetNumberOfPoints() == 0:
        raise SystemExit("no surface read from %s" % args.input)

    basis = vtkManifoldHarmonicBasis()
    basis.SetInputData(surface)
    basis.SetNumberOfHarmonics(args.harmonics)
    basis.SetNumberOfThreads(args.threads)
    basis.Update()
    eigenvalues = basis.GetOutput().GetFieldData().GetArray(
        vtkManifoldHarmonicBasis.EigenvaluesArrayName())
    if eigenvalues is None:
        raise SystemExit("the basis could not be computed")
    m = eigenvalues.GetNumberOfTuples()
    highest = math.sqrt(max(eigenvalues.GetValue(m - 1), 0.0))
    print("%d points, %d harmonics, frequencies up to %g"
          % (surface.GetNumberOfPoints(), m, highest))

    transform = vtkManifoldHarmonicTransform()
    transform.SetInputConnection(basis.GetOutputPort())
    transform.SetNumberOfThreads(args.threads)

    cutoff = args.cutoff if args.cutoff is not None else 0.5 * highest
    time = args.time if args.time is not None else (
        math.log(2.0) / cutoff ** 2 if cutoff > 0.0 else 0.0)
    spectral = vtkSpectralFilter()
    spectral.SetInputConnection(transform.GetOutputPort())
    spectral.SetNumberOfThreads(args.threads)
    spectral.SetFilterKind(KINDS[args.kind])
    spectral.SetCutoffUnitsToAbsoluteFrequency()  # the options are frequencies
    spectral.SetCutoff(cutoff)
    spectral.SetUpperCutoff(args.upper if args.upper is not None else 2.0 * cutoff)
    spectral.SetGain(args.gain)
    spectral.SetTime(time)
    spectral.SetReinjectHighFrequencies(not args.no_reinject)
    spectral.RemoveAllControlPoints()
    spectral.AddControlPoint(0.0, 1.0)
    spectral.AddControlPoint(cutoff, 0.0)
    if not spectral.GetExecutive().Update():
        raise SystemExit("the spectral filter failed")

    writer = vtkXMLPolyDataWriter()
    writer.SetInputConnection(spectral.GetOutputPort())
    writer.SetFileName(args.output)
    # Inline binary data: VTK before 9.3.1 cannot read appended data back with expat >= 2.6.
    writer.SetDataModeToBinary()
    if writer.Write() != 1 or writer.GetErrorCode() != 0:
        raise SystemExit("could not write %s" % args.output)
    setting = "time %g" % time if args.kind == "heat" else "cutoff %g" % cutoff
    print("filter %s, %s: wrote %s" % (args.kind, setting, args.output))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
