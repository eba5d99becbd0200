// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Tetrahedral volumes and Dirichlet conditions through the core's entry point (Basis.h): the P1
// operators of tetrahedra (Operators/Operators.h) against independent formulas, the spectra of
// the unit cube, the unit ball, the unit square and the unit disc against their analytic values
// (computed here: products of sines and cosines, zeros of Bessel functions found by bisection),
// second-order convergence, filtering on a volume, and the volume defects PrepareMesh handles.
#include "Basis.h"
#include "BasisChecks.h"
#include "Checks.h"
#include "Filtering/Transfer.h"
#include "Meshes.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <vector>

using namespace spectral;
using namespace spectral::testing;

namespace
{
const double Pi = 3.14159265358979323846;

//------------------------------------------------------------------------------
// The k smallest eigenvalues of the mesh's Laplacian with the given boundary condition.
BasisResult Solve(const TriangleMesh& mesh, int k, BoundaryCondition boundary)
{
  BasisOptions options;
  options.NumberOfHarmonics = k;
  options.Operators.Boundary = boundary;
  options.CheckMemory = false;
  return ComputeBasis(mesh, options);
}

//------------------------------------------------------------------------------
// pi^2 (a^2 + b^2 [+ c^2]) for a, b [, c] >= first, sorted: the Laplacian of the unit square
// (dimension 2) or cube (3), Neumann (first 0) or Dirichlet (first 1).
std::vector<double> BoxSpectrum(int dimension, int first, int count)
{
  std::vector<double> lambda;
  const int top = first + 12;
  for (int a = first; a < top; ++a)
  {
    for (int b = first; b < top; ++b)
    {
      for (int c = (dimension == 3 ? first : 0); c < (dimension == 3 ? top : 1); ++c)
      {
        lambda.push_back(Pi * Pi * (a * a + b * b + c * c));
      }
    }
  }
  std::sort(lambda.begin(), lambda.end());
  lambda.resize(static_cast<std::size_t>(count));
  return lambda;
}

//------------------------------------------------------------------------------
// The zeros of f in (from, to), found by a scan of step h and bisection to round-off.
std::vector<double> Zeros(const std::function<double(double)>& f, double from, double to)
{
  const double h = 1e-3;
  std::vector<double> zeros;
  for (double x = from; x + h <= to; x += h)
  {
    double lo = x;
    double hi = x + h;
    double flo = f(lo);
    if (flo == 0.0 || (flo < 0.0) == (f(hi) < 0.0))
    {
      continue;
    }
    for (int i = 0; i < 100; ++i)
    {
      const double mid = 0.5 * (lo + hi);
      if ((f(mid) < 0.0) == (flo < 0.0))
      {
        lo = mid;
        flo = f(mid);
      }
      else
      {
        hi = mid;
      }
    }
    zeros.push_back(0.5 * (lo + hi));
  }
  return zeros;
}

//------------------------------------------------------------------------------
// The Bessel function J_n(x) = (1 / 2 pi) int_0^2pi cos(n t - x sin t) dt, by the trapezoid
// rule (exponentially accurate for this periodic integrand).
double BesselJ(int n, double x)
{
  const int N = 256;
  double sum = 0.0;
  for (int i = 0; i < N; ++i)
  {
    const double t = 2.0 * Pi * i / N;
    sum += std::cos(n * t - x * std::sin(t));
  }
  return sum / N;
}

//------------------------------------------------------------------------------
// The derivative of the spherical Bessel function j_l: j_0' = -j_1, j_l' = j_(l-1) - (l+1)/x j_l,
// with j_l from the upward recurrence (stable for the x > l used here).
double SphericalBesselDerivative(int l, double x)
{
  std::vector<double> j(static_cast<std::size_t>(l + 2));
  j[0] = std::sin(x) / x;
  j[1] = std::sin(x) / (x * x) - std::cos(x) / x;
  for (int k = 1; k + 1 <= l; ++k)
  {
    j[static_cast<std::size_t>(k + 1)] =
      (2 * k + 1) / x * j[static_cast<std::size_t>(k)] - j[static_cast<std::size_t>(k - 1)];
  }
  return l == 0 ? -j[1]
                : j[static_cast<std::size_t>(l - 1)] - (l + 1) / x * j[static_cast<std::size_t>(l)];
}

//------------------------------------------------------------------------------
// Eigenvalues z^2 of the zeros z < limit of each f_n (n = 0..orders-1), each repeated
// multiplicity(n) times, with `extra` (0 for Neumann) in front; the `count` smallest.
std::vector<double> SpectrumFromZeros(const std::function<double(int, double)>& f,
  const std::function<int(int)>& multiplicity,
  int orders,
  double limit,
  int count,
  bool zero)
{
  std::vector<double> lambda;
  if (zero)
  {
    lambda.push_back(0.0);
  }
  for (int n = 0; n < orders; ++n)
  {
    for (double z : Zeros([&f, n](double x) { return f(n, x); }, 0.5, limit))
    {
      lambda.insert(lambda.end(), static_cast<std::size_t>(multiplicity(n)), z * z);
    }
  }
  std::sort(lambda.begin(), lambda.end());
  Check(static_cast<int>(lambda.size()) >= count, "enough analytic eigenvalues");
  lambda.resize(static_cast<std::size_t>(count));
  return lambda;
}

//------------------------------------------------------------------------------
// The largest relative error of the computed eigenvalues against the analytic ones (sorted,
// so that each cluster of equal analytic values is matched by as many computed ones: the
// multiplicities), zero eigenvalues measured against the first non-zero one.
double SpectrumError(const Vector& computed, const std::vector<double>& analytic, bool print)
{
  double worst = 0.0;
  const double scale = *std::upper_bound(analytic.begin(), analytic.end(), 0.0);
  for (std::size_t k = 0; k < analytic.size(); ++k)
  {
    const double exact = analytic[k];
    const double error =
      std::abs(computed[static_cast<Eigen::Index>(k)] - exact) / (exact > 0.0 ? exact : scale);
    if (print)
    {
      std::printf(
        "  %2zu  %12.6f  %12.6f  %.2e\n", k, computed[static_cast<Eigen::Index>(k)], exact, error);
    }
    worst = std::max(worst, error);
  }
  return worst;
}

//------------------------------------------------------------------------------
// A random tetrahedron's P1 stiffness against the dihedral-angle formula: the weight of edge
// ij is l_kl cot(theta_kl) / 6, theta_kl the dihedral angle at the opposite edge kl.
void StiffnessFromDihedralAngles()
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial)
  {
    TriangleMesh tet;
    tet.Vertices.resize(4, 3);
    for (int i = 0; i < 12; ++i)
    {
      tet.Vertices(i / 3, i % 3) = coordinate(random);
    }
    tet.Tets.resize(1, 4);
    tet.Tets << 0, 1, 2, 3;
    const Eigen::MatrixXd Q = CotanStiffness(tet);
    double worst = 0.0;
    for (int i = 0; i < 4; ++i)
    {
      for (int j = i + 1; j < 4; ++j)
      {
        int kl[2];
        int n = 0;
        for (int c = 0; c < 4; ++c)
        {
          if (c != i && c != j)
          {
            kl[n++] = c;
          }
        }
        const Eigen::Vector3d k = tet.Vertices.row(kl[0]).transpose();
        const Eigen::Vector3d l = tet.Vertices.row(kl[1]).transpose();
        const Eigen::Vector3d e = (l - k).normalized();
        // The dihedral angle at kl: between the faces kli and klj, measured across kl.
        Eigen::Vector3d u = tet.Vertices.row(i).transpose() - k;
        Eigen::Vector3d v = tet.Vertices.row(j).transpose() - k;
        u -= u.dot(e) * e;
        v -= v.dot(e) * e;
        const double theta = std::acos(u.dot(v) / (u.norm() * v.norm()));
        const double weight = (l - k).norm() / std::tan(theta) / 6.0;
        worst = std::max(worst, std::abs(-Q(i, j) - weight) / std::max(1.0, std::abs(weight)));
      }
    }
    CheckBelow(
      worst, 1e-12, "P1 edge weights equal l cot(theta) / 6, trial " + std::to_string(trial));
    CheckBelow(Q.rowwise().sum().cwiseAbs().maxCoeff(), 1e-13, "Q 1 = 0");
  }
}

