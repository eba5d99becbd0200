// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Constants.h
 * @brief The mathematical constants of the core, each written once.
 */
#ifndef spectral_Constants_h
#define spectral_Constants_h

namespace spectral
{
/// pi to double precision (M_PI is not standard C++17).
constexpr double Pi = 3.14159265358979323846;
} // namespace spectral

#endif
