// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Meshes of any size for the benchmark: a torus with radial noise (a stand-in for a scan).
#ifndef spectral_BenchMeshes_h
#define spectral_BenchMeshes_h

#include "Mesh.h"

#include <cmath>
#include <random>

namespace spectral
{
namespace bench
{
/**
 * Torus with major radius 1 and minor radius 0.35, nu by nv quads split into triangles, each point
 * moved along the tube normal by uniform noise of `noise` times the minor radius (fixed seed).
 * nu * nv points.
 */
inline TriangleMesh NoisyTorus(int nu, int nv, double noise)
{
  const double pi = 3.14159265358979323846;
  const double R = 1.0;
  const double r = 0.35;
  std::mt19937 generator(7u);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  TriangleMesh mesh;
  mesh.Vertices.resize(static_cast<Eigen::Index>(nu) * nv, 3);
  for (int i = 0; i < nu; ++i)
  {
    const double u = 2.0 * pi * i / nu;
    for (int j = 0; j < nv; ++j)
    {
      const double v = 2.0 * pi * j / nv;
      const double rr = r * (1.0 + noise * uniform(generator));
      mesh.Vertices.row(static_cast<Eigen::Index>(i) * nv + j) << (R + rr * std::cos(v)) *
          std::cos(u),
        (R + rr * std::cos(v)) * std::sin(u), rr * std::sin(v);
    }
  }
  mesh.Faces.resize(2 * static_cast<Eigen::Index>(nu) * nv, 3);
  Eigen::Index t = 0;
  for (int i = 0; i < nu; ++i)
  {
    for (int j = 0; j < nv; ++j)
    {
      const int a = i * nv + j;
      const int b = ((i + 1) % nu) * nv + j;
      const int c = ((i + 1) % nu) * nv + (j + 1) % nv;
      const int d = i * nv + (j + 1) % nv;
      mesh.Faces.row(t++) << a, b, c;
      mesh.Faces.row(t++) << a, c, d;
    }
  }
  return mesh;
}

/// A noisy torus of about n points with a tube resolution proportional to the ring's.
inline TriangleMesh NoisyTorusOfSize(int n, double noise)
{
  // Points are spaced evenly when nv / nu = r / R = 0.35.
  const int nu = static_cast<int>(std::lround(std::sqrt(n / 0.35)));
  const int nv = std::max(3, static_cast<int>(std::lround(static_cast<double>(n) / nu)));
  return NoisyTorus(nu, nv, noise);
}
} // namespace bench
} // namespace spectral

#endif