//------------------------------------------------------------------------------
// Linear functions are in the kernel of Q at interior points (P1 reproduces them exactly), the
// mass is the volume, the consistent mass sums to the lumped mass, and both orientations of
// every tetrahedron give the same operators.
void TetrahedralOperators()
{
  TriangleMesh box = TetrahedralBox(1.0, 2.0, 0.5, 4, 5, 3);
  // Jitter the interior points, so that the weights are not those of a regular grid.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const std::vector<char> boundary = BoundaryPoints(box);
  int interior = 0;
  for (Eigen::Index i = 0; i < box.Vertices.rows(); ++i)
  {
    if (!boundary[static_cast<std::size_t>(i)])
    {
      box.Vertices.row(i) += Eigen::RowVector3d(jitter(random), jitter(random), jitter(random));
      ++interior;
    }
  }
  Check(interior == 3 * 4 * 2,
    "the boundary of the box is its six faces (interior " + std::to_string(interior) + ")");
  const SparseMatrix Q = CotanStiffness(box);
  const Vector linear =
    box.Vertices * Eigen::Vector3d(0.3, -1.2, 2.0) + Vector::Constant(box.Vertices.rows(), 0.7);
  const Vector Ql = Q * linear;
  double worst = 0.0;
  for (Eigen::Index i = 0; i < Ql.size(); ++i)
  {
    worst = boundary[static_cast<std::size_t>(i)] ? worst : std::max(worst, std::abs(Ql[i]));
  }
  CheckBelow(worst, 1e-12, "Q of a linear function vanishes at interior points");
  CheckNear(LumpedMass(box).sum(), 1.0, 1e-13, "the lumped mass is the volume");
  CheckNear(Measure(box), 1.0, 1e-13, "the measure is the volume");
  const SparseMatrix B = ConsistentMass(box);
  CheckBelow((B * Vector::Ones(B.cols()) - LumpedMass(box)).cwiseAbs().maxCoeff(),
    1e-15,
    "consistent row sums equal the lumped mass");
  CheckNear(linear.dot(B * linear) > 0.0 ? 1.0 : 0.0, 1.0, 0.0, "consistent mass positive");

  TriangleMesh flipped = box;
  for (Eigen::Index t = 0; t < flipped.Tets.rows(); t += 2)
  {
    std::swap(flipped.Tets(t, 0), flipped.Tets(t, 1));
  }
  CheckBelow(Eigen::MatrixXd(CotanStiffness(flipped) - Q).cwiseAbs().maxCoeff(),
    1e-14,
    "either orientation gives the same stiffness");
  CheckBelow(Eigen::MatrixXd(ConsistentMass(flipped) - B).cwiseAbs().maxCoeff(),
    1e-16,
    "either orientation gives the same mass");
}

