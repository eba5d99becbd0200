# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""Start-up script of scripts/screenshot-functional-map.sh (paraview --script=).

The source: the bunny (Clean) with the integer label Part (1 on its top fifth: the ears and the
top of the head), made by a Calculator. The target: a second, coarser scan (Decimate keeps half
the points) moved rigidly (Transform). Functional Map with its defaults (Input = target,
Source = source) carries Part to the target through the point map. The render view shows the
source (left) and the target (right), both coloured by Part; the Properties panel shows Functional
Map. arrange() and capture() are called by screenshot-functional-map.xml.
"""

import os
import sys

from paraview import simple

BUNNY = os.environ["MANIFOLDHARMONICS_BUNNY"]
sys.path.insert(0, os.environ["MANIFOLDHARMONICS_WINDOW_IMAGE"])
from WindowImage import window_image  # noqa: E402

reader = simple.PLYReader(registrationName="bunny.ply", FileNames=[BUNNY])
clean = simple.Clean(registrationName="Scan 1", Input=reader)
source = simple.Calculator(registrationName="Scan 1 with Part", Input=clean,
                           ResultArrayName="Part", ResultArrayType="Int",
                           Function="coordsY > 7.76")
coarse = simple.Decimate(registrationName="Scan 2 (coarser)", Input=clean, TargetReduction=0.5,
                         PreserveTopology=1)
target = simple.Transform(registrationName="Scan 2 (moved)", Input=coarse)
target.Transform.Translate = [12.0, 0.0, 0.0]
target.Transform.Rotate = [0.0, 30.0, 0.0]
fmap = simple.FunctionalMap(registrationName="FunctionalMap1", Input=target, Source=source)

view = simple.GetActiveViewOrCreate("RenderView")
for proxy in (source, fmap):
    display = simple.Show(proxy, view)
    simple.ColorBy(display, ("POINTS", "Part"))
    display.SetRepresentationType("Surface With Edges")
    display.EdgeColor = [0.3, 0.3, 0.3]
colours = simple.GetColorTransferFunction("Part")
colours.ApplyPreset("Cool to Warm", True)
colours.RescaleTransferFunction(0.0, 1.0)
colours.Discretize = 1
colours.NumberOfTableValues = 2
view.OrientationAxesVisibility = 0
simple.SetActiveSource(fmap)


def arrange():
    """Both scans in view, the colour bar titled."""
    bar = simple.GetScalarBar(colours, view)
    bar.Title = "Part (scan 1 -> scan 2)"
    bar.ComponentTitle = ""
    bar.Visibility = 1
    view.CameraPosition = [6.5, 4.8, 38.0]
    view.CameraFocalPoint = [6.5, 4.8, 0.0]
    view.CameraViewUp = [0.0, 1.0, 0.0]
    view.CameraViewAngle = 30.0
    simple.Render(view)


def capture():
    window_image(os.environ["MANIFOLDHARMONICS_FRAMEBUFFER"],
                 os.environ["MANIFOLDHARMONICS_SCREENSHOT"])
