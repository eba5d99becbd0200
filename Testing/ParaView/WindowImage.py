# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
"""The ParaView window as a PNG, from the screen file of an Xvfb started with -fbdir.

Used inside paraview (its Python has numpy) by the GUI test (TestManifoldHarmonicsGUI.py.in,
Documentation/images/paraview-gui.png) and by scripts/screenshot-functional-map.py
(Documentation/images/functional-map.png).
"""

import struct


def window_image(framebuffer, path):
    """Convert the X screen (an XWD file, 32-bit TrueColor) to a PNG of the ParaView window."""
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkImageData
    from vtkmodules.vtkIOImage import vtkPNGWriter
    import numpy

    with open(framebuffer, "rb") as stream:
        data = stream.read()
    header = struct.unpack(">25I", data[:100])
    header_size, width, height = header[0], header[4], header[5]
    little_endian, bits_per_pixel, bytes_per_line, colormap_entries = (
        header[7] == 0, header[11], header[12], header[19])
    if bits_per_pixel != 32:
        raise RuntimeError("framebuffer with %d bits per pixel" % bits_per_pixel)
    pixels = numpy.frombuffer(data, dtype="<u4" if little_endian else ">u4",
                              count=height * bytes_per_line // 4,
                              offset=header_size + 12 * colormap_entries)
    pixels = pixels.reshape(height, bytes_per_line // 4)[:, :width]
    rgb = numpy.stack([(pixels >> 16) & 255, (pixels >> 8) & 255, pixels & 255], axis=-1)
    # The window sits in the top left corner of an otherwise black screen.
    used = numpy.argwhere(rgb.max(axis=2) > 0)
    rows, columns = used.max(axis=0) + 1
    window = numpy.ascontiguousarray(rgb[rows - 1::-1, :columns].astype(numpy.uint8))
    image = vtkImageData()
    image.SetDimensions(columns, rows, 1)
    image.GetPointData().SetScalars(numpy_to_vtk(window.reshape(-1, 3), deep=1))
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputData(image)
    writer.Write()