//------------------------------------------------------------------------------
// The unit cube of tetrahedra (21^3 points): Neumann pi^2 (a^2 + b^2 + c^2), a, b, c >= 0, and
// Dirichlet, a, b, c >= 1, within 2% for the first 20, multiplicities included.
void UnitCube()
{
  const TriangleMesh cube = TetrahedralBox(1.0, 1.0, 1.0, 20, 20, 20);
  std::printf(" Neumann\n");
  const BasisResult neumann = Solve(cube, 20, BoundaryCondition::Neumann);
  CheckBelow(SpectrumError(neumann.Pairs.Eigenvalues, BoxSpectrum(3, 0, 20), true),
    0.02,
    "Neumann cube within 2%");
  Check(neumann.ConstantHarmonics && neumann.BoundaryPoints == 0, "Neumann keeps every point");
  std::printf(" Dirichlet\n");
  const BasisResult dirichlet = Solve(cube, 20, BoundaryCondition::Dirichlet);
  CheckBelow(SpectrumError(dirichlet.Pairs.Eigenvalues, BoxSpectrum(3, 1, 20), true),
    0.02,
    "Dirichlet cube within 2%");
  Check(!dirichlet.ConstantHarmonics, "Dirichlet has no constant harmonic");
  Check(dirichlet.BoundaryPoints == 21 * 21 * 21 - 19 * 19 * 19,
    "the boundary points are eliminated (" + std::to_string(dirichlet.BoundaryPoints) + ")");
  Check(dirichlet.InputPointIds.size() == 19 * 19 * 19, "rows for the interior points only");
  // The harmonics are M-orthonormal on the interior rows.
  const DenseMatrix& H = dirichlet.Pairs.Eigenvectors;
  const Eigen::MatrixXd gram = H.transpose() * dirichlet.LumpedMass.asDiagonal() * H;
  CheckBelow((gram - Eigen::MatrixXd::Identity(20, 20)).cwiseAbs().maxCoeff(),
    1e-8,
    "Dirichlet harmonics M-orthonormal");
}

