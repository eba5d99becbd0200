#!/bin/bash
# SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
# SPDX-License-Identifier: BSD-3-Clause
# Renders Documentation/images/functional-map.png: the paraview GUI with Functional Map applied
# to two scans of the bunny, a label carried from one to the other.
#   bash scripts/screenshot-functional-map.sh [build directory, default: build] [output png]
# Needs xvfb-run and a configured and built tree (the plugin and its Python package).
set -euo pipefail
top="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:-${top}/build}" && pwd)"
output="$(realpath -m "${2:-${top}/Documentation/images/functional-map.png}")"
. "${build}/env.sh"
framebuffer="$(mktemp -d)"
trap 'rm -rf "${framebuffer}"' EXIT
MANIFOLDHARMONICS_BUNNY="${top}/Testing/Data/bunny.ply" \
MANIFOLDHARMONICS_FRAMEBUFFER="${framebuffer}/Xvfb_screen0" \
MANIFOLDHARMONICS_SCREENSHOT="${output}" \
MANIFOLDHARMONICS_WINDOW_IMAGE="${top}/Testing/ParaView" \
  xvfb-run -a -s "-screen 0 1280x800x24 -nocursor -fbdir ${framebuffer}" \
  paraview --dr \
    "--script=${top}/scripts/screenshot-functional-map.py" \
    "--test-script=${top}/scripts/screenshot-functional-map.xml" \
    --exit
test -s "${output}"
echo "wrote ${output}"
