// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Functional maps (FunctionalMap.h): the checks of the two shapes, the descriptors and the
// initial map, the ZoomOut refinement, the nearest rows by blocks, transfer and mode alignment.
#include "Filtering/FunctionalMap.h"

#include "Common/Eigenvalues.h"
#include "Common/Threads.h"
#include "Filtering/Descriptors.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

namespace spectral
{
namespace
{
/// The landmark heat kernels: their number of times, and the harmonic (counted from the first
/// non-constant one) whose 1 / lambda is the shortest time (see LandmarkKernelTimes).
constexpr int NumberOfLandmarkKernelTimes = 16;
constexpr Eigen::Index LandmarkKernelHarmonics = 10;
/// The orientation term uses every this many-th descriptor (5 of the default 50).
constexpr Eigen::Index OrientationDescriptorStep = 10;
/// The largest InitialSize with the orientation term, which solves for the k^2 entries of C
/// at once (O(k^6): about a second at k = 40 on one core).
constexpr int MaximumOrientedSize = 60;

/// Query rows and database rows per block of the nearest-row search: a block of distances is
/// QueryBlock x DatabaseBlock doubles (2 MB) per thread.
constexpr Eigen::Index QueryBlock = 256;
constexpr Eigen::Index DatabaseBlock = 1024;

double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Sizes and values of one shape: n rows everywhere, m >= 2 ascending finite eigenvalues,
/// finite harmonics, non-negative finite masses, some mass.
void CheckShape(const SpectralShape& shape, const char* name)
{
  const std::string who(name);
  const Eigen::Index n = shape.Harmonics.rows();
  const Eigen::Index m = shape.Harmonics.cols();
  if (m < 2)
  {
    throw InvalidInput("the " + who + " has " + std::to_string(m) +
      " harmonics; a functional map needs at least 2 (compute a basis with more)");
  }
  if (shape.Eigenvalues.size() != m)
  {
    throw InvalidInput("the " + who + " has " + std::to_string(shape.Eigenvalues.size()) +
      " eigenvalues for " + std::to_string(m) + " harmonics");
  }
  if (shape.Mass.size() != n)
  {
    throw InvalidInput("the " + who + " has " + std::to_string(shape.Mass.size()) +
      " masses for " + std::to_string(n) + " points of its harmonics");
  }
  if (shape.Vertices.rows() != 0 && shape.Vertices.rows() != n)
  {
    throw InvalidInput("the " + who + " has " + std::to_string(shape.Vertices.rows()) +
      " points for " + std::to_string(n) + " rows of its harmonics");
  }
  if (!shape.Eigenvalues.allFinite() || !shape.Harmonics.allFinite() || !shape.Mass.allFinite())
  {
    throw InvalidInput("the " + who + " has non-finite eigenvalues, harmonics or masses");
  }
  for (Eigen::Index k = 1; k < m; ++k)
  {
    if (shape.Eigenvalues[k] < shape.Eigenvalues[k - 1])
    {
      throw InvalidInput("the eigenvalues of the " + who + " are not ascending");
    }
  }
  if ((shape.Mass.array() < 0.0).any() || !(shape.Mass.sum() > 0.0))
  {
    throw InvalidInput("the " + who + " has a negative mass or no point of positive mass");
  }
}

/// The eigenvalues of a shape with the rule of Common/Eigenvalues.h for the zero ones.
Spectrum SpectrumOf(const SpectralShape& shape)
{
  Spectrum spectrum;
  spectrum.Lambda = shape.Eigenvalues;
  const double top = shape.Eigenvalues.maxCoeff();
  spectrum.NonZero.resize(static_cast<std::size_t>(shape.Eigenvalues.size()));
  for (Eigen::Index k = 0; k < shape.Eigenvalues.size(); ++k)
  {
    spectrum.NonZero[static_cast<std::size_t>(k)] = !IsZeroEigenvalue(shape.Eigenvalues[k], top);
  }
  return spectrum;
}

/// The index of the first non-zero eigenvalue of a spectrum (m if there is none).
Eigen::Index FirstNonZero(const Spectrum& spectrum)
{
  Eigen::Index k = 0;
  while (k < spectrum.Lambda.size() && !spectrum.NonZero[static_cast<std::size_t>(k)])
  {
    ++k;
  }
  return k;
}

/// The energies both shapes use: from the first non-zero eigenvalue to the last of the
/// `common` first ones, the larger first and the smaller last of the two shapes.
WaveKernelEnergies CommonEnergies(
  const Spectrum& source, const Spectrum& target, Eigen::Index common, int count)
{
  const Eigen::Index first = std::max(FirstNonZero(source), FirstNonZero(target));
  if (first >= common - 1)
  {
    throw InvalidInput("a functional map needs at least two non-constant harmonics among the "
                       "first " + std::to_string(common) + " of both shapes");
  }
  Spectrum both;
  both.Lambda.resize(2);
  both.Lambda << std::max(source.Lambda[first], target.Lambda[first]),
    std::min(source.Lambda[common - 1], target.Lambda[common - 1]);
  both.NonZero.assign(2, true);
  return DefaultWaveKernelEnergies(both, count);
}

/// Divide each column by its D-norm (columns of norm 0 stay 0).
void NormalizeColumns(RowMatrix& F, const Vector& mass)
{
  for (Eigen::Index c = 0; c < F.cols(); ++c)
  {
    const double norm = std::sqrt((F.col(c).array().square() * mass.array()).sum());
    if (norm > 0.0)
    {
      F.col(c) /= norm;
    }
  }
}

/// Phi_k^T D F: the coefficients of the columns of F on the first k harmonics.
DenseMatrix Project(const SpectralShape& shape, const RowMatrix& F, Eigen::Index k)
{
  const RowMatrix weighted = shape.Mass.asDiagonal() * F;
  return shape.Harmonics.leftCols(k).transpose() * weighted;
}

/// The times of the landmark heat kernels: NumberOfLandmarkKernelTimes, log-spaced over
/// [1 / lambda_K, 1 / lambda_1] with lambda_1 the first non-zero eigenvalue and lambda_K the
/// LandmarkKernelHarmonics-th after it (at most the k-th), the larger lambda_1 and the smaller
/// lambda_K of the two shapes.
Vector LandmarkKernelTimes(const Spectrum& source, const Spectrum& target, Eigen::Index k)
{
  const Eigen::Index first = std::max(FirstNonZero(source), FirstNonZero(target));
  if (first >= k)
  {
    throw InvalidInput("landmarks need a non-constant harmonic among the first " +
      std::to_string(k) + " of both shapes (raise InitialSize)");
  }
  const Eigen::Index last = std::min<Eigen::Index>(first + LandmarkKernelHarmonics - 1, k - 1);
  const double longest = 1.0 / std::max(source.Lambda[first], target.Lambda[first]);
  const double shortest =
    std::min(longest, 1.0 / std::min(source.Lambda[last], target.Lambda[last]));
  Vector times(NumberOfLandmarkKernelTimes);
  for (int j = 0; j < NumberOfLandmarkKernelTimes; ++j)
  {
    times[j] = shortest *
      std::pow(longest / shortest, j / static_cast<double>(NumberOfLandmarkKernelTimes - 1));
  }
  return times;
}

/// e^{-lambda_k t_j} (m by T), with the zero eigenvalues counted as exactly 0.
DenseMatrix HeatWeights(const Vector& lambda, const Spectrum& spectrum, const Vector& times)
{
  DenseMatrix W(lambda.size(), times.size());
  for (Eigen::Index k = 0; k < lambda.size(); ++k)
  {
    const double l = spectrum.NonZero[static_cast<std::size_t>(k)] ? lambda[k] : 0.0;
    W.row(k) = (-l * times.transpose().array()).exp().matrix();
  }
  return W;
}

/// The coefficients (on the first k harmonics) of the kernels sum_k W_kj h_k(p) h_k(x) between
/// each landmark point p and every point x, one column per landmark and column of W, each
/// of unit norm over all the harmonics.
DenseMatrix LandmarkCoefficients(const SpectralShape& shape, const DenseMatrix& W,
  const std::vector<int>& points, Eigen::Index k)
{
  const Eigen::Index E = W.cols();
  DenseMatrix result(k, static_cast<Eigen::Index>(points.size()) * E);
  for (std::size_t l = 0; l < points.size(); ++l)
  {
    const Eigen::Index p = points[l];
    for (Eigen::Index e = 0; e < E; ++e)
    {
      Vector column = W.col(e).cwiseProduct(shape.Harmonics.row(p).transpose());
      const double norm = column.norm();
      result.col(static_cast<Eigen::Index>(l) * E + e) =
        norm > 0.0 ? Vector(column.head(k) / norm) : Vector(column.head(k));
    }
  }
  return result;
}

/// The weights w_ij = weight (lambda2_i - lambda1_j)^2 / s of the commutativity term, s the sum
/// of the (lambda2_i - lambda1_j)^2 (k by k).
DenseMatrix CommutativityPenalty(const Vector& lambda1, const Vector& lambda2, double weight)
{
  const Eigen::Index k = lambda1.size();
  DenseMatrix penalty(k, k);
  for (Eigen::Index i = 0; i < k; ++i)
  {
    for (Eigen::Index j = 0; j < k; ++j)
    {
      const double d = lambda2[i] - lambda1[j];
      penalty(i, j) = d * d;
    }
  }
  const double scale = penalty.sum();
  if (scale > 0.0)
  {
    penalty *= weight / scale;
  }
  return penalty;
}

/// The C minimizing ||C A - B||^2 + sum_ij w_ij C_ij^2 (w = penalty), row by row:
/// (A A^T + diag(w_i.)) c_i = A b_i.
DenseMatrix SolveRows(const DenseMatrix& A, const DenseMatrix& B, const DenseMatrix& penalty)
{
  const Eigen::Index k = A.rows();
  const DenseMatrix gram = A * A.transpose();
  const DenseMatrix right = B * A.transpose(); // row i is (A b_i)^T
  DenseMatrix C(k, k);
  for (Eigen::Index i = 0; i < k; ++i)
  {
    DenseMatrix system = gram;
    system.diagonal() += penalty.row(i).transpose();
    C.row(i) = system.ldlt().solve(right.row(i).transpose()).transpose();
  }
  return C;
}

/// N += s (P kron R): entry (i + k j, i' + k j') += s P(j, j') R(i, i'), the normal matrix of
/// vec(C) stacked by columns.
void AddKronecker(DenseMatrix& N, const DenseMatrix& P, const DenseMatrix& R, double s)
{
  const Eigen::Index k = R.rows();
  for (Eigen::Index j = 0; j < k; ++j)
  {
    for (Eigen::Index jj = 0; jj < k; ++jj)
    {
      N.block(k * j, k * jj, k, k) += (s * P(j, jj)) * R;
    }
  }
}

/**
 * The C minimizing ||C A - B||^2 + sum_ij w_ij C_ij^2 + sum_g weight_g ||C X_g - Y_g C||^2 over
 * all k^2 entries at once (the last terms couple the rows): the normal equations of vec(C),
 * (A A^T kron I + diag(vec w) + sum_g weight_g (X X^T kron I - X kron Y - X^T kron Y^T +
 * I kron Y^T Y)) vec C = vec(B A^T). O(k^6) to solve.
 */
DenseMatrix SolveWhole(const DenseMatrix& A, const DenseMatrix& B, const DenseMatrix& penalty,
  const std::vector<std::pair<DenseMatrix, DenseMatrix>>& operators, double weight)
{
  const Eigen::Index k = A.rows();
  const DenseMatrix I = DenseMatrix::Identity(k, k);
  DenseMatrix N = DenseMatrix::Zero(k * k, k * k);
  AddKronecker(N, A * A.transpose(), I, 1.0);
  for (const auto& XY : operators)
  {
    const DenseMatrix& X = XY.first;
    const DenseMatrix& Y = XY.second;
    AddKronecker(N, X * X.transpose(), I, weight);
    AddKronecker(N, X, Y, -weight);
    AddKronecker(N, X.transpose(), Y.transpose(), -weight);
    AddKronecker(N, I, Y.transpose() * Y, weight);
  }
  N.diagonal() += Eigen::Map<const Vector>(penalty.data(), k * k);
  const DenseMatrix right = B * A.transpose();
  const Vector c = N.ldlt().solve(Eigen::Map<const Vector>(right.data(), k * k));
  return Eigen::Map<const DenseMatrix>(c.data(), k, k);
}

/**
 * The orientation operator of a descriptor g in the first k harmonics (Ren et al. 2018):
 * Q = Phi^T D O_g Phi with (O_g f) = <grad f x grad g, n>, constant per triangle for the linear
 * f and g of the mesh and given to its corners with a third of its area each:
 * Q_ij = sum_t (A_t / 3) (sum_{v in t} phi_i(v)) <grad phi_j x grad g, n>_t. The normal n is
 * that of the triangle's order of points, so the operator changes sign with the orientation.
 */
DenseMatrix OrientationOperator(const SpectralShape& shape, const Vector& g, Eigen::Index k)
{
  const Triangles& faces = shape.Faces;
  const Eigen::Index F = faces.rows();
  RowMatrix sums(F, k);
  RowMatrix values(F, k);
  for (Eigen::Index t = 0; t < F; ++t)
  {
    const int v[3] = { faces(t, 0), faces(t, 1), faces(t, 2) };
    const Eigen::Vector3d p[3] = { shape.Vertices.row(v[0]).transpose(),
      shape.Vertices.row(v[1]).transpose(), shape.Vertices.row(v[2]).transpose() };
    const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
    const double twiceArea = normal.norm();
    if (!(twiceArea > 0.0))
    {
      sums.row(t).setZero();
      values.row(t).setZero();
      continue;
    }
    const Eigen::Vector3d n = normal / twiceArea;
    // grad B_c = n x (opposite edge) / 2A for the hat function B_c of corner c.
    Eigen::Vector3d gradient[3];
    for (int c = 0; c < 3; ++c)
    {
      gradient[c] = n.cross(p[(c + 2) % 3] - p[(c + 1) % 3]) / twiceArea;
    }
    const Eigen::Vector3d gradG = g[v[0]] * gradient[0] + g[v[1]] * gradient[1] + g[v[2]] * gradient[2];
    const Eigen::Vector3d w = gradG.cross(n); // <grad f x grad g, n> = grad f . (grad g x n)
    const double area = twiceArea / 6.0; // a third of the triangle's area
    sums.row(t) = area * (shape.Harmonics.row(v[0]).head(k) + shape.Harmonics.row(v[1]).head(k) +
      shape.Harmonics.row(v[2]).head(k));
    values.row(t) = gradient[0].dot(w) * shape.Harmonics.row(v[0]).head(k) +
      gradient[1].dot(w) * shape.Harmonics.row(v[1]).head(k) +
      gradient[2].dot(w) * shape.Harmonics.row(v[2]).head(k);
  }
  return sums.transpose() * values;
}

/// The resolved sizes (0 for automatic), checked against both bases.
std::pair<int, int> ResolveSizes(const FunctionalMapOptions& options, Eigen::Index m1,
  Eigen::Index m2)
{
  const int common = static_cast<int>(std::min(m1, m2));
  int final = options.FinalSize;
  if (final == 0)
  {
    final = std::min(DefaultFunctionalMapFinalSize, common);
  }
  if (final < 1 || final > common)
  {
    throw InvalidInput("the final size of the functional map (" +
      std::to_string(options.FinalSize) + ") must be between 1 and the harmonics of both bases (" +
      std::to_string(m1) + " on the source, " + std::to_string(m2) +
      " on the target): lower FinalSize or compute more harmonics");
  }
  int initial = options.InitialSize;
  if (initial == 0)
  {
    initial = std::min(DefaultFunctionalMapInitialSize, final);
  }
  if (initial < 1 || initial > final)
  {
    throw InvalidInput("the initial size of the functional map (" +
      std::to_string(options.InitialSize) + ") must be between 1 and its final size (" +
      std::to_string(final) + ")");
  }
  return { initial, final };
}

void CheckOptions(const FunctionalMapOptions& options, const SpectralShape& source,
  const SpectralShape& target)
{
  if (options.OrientationTerm)
  {
    for (const SpectralShape* shape : { &source, &target })
    {
      if (shape->Faces.rows() == 0 || shape->Vertices.rows() != shape->Harmonics.rows())
      {
        throw InvalidInput("the orientation term needs the points and the triangles of both "
                           "shapes");
      }
      if (shape->Faces.minCoeff() < 0 || shape->Faces.maxCoeff() >= shape->Harmonics.rows())
      {
        throw InvalidInput("a triangle of a shape has a point index out of range");
      }
    }
  }
  if (options.ZoomOutStep < 1 || options.NumberOfDescriptors < 1 || options.ZoomOutSamples < 0)
  {
    throw InvalidInput("the ZoomOut step and the number of descriptors must be at least 1, the "
                       "ZoomOut samples at least 0");
  }
  const auto bad = [](double w) { return !(w >= 0.0) || !std::isfinite(w); };
  if (bad(options.DescriptorWeight) || !(options.DescriptorWeight > 0.0) ||
    bad(options.CommutativityWeight) || bad(options.LandmarkWeight) ||
    bad(options.OrientationWeight))
  {
    throw InvalidInput("the weights of a functional map must be finite and non-negative, the "
                       "descriptor weight positive");
  }
  for (const auto& pair : options.Landmarks)
  {
    if (pair.first < 0 || pair.first >= source.Harmonics.rows() || pair.second < 0 ||
      pair.second >= target.Harmonics.rows())
    {
      throw InvalidInput("the landmark (" + std::to_string(pair.first) + ", " +
        std::to_string(pair.second) + ") is out of range: the source has " +
        std::to_string(source.Harmonics.rows()) + " points, the target " +
        std::to_string(target.Harmonics.rows()));
    }
    if (!OnSurface(source, pair.first) || !OnSurface(target, pair.second))
    {
      throw InvalidInput("the landmark (" + std::to_string(pair.first) + ", " +
        std::to_string(pair.second) + ") is on a point outside the surface (zero mass and "
        "harmonics)");
    }
  }
}

/// The point map of C with the landmarks imposed.
std::vector<int> PointMapWithLandmarks(const SpectralShape& source, const SpectralShape& target,
  const DenseMatrix& C, const FunctionalMapOptions& options)
{
  std::vector<int> ids = PointMapFromFunctionalMap(source, target, C, options.Threads);
  for (const auto& pair : options.Landmarks)
  {
    ids[static_cast<std::size_t>(pair.second)] = pair.first;
  }
  return ids;
}

/**
 * The map of a point map on sample points: C minimizing sum_j W_j ||Phi2_k(j) C - Phi1_k(ids_j)||^2,
 * i.e. (P2^T W P2) C = P2^T W Pi P1, with W the target's masses. On all the points of a shape,
 * P2^T D2 P2 = I and this is Phi2^T D2 Pi Phi1 (FunctionalMapFromPointMap); on samples the
 * Gram matrix is solved for.
 */
DenseMatrix MapOfSamples(const SpectralShape& source, const SpectralShape& target,
  const std::vector<int>& ids, Eigen::Index k)
{
  const Eigen::Index n2 = target.Harmonics.rows();
  RowMatrix weighted(n2, k);
  RowMatrix matched = RowMatrix::Zero(n2, k);
  for (Eigen::Index j = 0; j < n2; ++j)
  {
    const int i = ids[static_cast<std::size_t>(j)];
    const double w = i >= 0 ? target.Mass[j] : 0.0;
    weighted.row(j) = w * target.Harmonics.row(j).head(k);
    if (i >= 0)
    {
      matched.row(j) = source.Harmonics.row(i).head(k);
    }
  }
  const DenseMatrix gram = weighted.transpose() * target.Harmonics.leftCols(k);
  return gram.ldlt().solve(DenseMatrix(weighted.transpose() * matched));
}

/**
 * `count` points of positive mass spread over the shape by farthest-point sampling (in 3D when
 * the shape has its points, else in the embedding of its first three non-constant harmonics),
 * starting from the given points (the landmarks) or from the first point of positive mass;
 * ties go to the smallest index. O(n count).
 */
std::vector<int> FarthestPoints(const SpectralShape& shape, const Spectrum& spectrum,
  Eigen::Index count, const std::vector<int>& start)
{
  const Eigen::Index n = shape.Harmonics.rows();
  Points where(n, 3);
  if (shape.Vertices.rows() == n)
  {
    where = shape.Vertices;
  }
  else
  {
    where.setZero();
    Eigen::Index c = 0;
    for (Eigen::Index k = FirstNonZero(spectrum); k < shape.Harmonics.cols() && c < 3; ++k, ++c)
    {
      where.col(c) = shape.Harmonics.col(k) / std::sqrt(spectrum.Lambda[k]);
    }
  }
  Vector distance = Vector::Constant(n, std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < n; ++i)
  {
    if (!(shape.Mass[i] > 0.0))
    {
      distance[i] = -1.0; // never chosen
    }
  }
  std::vector<int> chosen;
  const auto take = [&](Eigen::Index p)
  {
    chosen.push_back(static_cast<int>(p));
    distance = distance.cwiseMin((where.rowwise() - where.row(p)).rowwise().squaredNorm());
    distance[p] = -1.0;
  };
  for (int p : start)
  {
    if (distance[p] >= 0.0)
    {
      take(p);
    }
  }
  if (chosen.empty())
  {
    Eigen::Index first = 0;
    while (!(shape.Mass[first] > 0.0))
    {
      ++first;
    }
    take(first);
  }
  while (static_cast<Eigen::Index>(chosen.size()) < count)
  {
    Eigen::Index farthest = 0;
    if (distance.maxCoeff(&farthest) < 0.0)
    {
      break; // every point of positive mass is taken
    }
    take(farthest);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

/// The rows `points` of a shape at unit area: its basis and eigenvalues, and the same weight for
/// each point (farthest-point samples cover about equal areas, whatever the masses of the points),
/// summing to 1 (so that AtUnitArea leaves the samples as they are).
SpectralShape Restricted(const SpectralShape& shape, const std::vector<int>& points)
{
  SpectralShape part;
  part.Harmonics.resize(static_cast<Eigen::Index>(points.size()), shape.Harmonics.cols());
  part.Mass.resize(static_cast<Eigen::Index>(points.size()));
  for (std::size_t r = 0; r < points.size(); ++r)
  {
    part.Harmonics.row(static_cast<Eigen::Index>(r)) = shape.Harmonics.row(points[r]);
    part.Mass[static_cast<Eigen::Index>(r)] = 1.0 / static_cast<double>(points.size());
  }
  part.Eigenvalues = shape.Eigenvalues;
  return part;
}

/// `shape` at unit area (UnitArea), or `shape` itself when its area is 1 to rounding (the shapes
/// inside ComputeFunctionalMap, already scaled): `storage` holds the scaled copy.
const SpectralShape& AtUnitArea(const SpectralShape& shape, SpectralShape& storage)
{
  const double area = shape.Mass.sum();
  if (std::abs(area - 1.0) <= 1e-12 || !(area > 0.0) || !std::isfinite(area))
  {
    return shape; // CheckShape refuses a shape without positive finite area.
  }
  storage = UnitArea(shape);
  return storage;
}

std::vector<bool> PositiveMass(const Vector& mass)
{
  std::vector<bool> positive(static_cast<std::size_t>(mass.size()));
  for (Eigen::Index i = 0; i < mass.size(); ++i)
  {
    positive[static_cast<std::size_t>(i)] = mass[i] > 0.0;
  }
  return positive;
}
} // namespace

//------------------------------------------------------------------------------
std::vector<int> NearestRows(const RowMatrix& queries, const RowMatrix& database,
  const std::vector<bool>& allowed, int threads)
{
  if (queries.cols() != database.cols())
  {
    throw InvalidInput("nearest rows: the queries have " + std::to_string(queries.cols()) +
      " columns, the database " + std::to_string(database.cols()));
  }
  if (!allowed.empty() && static_cast<Eigen::Index>(allowed.size()) != database.rows())
  {
    throw InvalidInput("nearest rows: the mask has " + std::to_string(allowed.size()) +
      " entries for " + std::to_string(database.rows()) + " database rows");
  }
  const Eigen::Index nq = queries.rows();
  const Eigen::Index nd = database.rows();
  std::vector<int> nearest(static_cast<std::size_t>(nq), -1);
  if (nq == 0 || nd == 0)
  {
    return nearest;
  }
  const Vector norms = database.rowwise().squaredNorm();
  // Blocks at fixed positions, so that each distance is the same whatever the thread count.
  const Eigen::Index blocks = (nq + QueryBlock - 1) / QueryBlock;
  const int parts = static_cast<int>(std::min<Eigen::Index>(
    blocks, ThreadsForWork(nq * nd * std::max<Eigen::Index>(1, queries.cols()), 1 << 22, threads)));
  ForEachRowRange(blocks, parts,
    [&](int, Eigen::Index firstBlock, Eigen::Index count)
    {
      DenseMatrix products;
      for (Eigen::Index b = firstBlock; b < firstBlock + count; ++b)
      {
        const Eigen::Index q0 = b * QueryBlock;
        const Eigen::Index qn = std::min(QueryBlock, nq - q0);
        std::vector<double> best(static_cast<std::size_t>(qn),
          std::numeric_limits<double>::infinity());
        for (Eigen::Index d0 = 0; d0 < nd; d0 += DatabaseBlock)
        {
          const Eigen::Index dn = std::min(DatabaseBlock, nd - d0);
          products.noalias() =
            queries.middleRows(q0, qn) * database.middleRows(d0, dn).transpose();
          for (Eigen::Index r = 0; r < qn; ++r)
          {
            double& bestOfRow = best[static_cast<std::size_t>(r)];
            int& nearestOfRow = nearest[static_cast<std::size_t>(q0 + r)];
            for (Eigen::Index c = 0; c < dn; ++c)
            {
              const Eigen::Index i = d0 + c;
              if (!allowed.empty() && !allowed[static_cast<std::size_t>(i)])
              {
                continue;
              }
              const double distance = norms[i] - 2.0 * products(r, c);
              if (distance < bestOfRow)
              {
                bestOfRow = distance;
                nearestOfRow = static_cast<int>(i);
              }
            }
          }
        }
      }
    });
  return nearest;
}

//------------------------------------------------------------------------------
std::vector<int> PointMapFromFunctionalMap(
  const SpectralShape& givenSource, const SpectralShape& givenTarget, const DenseMatrix& map, int threads)
{
  SpectralShape scaledSource, scaledTarget;
  const SpectralShape& source = AtUnitArea(givenSource, scaledSource);
  const SpectralShape& target = AtUnitArea(givenTarget, scaledTarget);
  const Eigen::Index k2 = map.rows();
  const Eigen::Index k1 = map.cols();
  if (k1 < 1 || k2 < 1 || k1 > source.Harmonics.cols() || k2 > target.Harmonics.cols())
  {
    throw InvalidInput("a functional map of " + std::to_string(k2) + " by " +
      std::to_string(k1) + " does not fit bases of " + std::to_string(target.Harmonics.cols()) +
      " (target) and " + std::to_string(source.Harmonics.cols()) + " (source) harmonics");
  }
  if (source.Mass.size() != source.Harmonics.rows() ||
    target.Mass.size() != target.Harmonics.rows())
  {
    throw InvalidInput("a shape has a mass vector of the wrong size");
  }
  const std::vector<bool> allowed = PositiveMass(source.Mass);
  if (std::find(allowed.begin(), allowed.end(), true) == allowed.end())
  {
    throw InvalidInput("the source has no point of positive mass");
  }
  // Only the target points on the surface are queried.
  std::vector<int> rows;
  for (Eigen::Index j = 0; j < target.Mass.size(); ++j)
  {
    if (OnSurface(target, j))
    {
      rows.push_back(static_cast<int>(j));
    }
  }
  RowMatrix queries(static_cast<Eigen::Index>(rows.size()), k1);
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    queries.row(static_cast<Eigen::Index>(r)).noalias() =
      target.Harmonics.row(rows[r]).head(k2) * map;
  }
  const RowMatrix database = source.Harmonics.leftCols(k1);
  const std::vector<int> nearest = NearestRows(queries, database, allowed, threads);
  std::vector<int> ids(static_cast<std::size_t>(target.Mass.size()), -1);
  for (std::size_t r = 0; r < rows.size(); ++r)
  {
    ids[static_cast<std::size_t>(rows[r])] = nearest[r];
  }
  return ids;
}

//------------------------------------------------------------------------------
SpectralShape UnitArea(const SpectralShape& shape)
{
  const double area = shape.Mass.sum();
  SpectralShape scaled;
  scaled.Harmonics = shape.Harmonics * std::sqrt(area);
  scaled.Eigenvalues = shape.Eigenvalues * area;
  scaled.Mass = shape.Mass / area;
  scaled.Vertices = shape.Vertices / std::sqrt(area);
  scaled.Faces = shape.Faces;
  return scaled;
}

//------------------------------------------------------------------------------
bool OnSurface(const SpectralShape& shape, Eigen::Index i)
{
  return shape.Mass[i] > 0.0 || !shape.Harmonics.row(i).isZero(0.0);
}

//------------------------------------------------------------------------------
DenseMatrix FunctionalMapFromPointMap(const SpectralShape& givenSource,
  const SpectralShape& givenTarget, const std::vector<int>& correspondingPointIds, int k)
{
  SpectralShape scaledSource, scaledTarget;
  const SpectralShape& source = AtUnitArea(givenSource, scaledSource);
  const SpectralShape& target = AtUnitArea(givenTarget, scaledTarget);
  if (k < 1 || k > source.Harmonics.cols() || k > target.Harmonics.cols())
  {
    throw InvalidInput("a functional map of size " + std::to_string(k) +
      " needs that many harmonics on both shapes (" + std::to_string(source.Harmonics.cols()) +
      " on the source, " + std::to_string(target.Harmonics.cols()) + " on the target)");
  }
  const Eigen::Index n2 = target.Harmonics.rows();
  if (static_cast<Eigen::Index>(correspondingPointIds.size()) != n2 || target.Mass.size() != n2)
  {
    throw InvalidInput("the point map has " + std::to_string(correspondingPointIds.size()) +
      " entries for " + std::to_string(n2) + " target points");
  }
  // G = D2 Pi Phi1_k, then C = Phi2_k^T G.
  RowMatrix G = RowMatrix::Zero(n2, k);
  for (Eigen::Index j = 0; j < n2; ++j)
  {
    const int i = correspondingPointIds[static_cast<std::size_t>(j)];
    if (i < -1 || i >= source.Harmonics.rows())
    {
      throw InvalidInput("the point map holds the source point " + std::to_string(i) +
        ", out of range (the source has " + std::to_string(source.Harmonics.rows()) + ")");
    }
    if (i >= 0)
    {
      G.row(j) = target.Mass[j] * source.Harmonics.row(i).head(k);
    }
  }
  return target.Harmonics.leftCols(k).transpose() * G;
}

//------------------------------------------------------------------------------
FunctionalMapResult ComputeFunctionalMap(const SpectralShape& givenSource,
  const SpectralShape& givenTarget, const FunctionalMapOptions& options, const Monitor& monitor)
{
  const auto start = std::chrono::steady_clock::now();
  CheckShape(givenSource, "source");
  CheckShape(givenTarget, "target");
  // Two scans of one object differ in size (units, or the area noise adds): the map is that of
  // the shapes at unit area, whose spectra and harmonics compare.
  SpectralShape scaledSource, scaledTarget;
  const SpectralShape& source = AtUnitArea(givenSource, scaledSource);
  const SpectralShape& target = AtUnitArea(givenTarget, scaledTarget);
  CheckOptions(options, source, target);
  FunctionalMapResult result;
  std::tie(result.InitialSize, result.FinalSize) =
    ResolveSizes(options, source.Harmonics.cols(), target.Harmonics.cols());
  const Eigen::Index k0 = result.InitialSize;
  if (options.OrientationTerm && result.InitialSize > MaximumOrientedSize)
  {
    throw InvalidInput("with the orientation term the initial size of the map (" +
      std::to_string(result.InitialSize) + ") must be at most " +
      std::to_string(MaximumOrientedSize) + ": it solves for the k^2 entries at once");
  }
  if (options.ZoomOutSamples > 0 && options.ZoomOutSamples < 2 * result.FinalSize)
  {
    throw InvalidInput("ZoomOutSamples (" + std::to_string(options.ZoomOutSamples) +
      ") must be 0 (every point) or at least twice the final size of the map (" +
      std::to_string(2 * result.FinalSize) + ")");
  }
  const Eigen::Index common = std::min(source.Harmonics.cols(), target.Harmonics.cols());
  std::vector<int> landmarks1;
  std::vector<int> landmarks2;
  for (const auto& pair : options.Landmarks)
  {
    landmarks1.push_back(pair.first);
    landmarks2.push_back(pair.second);
  }

  // Descriptors and the initial map.
  monitor.Begin("Descriptors");
  monitor.ThrowIfCancelled();
  const Spectrum spectrum1 = SpectrumOf(source);
  const Spectrum spectrum2 = SpectrumOf(target);
  const WaveKernelEnergies energies =
    CommonEnergies(spectrum1, spectrum2, common, options.NumberOfDescriptors);
  RowMatrix F1 = WaveKernelSignature(
    BasisView(source.Harmonics.data(), source.Harmonics.rows(), source.Harmonics.cols()),
    spectrum1, energies);
  RowMatrix F2 = WaveKernelSignature(
    BasisView(target.Harmonics.data(), target.Harmonics.rows(), target.Harmonics.cols()),
    spectrum2, energies);
  NormalizeColumns(F1, source.Mass);
  NormalizeColumns(F2, target.Mass);
  const DenseMatrix A = Project(source, F1, k0);
  const DenseMatrix B = Project(target, F2, k0);
  monitor.Report(0.1);
  monitor.ThrowIfCancelled();

  // Weighted descriptors, each family divided by its number of columns.
  const Eigen::Index q = A.cols();
  const Eigen::Index L = static_cast<Eigen::Index>(options.Landmarks.size());
  const Eigen::Index ql = options.LandmarkWeight > 0.0 ? L * NumberOfLandmarkKernelTimes : 0;
  DenseMatrix Aw(k0, q + ql);
  DenseMatrix Bw(k0, q + ql);
  const double descriptorScale = std::sqrt(options.DescriptorWeight / static_cast<double>(q));
  Aw.leftCols(q) = descriptorScale * A;
  Bw.leftCols(q) = descriptorScale * B;
  if (ql > 0)
  {
    const double landmarkScale =
      std::sqrt(options.DescriptorWeight * options.LandmarkWeight / static_cast<double>(ql));
    const Vector times = LandmarkKernelTimes(spectrum1, spectrum2, k0);
    const DenseMatrix W1 = HeatWeights(source.Eigenvalues, spectrum1, times);
    const DenseMatrix W2 = HeatWeights(target.Eigenvalues, spectrum2, times);
    Aw.rightCols(ql) = landmarkScale * LandmarkCoefficients(source, W1, landmarks1, k0);
    Bw.rightCols(ql) = landmarkScale * LandmarkCoefficients(target, W2, landmarks2, k0);
  }
  const DenseMatrix penalty = CommutativityPenalty(
    source.Eigenvalues.head(k0), target.Eigenvalues.head(k0), options.CommutativityWeight);
  if (options.OrientationTerm && options.OrientationWeight > 0.0)
  {
    // One operator pair per OrientationDescriptorStep-th descriptor of the lowest third of the
    // energies, each scaled by the norm of the source's operator; their weights share
    // OrientationWeight. The wave kernels of higher energies differ between two triangulations
    // of one shape (a bunny and its 50% decimation: operators twice as large on one as on the
    // other), and their operators pulled the map off the right one in either orientation (30%
    // of the diagonal); on the lowest third the term keeps the right map (0.83%, as without it)
    // and the mirror one when the target is turned over (24%).
    std::vector<std::pair<DenseMatrix, DenseMatrix>> operators;
    for (Eigen::Index c = OrientationDescriptorStep / 2; c < F1.cols() / 3;
         c += OrientationDescriptorStep)
    {
      DenseMatrix X = OrientationOperator(source, F1.col(c), k0);
      DenseMatrix Y = OrientationOperator(target, F2.col(c), k0);
      const double norm = X.norm();
      if (norm > 0.0)
      {
        operators.emplace_back(X / norm, Y / norm);
      }
    }
    result.InitialMap = SolveWhole(Aw, Bw, penalty, operators,
      options.DescriptorWeight * options.OrientationWeight /
        static_cast<double>(std::max<std::size_t>(1, operators.size())));
  }
  else
  {
    result.InitialMap = SolveRows(Aw, Bw, penalty);
  }
  const double normB = B.norm();
  result.DescriptorResidual = normB > 0.0 ? (result.InitialMap * A - B).norm() / normB : 0.0;
  result.EstimateSeconds = SecondsSince(start);
  monitor.Report(0.2);

  // ZoomOut, on samples of both shapes when they have more points than ZoomOutSamples.
  monitor.Begin("Refine");
  const auto refine = std::chrono::steady_clock::now();
  const Eigen::Index samples = options.ZoomOutSamples;
  const bool sampled = samples > 0 && result.FinalSize > result.InitialSize &&
    (source.Harmonics.rows() > samples || target.Harmonics.rows() > samples);
  SpectralShape part1;
  SpectralShape part2;
  FunctionalMapOptions partOptions = options;
  if (sampled)
  {
    const std::vector<int> points1 = FarthestPoints(source, spectrum1, samples, landmarks1);
    const std::vector<int> points2 = FarthestPoints(target, spectrum2, samples, landmarks2);
    part1 = Restricted(source, points1);
    part2 = Restricted(target, points2);
    // The landmarks are among the samples: their indices there.
    for (auto& pair : partOptions.Landmarks)
    {
      pair.first = static_cast<int>(
        std::lower_bound(points1.begin(), points1.end(), pair.first) - points1.begin());
      pair.second = static_cast<int>(
        std::lower_bound(points2.begin(), points2.end(), pair.second) - points2.begin());
    }
    result.Samples = { static_cast<int>(points1.size()), static_cast<int>(points2.size()) };
  }
  const SpectralShape& work1 = sampled ? part1 : source;
  const SpectralShape& work2 = sampled ? part2 : target;
  DenseMatrix C = result.InitialMap;
  monitor.ThrowIfCancelled();
  std::vector<int> ids = PointMapWithLandmarks(work1, work2, C, partOptions);
  result.Iterations = 1;
  const int steps = (result.FinalSize - result.InitialSize + options.ZoomOutStep - 1) /
    options.ZoomOutStep;
  for (int k = result.InitialSize; k < result.FinalSize;)
  {
    k = std::min(k + options.ZoomOutStep, result.FinalSize);
    C = sampled ? MapOfSamples(work1, work2, ids, k)
                : FunctionalMapFromPointMap(work1, work2, ids, k);
    monitor.ThrowIfCancelled();
    ids = PointMapWithLandmarks(work1, work2, C, partOptions);
    monitor.Report(0.2 + 0.7 * result.Iterations / static_cast<double>(steps + 1));
    ++result.Iterations;
  }
  if (sampled)
  {
    // The point map of the final C on every point.
    ids = PointMapWithLandmarks(source, target, C, options);
  }
  result.Map = C;
  result.CorrespondingPointIds = std::move(ids);
  result.RefinementSeconds = SecondsSince(refine);
  monitor.Report(1.0);
  return result;
}

//------------------------------------------------------------------------------
RowMatrix TransferThroughMap(const SpectralShape& givenSource, const SpectralShape& givenTarget,
  const DenseMatrix& map, const ConstRowView& values)
{
  SpectralShape scaledSource, scaledTarget;
  const SpectralShape& source = AtUnitArea(givenSource, scaledSource);
  const SpectralShape& target = AtUnitArea(givenTarget, scaledTarget);
  const Eigen::Index k2 = map.rows();
  const Eigen::Index k1 = map.cols();
  if (k1 > source.Harmonics.cols() || k2 > target.Harmonics.cols())
  {
    throw InvalidInput("a functional map of " + std::to_string(k2) + " by " +
      std::to_string(k1) + " does not fit bases of " + std::to_string(target.Harmonics.cols()) +
      " (target) and " + std::to_string(source.Harmonics.cols()) + " (source) harmonics");
  }
  const Eigen::Index n1 = source.Harmonics.rows();
  if (values.rows() != n1 || source.Mass.size() != n1)
  {
    throw InvalidInput("the source values have " + std::to_string(values.rows()) +
      " rows for " + std::to_string(n1) + " source points");
  }
  // D1 X, with the points of zero mass left out (their values may be anything, even NaN).
  RowMatrix weighted = RowMatrix::Zero(n1, values.cols());
  for (Eigen::Index i = 0; i < n1; ++i)
  {
    if (source.Mass[i] > 0.0)
    {
      weighted.row(i) = source.Mass[i] * values.row(i);
    }
  }
  const DenseMatrix coefficients = source.Harmonics.leftCols(k1).transpose() * weighted;
  return target.Harmonics.leftCols(k2) * (map * coefficients);
}

//------------------------------------------------------------------------------
RowMatrix TransferThroughPoints(
  const std::vector<int>& correspondingPointIds, const ConstRowView& values)
{
  RowMatrix result(static_cast<Eigen::Index>(correspondingPointIds.size()), values.cols());
  for (std::size_t j = 0; j < correspondingPointIds.size(); ++j)
  {
    const int i = correspondingPointIds[j];
    if (i < -1 || i >= values.rows())
    {
      throw InvalidInput("the point map holds the source point " + std::to_string(i) +
        ", out of range (the values have " + std::to_string(values.rows()) + " rows)");
    }
    if (i >= 0)
    {
      result.row(static_cast<Eigen::Index>(j)) = values.row(i);
    }
    else
    {
      result.row(static_cast<Eigen::Index>(j)).setConstant(
        std::numeric_limits<double>::quiet_NaN());
    }
  }
  return result;
}

//------------------------------------------------------------------------------
RowMatrix AlignModes(const SpectralShape& source, const SpectralShape& target,
  const DenseMatrix& map, std::vector<int>* order, Vector* signs)
{
  const Eigen::Index k2 = map.rows();
  const Eigen::Index k1 = map.cols();
  if (k1 > k2 || k1 > source.Harmonics.cols() || k2 > target.Harmonics.cols() ||
    target.Eigenvalues.size() < k2)
  {
    throw InvalidInput("mode alignment needs a map of k2 by k1 with k1 <= k2 and bases of at "
                       "least that many harmonics");
  }
  // Near-degenerate groups of the target's first k2 eigenvalues: group[j] is the first index.
  std::vector<Eigen::Index> group(static_cast<std::size_t>(k2), 0);
  const double top = target.Eigenvalues.head(k2).maxCoeff();
  for (Eigen::Index j = 1; j < k2; ++j)
  {
    const double a = target.Eigenvalues[j - 1];
    const double b = target.Eigenvalues[j];
    const bool bothZero = IsZeroEigenvalue(a, top) && IsZeroEigenvalue(b, top);
    const bool close = !IsZeroEigenvalue(a, top) && b - a <= DegenerateEigenvalueGap * b;
    group[static_cast<std::size_t>(j)] = bothZero || close ? group[static_cast<std::size_t>(j - 1)] : j;
  }
  std::vector<bool> used(static_cast<std::size_t>(k2), false);
  RowMatrix aligned = RowMatrix::Zero(target.Harmonics.rows(), k1);
  if (order)
  {
    order->assign(static_cast<std::size_t>(k1), -1);
  }
  if (signs)
  {
    signs->setOnes(k1);
  }
  for (Eigen::Index k = 0; k < k1; ++k)
  {
    Eigen::Index best = -1;
    for (Eigen::Index j = 0; j < k2; ++j)
    {
      if (!used[static_cast<std::size_t>(j)] &&
        (best < 0 || std::abs(map(j, k)) > std::abs(map(best, k))))
      {
        best = j;
      }
    }
    used[static_cast<std::size_t>(best)] = true;
    const Eigen::Index first = group[static_cast<std::size_t>(best)];
    Eigen::Index count = 1;
    while (first + count < k2 && group[static_cast<std::size_t>(first + count)] == first)
    {
      ++count;
    }
    const Vector c = map.col(k).segment(first, count);
    const double norm = c.norm();
    if (norm > 0.0)
    {
      aligned.col(k) = target.Harmonics.middleCols(first, count) * (c / norm);
    }
    if (order)
    {
      (*order)[static_cast<std::size_t>(k)] = static_cast<int>(best);
    }
    if (signs)
    {
      (*signs)[k] = map(best, k) < 0.0 ? -1.0 : 1.0;
    }
  }
  return aligned;
}
} // namespace spectral