//------------------------------------------------------------------------------
// Second order: halving the edges divides the eigenvalue errors of the cube by about 4.
void CubeConvergesAtSecondOrder()
{
  for (BoundaryCondition boundary : { BoundaryCondition::Neumann, BoundaryCondition::Dirichlet })
  {
    const bool dirichlet = boundary == BoundaryCondition::Dirichlet;
    const std::vector<double> exact = BoxSpectrum(3, dirichlet ? 1 : 0, 11);
    double errors[2];
    for (int level = 0; level < 2; ++level)
    {
      const int n = 8 << level;
      const Vector lambda =
        Solve(TetrahedralBox(1.0, 1.0, 1.0, n, n, n), 11, boundary).Pairs.Eigenvalues;
      errors[level] = 0.0;
      for (std::size_t k = dirichlet ? 0 : 1; k < exact.size(); ++k)
      {
        errors[level] += std::abs(lambda[static_cast<Eigen::Index>(k)] - exact[k]) / exact[k];
      }
    }
    const double order = std::log2(errors[0] / errors[1]);
    std::printf(" %s: summed relative errors %.3e (n = 8), %.3e (n = 16), order %.2f\n",
      dirichlet ? "Dirichlet" : "Neumann",
      errors[0],
      errors[1],
      order);
    CheckNear(order,
      2.0,
      0.3,
      std::string(dirichlet ? "Dirichlet" : "Neumann") + " cube converges at second order");
  }
}

//------------------------------------------------------------------------------
// The unit ball: Neumann eigenvalues are the squares of the zeros of j_l', multiplicity 2l+1.
void UnitBall()
{
  const std::vector<double> exact = SpectrumFromZeros(
    SphericalBesselDerivative, [](int l) { return 2 * l + 1; }, 8, 8.0, 17, true);
  const BasisResult ball = Solve(TetrahedralBall(16), 17, BoundaryCondition::Neumann);
  CheckBelow(
    SpectrumError(ball.Pairs.Eigenvalues, exact, true), 0.03, "Neumann unit ball within 3%");
}

//------------------------------------------------------------------------------
// The Dirichlet unit square, pi^2 (a^2 + b^2) with a, b >= 1, and unit disc, the squares of the
// zeros of J_n (multiplicity 2 for n > 0).
void DirichletSquareAndDisc()
{
  std::printf(" square\n");
  const BasisResult square = Solve(Rectangle(1.0, 1.0, 40, 40), 12, BoundaryCondition::Dirichlet);
  CheckBelow(SpectrumError(square.Pairs.Eigenvalues, BoxSpectrum(2, 1, 12), true),
    0.02,
    "Dirichlet square within 2%");
  Check(square.BoundaryPoints == 4 * 40, "the square's boundary points are eliminated");
  std::printf(" disc\n");
  const std::vector<double> exact = SpectrumFromZeros(
    BesselJ, [](int n) { return n == 0 ? 1 : 2; }, 8, 12.0, 12, false);
  const BasisResult disc = Solve(Disc(48), 12, BoundaryCondition::Dirichlet);
  CheckBelow(
    SpectrumError(disc.Pairs.Eigenvalues, exact, true), 0.02, "Dirichlet unit disc within 2%");
}

//------------------------------------------------------------------------------
// A closed surface has no boundary: Dirichlet is ignored with a warning, and the spectrum is
// the Neumann one; a mesh whose points all lie on the boundary is refused.
void DirichletWithoutInterior()
{
  const TriangleMesh sphere = Icosphere(2);
  const BasisResult closed = Solve(sphere, 10, BoundaryCondition::Dirichlet);
  const BasisResult free = Solve(sphere, 10, BoundaryCondition::Neumann);
  Check(std::any_of(closed.Warnings.begin(),
          closed.Warnings.end(),
          [](const std::string& w) { return w.find("Dirichlet is ignored") != std::string::npos; }),
    "a closed surface warns that Dirichlet is ignored");
  CheckBelow((closed.Pairs.Eigenvalues - free.Pairs.Eigenvalues).cwiseAbs().maxCoeff(),
    1e-9,
    "and gets the Neumann spectrum");
  Check(closed.ConstantHarmonics, "with its constant harmonic");
  CheckThrows<InvalidInput>([&]()
    { Solve(TetrahedralBox(1.0, 1.0, 1.0, 1, 1, 1), 2, BoundaryCondition::Dirichlet); },
    "a volume without interior points is refused under Dirichlet");
}

