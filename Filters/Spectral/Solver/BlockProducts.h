// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file BlockProducts.h
 * @brief Products of a tall matrix with a few columns, the reorthogonalization of the block
 *        Lanczos iteration, rows split over threads.
 *
 * Each block of the iteration is projected out of the whole Krylov basis B (n x K, K up to a
 * few hundred): C = B^T A, then A -= B C, with A only a few columns wide. Both products read B
 * once and do little arithmetic per entry of B. A general matrix product copies (packs) B into
 * its own layout in short pieces; these kernels read each column of B in place as a long stream
 * (2048 rows), keep that many rows of A row by row (all its columns of one row next to each
 * other, padded to 4, 8 or 16) in cache, and let a row of A serve several columns of B at once.
 * On the benchmark machine (AVX-512, two threads, n = 1e5, K = 128 to 300, 12 columns) B^T A
 * reads B at 23 to 24 GB/s and A -= B C at 19 to 21 GB/s, where Eigen's product reads it at 8 to
 * 10 (a plain sum: 29 GB/s). Wider A goes to Eigen's product.
 *
 * The same holds for products of the sparse matrices with many vectors (SymmetricSparseProduct).
 *
 * Every product takes a thread count `threads` as in Common/Threads.h (0, the default: every
 * core, BlockThreads). The rows are split into that many contiguous ranges; each range writes
 * its own rows, or (B^T A) its own partial sum, and the partial sums are added in the order of
 * the ranges, so the result does not depend on the scheduling and differs between thread counts
 * only by the rounding of those sums.
 *
 * Used by EigenSolver.cxx; tested by Testing/Core/TestBlockProducts.cxx.
 */
#ifndef spectral_BlockProducts_h
#define spectral_BlockProducts_h

#include "Common/Mesh.h"

#include <vector>

namespace spectral
{
namespace detail
{
/// One row of a narrow block, padded to Width columns: one or two SIMD registers (AVX-512), or
/// a few (AVX2); Eigen picks the instructions of the target. The kernels below, and the final
/// check's products (Verification.cxx), keep a few columns row by row in this layout.
template<int Width>
using Row = Eigen::Matrix<double, Width, 1>;

template<int Width>
using Rows = std::vector<Row<Width>, Eigen::aligned_allocator<Row<Width>>>;

/// The rows of `source` into the first source.cols() entries of rows[0], rows[1], ... (the
/// entries beyond them are left as they are).
template<int Width>
void CopyIn(const Eigen::Ref<const DenseMatrix>& source, Row<Width>* rows)
{
  for (Eigen::Index j = 0; j < source.cols(); ++j)
  {
    const double* column = source.data() + j * source.outerStride();
    for (Eigen::Index i = 0; i < source.rows(); ++i)
    {
      rows[i][j] = column[i];
    }
  }
}

/// The first target.cols() entries of rows[0], rows[1], ... into the rows of `target`.
template<int Width>
void CopyOut(const Row<Width>* rows, Eigen::Ref<DenseMatrix> target)
{
  for (Eigen::Index j = 0; j < target.cols(); ++j)
  {
    double* column = target.data() + j * target.outerStride();
    for (Eigen::Index i = 0; i < target.rows(); ++i)
    {
      column[i] = rows[i][j];
    }
  }
}
} // namespace detail

/// Widest A the kernels take.
constexpr int NarrowBlockWidth = 16;

/**
 * Number of row ranges (threads) for products over n rows: `requested` if >= 1 (at most n),
 * else ThreadsForWork (Common/Threads.h) with at least 4096 rows a thread, so 1 below 8192 rows.
 */
int BlockThreads(Eigen::Index n, int requested = 0);

/**
 * B^T A for a tall n x K matrix B and an n x w matrix A.
 * \param B column-major, any outer stride (e.g. the leading columns of a larger matrix).
 * \param A n x w, any outer stride.
 * \param threads As BlockThreads.
 * \return K x w.
 */
DenseMatrix TransposeProduct(const Eigen::Ref<const DenseMatrix>& B,
  const Eigen::Ref<const DenseMatrix>& A,
  int threads = 0);

/**
 * A -= B C for a tall n x K matrix B, an n x w matrix A and a K x w matrix C.
 * \param A updated in place.
 * \param threads As BlockThreads.
 */
void SubtractProduct(Eigen::Ref<DenseMatrix> A,
  const Eigen::Ref<const DenseMatrix>& B,
  const DenseMatrix& C,
  int threads = 0);

/**
 * out = A X for a symmetric sparse A (both triangles stored, as the stiffness, mass and shifted
 * matrices are) and a tall n x k X. Column i of A is row i, so each row of the result is one
 * pass over a column of A with 16 columns of X at a time kept row by row (a row-major copy), and
 * the rows are split over threads. Eigen's sparse-dense product scatters into one column at
 * a time on one thread: for the 100,000-point torus and 100 columns it took 123 to 158 ms where
 * this takes 63 to 92 ms (two threads). Fewer than 8 columns, one thread (by default below 8192
 * rows) or an uncompressed A use Eigen's product.
 * \param out n x k, not aliasing X.
 * \param threads As BlockThreads.
 */
void SymmetricSparseProduct(const SparseMatrix& A,
  const Eigen::Ref<const DenseMatrix>& X,
  Eigen::Ref<DenseMatrix> out,
  int threads = 0);
} // namespace spectral

#endif
