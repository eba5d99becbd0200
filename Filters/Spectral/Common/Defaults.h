// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Defaults.h
 * @brief The defaults that the core, the filters and the examples share, each written once.
 *
 * The filters' constructors and the core's option structures take their defaults from here; the
 * ParaView XML repeats them for the GUI and Testing/ParaView checks that it agrees.
 */
#ifndef spectral_Defaults_h
#define spectral_Defaults_h

namespace spectral
{
/// The number of harmonics computed when none is asked for.
constexpr int DefaultNumberOfHarmonics = 100;
/// The neighbours of each point that the point-cloud Laplacian triangulates (Sharp and Crane's
/// choice; Operators/PointCloud.h).
constexpr int DefaultNumberOfNeighbors = 30;
} // namespace spectral

#endif