//------------------------------------------------------------------------------
// Low-pass filtering a noisy scalar field on the tetrahedral ball: the projection on the first
// harmonics is at least 5 times closer to the clean field than the noisy field is.
void FilterNoisyFieldOnBall()
{
  const TriangleMesh ball = TetrahedralBall(18);
  const BasisResult basis = Solve(ball, 40, BoundaryCondition::Neumann);
  const Eigen::Index n = static_cast<Eigen::Index>(basis.InputPointIds.size());
  RowMatrix clean(n, 1);
  RowMatrix noisy(n, 1);
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (Eigen::Index r = 0; r < n; ++r)
  {
    const Eigen::RowVector3d p =
      ball.Vertices.row(basis.InputPointIds[static_cast<std::size_t>(r)]);
    clean(r, 0) = p.x() + 0.5 * p.y() * p.z() + 0.3 * p.squaredNorm();
    noisy(r, 0) = clean(r, 0) + noise(random);
  }
  const RowMatrix H = basis.Pairs.Eigenvectors;
  const BasisView view(H.data(), H.rows(), H.cols());
  const RowMatrix coefficients =
    ForwardTransform(view, basis.LumpedMass, ConstRowView(noisy.data(), n, 1));
  const RowMatrix filtered = FilterSignal(view,
    basis.LumpedMass,
    Vector::Ones(H.cols()),
    ConstRowView(coefficients.data(), coefficients.rows(), 1),
    ConstRowView(noisy.data(), n, 1),
    0.0);
  const auto rms = [&basis](const RowMatrix& e)
  {
    return std::sqrt(
      e.col(0).dot(basis.LumpedMass.asDiagonal() * e.col(0)) / basis.LumpedMass.sum());
  };
  const double before = rms(noisy - clean);
  const double after = rms(filtered - clean);
  std::printf(
    " RMS error %.4f noisy, %.4f filtered (%.1f times smaller)\n", before, after, before / after);
  CheckBelow(after * 5.0, before, "low-pass RMS error at least 5 times smaller");
}

//------------------------------------------------------------------------------
// Zero modes by construction in volumes: two tetrahedral boxes apart with natural conditions,
// lumped and consistent mass: two eigenvalues exactly 0, the constants of the boxes, the other
// harmonics M-orthogonal to them (BasisChecks.h). With Dirichlet conditions there is no zero
// mode: every eigenvalue is positive.
void ZeroModesOfVolumes()
{
  const TriangleMesh a = TetrahedralBox(1.0, 0.8, 0.6, 5, 4, 3);
  const TriangleMesh b = TetrahedralBox(0.5, 0.5, 0.5, 3, 3, 3);
  TriangleMesh boxes;
  boxes.Vertices.resize(a.Vertices.rows() + b.Vertices.rows(), 3);
  boxes.Vertices << a.Vertices, (b.Vertices.array() + 3.0).matrix();
  boxes.Tets.resize(a.Tets.rows() + b.Tets.rows(), 4);
  boxes.Tets << a.Tets, (b.Tets.array() + static_cast<int>(a.Vertices.rows())).matrix();
  for (const MassKind mass : { MassKind::Lumped, MassKind::Consistent })
  {
    BasisOptions options;
    options.NumberOfHarmonics = 20;
    options.Operators.Mass = mass;
    const BasisResult basis = ComputeBasis(boxes, options);
    CheckZeroModes(
      basis, 2, mass == MassKind::Lumped ? "two boxes, lumped: " : "two boxes, consistent: ");
  }
  const BasisResult dirichlet = Solve(boxes, 10, BoundaryCondition::Dirichlet);
  Check(dirichlet.Pairs.Eigenvalues[0] > 1.0,
    "two boxes, Dirichlet: no zero mode, lambda_0 > 1 (" +
      std::to_string(dirichlet.Pairs.Eigenvalues[0]) + ")");
}

