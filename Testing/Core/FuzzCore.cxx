// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target over the spectral core. The input bytes decode into a small triangle soup
// (coordinates on a coarse grid with occasional zero, tiny, huge and non-finite values;
// triangles with arbitrary, possibly repeated or out-of-range indices), which then goes through
// ComputeBasis (the filter's whole computation: PrepareMesh, either Laplacian, the eigensolver
// and its fallbacks) with a small m, and a filter round trip.
//
// Allowed outcomes are a documented exception (InvalidInput, SolverFailure) or a result that is
// finite and has the promised shape; anything else aborts, and so does a sanitizer report.
// Built by Testing/Core/CMakeLists.txt with MANIFOLDHARMONICS_FUZZ=ON; run by scripts/test.sh.
#include "Basis.h"
#include "Filtering/Transfer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>

namespace
{
/// Reads bytes from the fuzz input; zero once exhausted.
class Reader
{
public:
  Reader(const std::uint8_t* data, std::size_t size)
    : Data(data)
    , Size(size)
  {
  }
  std::uint8_t Byte() { return this->Position < this->Size ? this->Data[this->Position++] : 0; }
  bool Empty() const { return this->Position >= this->Size; }

private:
  const std::uint8_t* Data;
  std::size_t Size;
  std::size_t Position = 0;
};

void Require(bool condition, const char* what)
{
  if (!condition)
  {
    std::fprintf(stderr, "FuzzCore: %s\n", what);
    std::abort();
  }
}

/// A coordinate: mostly small integers (coplanar and coincident points are likely), sometimes
/// a value at an extreme scale or a non-finite one.
double Coordinate(Reader& in)
{
  const std::uint8_t b = in.Byte();
  switch (b)
  {
    case 250:
      return 1e-150;
    case 251:
      return 1e150;
    case 252:
      return -0.0;
    case 253:
      return 1e-7 * in.Byte();
    case 254:
      return std::numeric_limits<double>::quiet_NaN();
    case 255:
      return std::numeric_limits<double>::infinity();
    default:
      return static_cast<double>(b % 16) - 8.0 + (b / 16) * 0.0625;
  }
}

spectral::TriangleMesh Decode(Reader& in)
{
  spectral::TriangleMesh mesh;
  const int numPts = 1 + in.Byte() % 24;
  const int numTris = in.Byte() % 40;
  mesh.Vertices.resize(numPts, 3);
  for (int i = 0; i < numPts; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      mesh.Vertices(i, c) = Coordinate(in);
    }
  }
  mesh.Faces.resize(numTris, 3);
  for (int f = 0; f < numTris; ++f)
  {
    for (int c = 0; c < 3; ++c)
    {
      // Mostly in range; 255 gives an out-of-range index.
      const std::uint8_t b = in.Byte();
      mesh.Faces(f, c) = b == 255 ? numPts + 3 : b % numPts;
    }
  }
  return mesh;
}

void Run(Reader& in)
{
  const spectral::TriangleMesh input = Decode(in);
  // The whole computation of vtkManifoldHarmonicBasis: the core's one entry point.
  spectral::BasisOptions options;
  options.Operators.Laplacian = (in.Byte() & 1) != 0 ? spectral::LaplacianKind::IntrinsicDelaunay
                                                     : spectral::LaplacianKind::Cotangent;
  options.NumberOfHarmonics = 1 + in.Byte() % 6;
  options.Solver.BandSize = in.Byte() % 4;
  options.Solver.DenseThreshold = (in.Byte() & 1) ? 1000 : 0;
  spectral::BasisResult basis;
  try
  {
    basis = spectral::ComputeBasis(input, options);
  }
  catch (const spectral::InvalidInput&)
  {
    return;
  }
  catch (const spectral::SolverFailure&)
  {
    return;
  }
  const spectral::EigenResult& result = basis.Pairs;
  const int n = static_cast<int>(basis.InputPointIds.size());
  const spectral::Vector& lumped = basis.LumpedMass;
  Require(n > 0 && n <= input.Vertices.rows(), "point count");
  Require(lumped.size() == n && lumped.allFinite(), "finite mass of every used point");
  Require((lumped.array() > 0.0).all(), "every used point has mass");
  const int m = static_cast<int>(std::min<Eigen::Index>(options.NumberOfHarmonics, n));
  Require(result.Eigenvalues.size() == m && result.Eigenvectors.rows() == n &&
      result.Eigenvectors.cols() == m,
    "eigenpair shapes");
  Require(result.Eigenvalues.allFinite() && result.Eigenvectors.allFinite(), "finite eigenpairs");
  for (int k = 1; k < m; ++k)
  {
    Require(result.Eigenvalues[k] >= result.Eigenvalues[k - 1], "ascending eigenvalues");
  }
  spectral::Points used(n, 3);
  for (int r = 0; r < n; ++r)
  {
    used.row(r) = input.Vertices.row(basis.InputPointIds[static_cast<std::size_t>(r)]);
  }

  // Low-pass round trip of the coordinates through the basis.
  const spectral::RowMatrix H = result.Eigenvectors;
  const spectral::RowMatrix X = used;
  const spectral::BasisView view(H.data(), H.rows(), H.cols());
  const spectral::ConstRowView signal(X.data(), X.rows(), X.cols());
  const spectral::RowMatrix coefficients = spectral::ForwardTransform(view, lumped, signal);
  spectral::FilterParameters p;
  p.Kind = static_cast<spectral::FilterKind>(in.Byte() % 7);
  p.Cutoff = 0.5 * (in.Byte() % 8);
  p.UpperCutoff = p.Cutoff + 0.5 * (in.Byte() % 8);
  p.Time = 0.01 * in.Byte();
  const spectral::Vector gains = spectral::Gains(p, result.Eigenvalues);
  const spectral::ConstRowView coefficientView(
    coefficients.data(), coefficients.rows(), coefficients.cols());
  const spectral::RowMatrix Y =
    spectral::InverseTransform(view, gains, coefficientView, signal, in.Byte() % 2);
  Require(Y.rows() == n && Y.cols() == 3 && Y.allFinite(), "finite filtered signal");
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Reader in(data, size);
  Run(in);
  return 0;
}