//------------------------------------------------------------------------------
// Volume defects: zero-volume tetrahedra and duplicates are left out with a warning; a mesh
// mixing triangles and tetrahedra is refused; the intrinsic Delaunay Laplacian falls back to
// the cotangent one for tetrahedra, with a warning.
void VolumeDefects()
{
  const TriangleMesh box = TetrahedralBox(1.0, 1.0, 1.0, 3, 3, 3);
  TriangleMesh defective = box;
  const Eigen::Index t = box.Tets.rows();
  defective.Tets.conservativeResize(t + 3, 4);
  // Four coplanar points of the bottom face, a repeated point, and a duplicate (reoriented).
  defective.Tets.row(t) << 0, 1, 4, 5;
  defective.Tets.row(t + 1) << 0, 1, 1, 17;
  defective.Tets.row(t + 2) << box.Tets(5, 1), box.Tets(5, 0), box.Tets(5, 2), box.Tets(5, 3);
  const BasisResult clean = Solve(box, 8, BoundaryCondition::Neumann);
  const BasisResult repaired = Solve(defective, 8, BoundaryCondition::Neumann);
  const auto has = [&repaired](const std::string& text)
  {
    return std::any_of(repaired.Warnings.begin(),
      repaired.Warnings.end(),
      [&text](const std::string& w) { return w.find(text) != std::string::npos; });
  };
  Check(has("Left out 2 degenerate (zero-volume) tetrahedra"), "zero-volume tetrahedra named");
  Check(has("Left out 1 duplicated tetrahedra"), "the duplicate named");
  CheckBelow((repaired.Pairs.Eigenvalues - clean.Pairs.Eigenvalues).cwiseAbs().maxCoeff(),
    1e-9,
    "the repaired volume has the clean spectrum");

  TriangleMesh mixed = box;
  mixed.Faces.resize(1, 3);
  mixed.Faces << 0, 1, 5;
  CheckThrows<InvalidInput>([&]() { Solve(mixed, 4, BoundaryCondition::Neumann); },
    "a mesh with triangles and tetrahedra is refused");

  BasisOptions options;
  options.NumberOfHarmonics = 8;
  options.Operators.Laplacian = LaplacianKind::IntrinsicDelaunay;
  const BasisResult intrinsic = ComputeBasis(box, options);
  Check(
    std::any_of(intrinsic.Warnings.begin(),
      intrinsic.Warnings.end(),
      [](const std::string& w) { return w.find("for triangle surfaces") != std::string::npos; }),
    "the intrinsic Laplacian of a volume warns");
  CheckBelow((intrinsic.Pairs.Eigenvalues - clean.Pairs.Eigenvalues).cwiseAbs().maxCoeff(),
    1e-9,
    "and uses the cotangent one");

  // Two cubes apart, scaled: components and unit scaling work for volumes too.
  TriangleMesh two = box;
  const Eigen::Index n = box.Vertices.rows();
  two.Vertices.conservativeResize(2 * n, 3);
  two.Vertices.bottomRows(n) = box.Vertices;
  two.Vertices.bottomRows(n).col(0).array() += 3.0;
  two.Tets.conservativeResize(2 * t, 4);
  two.Tets.bottomRows(t) = box.Tets.array() + static_cast<int>(n);
  two.Vertices *= 1000.0;
  const BasisResult pair = Solve(two, 4, BoundaryCondition::Neumann);
  Check(pair.Components == 2, "two components");
  CheckNear(pair.LumpedMass.sum(), 2e9, 1e-6, "the lumped mass is the volume in the mesh's units");
  const Eigen::MatrixXd gram =
    pair.Pairs.Eigenvectors.transpose() * pair.LumpedMass.asDiagonal() * pair.Pairs.Eigenvectors;
  CheckBelow((gram - Eigen::MatrixXd::Identity(4, 4)).cwiseAbs().maxCoeff(),
    1e-9,
    "the harmonics are M-orthonormal in the mesh's units");
  CheckBelow(std::abs(pair.Pairs.Eigenvalues[1]), 1e-12, "two zero eigenvalues");
  CheckNear(pair.Pairs.Eigenvalues[2] * 1e6,
    clean.Pairs.Eigenvalues[1],
    1e-8 * clean.Pairs.Eigenvalues[1],
    "each cube's first eigenvalue, scaled by 1 / s^2");
}

const Case Cases[] = {
  { "ZeroModesOfVolumes", ZeroModesOfVolumes },
  { "StiffnessFromDihedralAngles", StiffnessFromDihedralAngles },
  { "TetrahedralOperators", TetrahedralOperators },
  { "UnitCube", UnitCube },
  { "CubeConvergesAtSecondOrder", CubeConvergesAtSecondOrder },
  { "UnitBall", UnitBall },
  { "DirichletSquareAndDisc", DirichletSquareAndDisc },
  { "DirichletWithoutInterior", DirichletWithoutInterior },
  { "FilterNoisyFieldOnBall", FilterNoisyFieldOnBall },
  { "VolumeDefects", VolumeDefects },
};
} // namespace

int main(int argc, char* argv[])
{
  return RunCases(argc, argv, Cases);
}
