// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
#include "Solver/BlockProducts.h"
#include "Common/Threads.h"

#include <algorithm>
#include <type_traits>
#include <vector>

namespace spectral
{
namespace
{
using detail::CopyIn;
using detail::CopyOut;
using detail::Row;
using detail::Rows;

/**
 * Rows per chunk. A chunk of the narrow block (2048 x 16 doubles at most, 256 KB) stays in the
 * per-core L2 cache while the columns of B stream past it. Long chunks matter: every column of B
 * is read as a stream of ChunkRows entries, and the hardware prefetcher needs a long stream to
 * reach full bandwidth (measured on the benchmark machine, two threads, K = 200: B^T A reads B
 * at 6 to 11 GB/s with chunks of 256 rows, at 15 to 16 GB/s with 1024 to 4096).
 */
constexpr Eigen::Index ChunkRows = 2048;

/**
 * Fewer columns of B than this go to Eigen's product: copying the rows of A costs about as much
 * as reading some 100 columns of B, and Eigen's product is as fast as the kernels up to there
 * (measured with n = 1e5 and 12 columns: equal at K = 96, kernels 25% faster at 128, 45% at 240).
 */
constexpr Eigen::Index KernelColumns = 96;

/// The padded row width of the kernels for K columns of B and w of A: 4, 8 or 16, or 0 where
/// Eigen's product does better (K < KernelColumns) or A is too wide.
int KernelWidth(Eigen::Index K, Eigen::Index w)
{
  if (K < KernelColumns || w > NarrowBlockWidth)
  {
    return 0;
  }
  return w <= 4 ? 4 : (w <= 8 ? 8 : NarrowBlockWidth);
}

/**
 * Columns of B handled together: each holds Width / (register width) accumulators, and the row
 * of the narrow block loaded once serves all of them. Eight fill the 32 vector registers of
 * AVX-512 for Width 16; AVX2 has 16 registers.
 */
#ifdef EIGEN_VECTORIZE_AVX512
constexpr int Group = 8;
#else
constexpr int Group = 3;
#endif

/// out[q] += sum_i B(i, q) rows[i] for the G columns of B starting at `column` (stride ldb), over h
/// rows.
template<int Width, int G>
void AccumulateColumns(const double* column,
  Eigen::Index ldb,
  const Rows<Width>& rows,
  Eigen::Index h,
  Row<Width>* out)
{
  Row<Width> sum[G];
  const double* b[G];
  for (int q = 0; q < G; ++q)
  {
    sum[q].setZero();
    b[q] = column + q * ldb;
  }
  for (Eigen::Index i = 0; i < h; ++i)
  {
    // A reference, not a copy: GCC 12 copies a Row<16> through four 32-byte stores and then
    // loads it as two 64-byte registers, which stalls every row on store forwarding (B^T A read
    // B at 11 GB/s with the copy, 23 GB/s without; two threads, n = 1e5, 12 columns).
    const Row<Width>& row = rows[static_cast<std::size_t>(i)];
    for (int q = 0; q < G; ++q)
    {
      sum[q] += b[q][i] * row;
    }
  }
  for (int q = 0; q < G; ++q)
  {
    out[q] += sum[q];
  }
}

/// rows[i] -= sum_q B(i, q) coefficients[q] for the G columns of B starting at `column`.
template<int Width, int G>
void SubtractColumns(const double* column,
  Eigen::Index ldb,
  const Row<Width>* coefficients,
  Rows<Width>& rows,
  Eigen::Index h)
{
  Row<Width> c[G];
  const double* b[G];
  for (int q = 0; q < G; ++q)
  {
    c[q] = coefficients[q];
    b[q] = column + q * ldb;
  }
  for (Eigen::Index i = 0; i < h; ++i)
  {
    Row<Width> row = rows[static_cast<std::size_t>(i)];
    for (int q = 0; q < G; ++q)
    {
      row -= b[q][i] * c[q];
    }
    rows[static_cast<std::size_t>(i)] = row;
  }
}

/**
 * Call work(std::integral_constant<int, G>(), k) for the columns [k, k + G) of [0, K): groups of
 * Group, then the remainder in groups of 4, 2 and 1 (a single accumulator would wait on its own
 * additions).
 */
template<typename Work>
void ForColumnGroups(Eigen::Index K, const Work& work)
{
  Eigen::Index k = 0;
  for (; k + Group <= K; k += Group)
  {
    work(std::integral_constant<int, Group>(), k);
  }
  if (Group > 4 && k + 4 <= K)
  {
    work(std::integral_constant<int, 4>(), k);
    k += 4;
  }
  for (; k + 2 <= K; k += 2)
  {
    work(std::integral_constant<int, 2>(), k);
  }
  if (k < K)
  {
    work(std::integral_constant<int, 1>(), k);
  }
}

/**
 * Call work(rows, c0, h) for the chunks [c0, c0 + h) of the rows [first, first + count), with
 * those rows of A in `rows` (zero-padded to Width).
 */
template<int Width, typename Work>
void ForEachChunk(const Eigen::Ref<const DenseMatrix>& A,
  Eigen::Index first,
  Eigen::Index count,
  const Work& work)
{
  Rows<Width> rows(static_cast<std::size_t>(std::min(ChunkRows, count)), Row<Width>::Zero());
  for (Eigen::Index c0 = first; c0 < first + count; c0 += ChunkRows)
  {
    const Eigen::Index h = std::min(ChunkRows, first + count - c0);
    CopyIn<Width>(A.middleRows(c0, h), rows.data());
    work(rows, c0, h);
  }
}

/// out += B^T A over the rows [first, first + count): K rows of Width.
template<int Width>
void TransposeRange(const Eigen::Ref<const DenseMatrix>& B,
  const Eigen::Ref<const DenseMatrix>& A,
  Eigen::Index first,
  Eigen::Index count,
  Rows<Width>& out)
{
  const Eigen::Index ldb = B.outerStride();
  ForEachChunk<Width>(A,
    first,
    count,
    [&](const Rows<Width>& rows, Eigen::Index c0, Eigen::Index h)
    {
      ForColumnGroups(B.cols(),
        [&](auto group, Eigen::Index k)
        {
          AccumulateColumns<Width, decltype(group)::value>(
            B.data() + k * ldb + c0, ldb, rows, h, &out[static_cast<std::size_t>(k)]);
        });
    });
}

/// A -= B C over the rows [first, first + count), with C as K rows of Width.
template<int Width>
void SubtractRange(Eigen::Ref<DenseMatrix> A,
  const Eigen::Ref<const DenseMatrix>& B,
  const Rows<Width>& C,
  Eigen::Index first,
  Eigen::Index count)
{
  const Eigen::Index ldb = B.outerStride();
  ForEachChunk<Width>(A,
    first,
    count,
    [&](Rows<Width>& rows, Eigen::Index c0, Eigen::Index h)
    {
      ForColumnGroups(B.cols(),
        [&](auto group, Eigen::Index k)
        {
          SubtractColumns<Width, decltype(group)::value>(
            B.data() + k * ldb + c0, ldb, &C[static_cast<std::size_t>(k)], rows, h);
        });
      CopyOut<Width>(rows.data(), A.middleRows(c0, h));
    });
}

template<int Width>
DenseMatrix TransposeProductOfWidth(const Eigen::Ref<const DenseMatrix>& B,
  const Eigen::Ref<const DenseMatrix>& A,
  int parts)
{
  const Eigen::Index K = B.cols();
  std::vector<Rows<Width>> partial(
    static_cast<std::size_t>(parts), Rows<Width>(static_cast<std::size_t>(K), Row<Width>::Zero()));
  ForEachRowRange(A.rows(),
    parts,
    [&](int part, Eigen::Index first, Eigen::Index count)
    { TransposeRange<Width>(B, A, first, count, partial[static_cast<std::size_t>(part)]); });
  DenseMatrix C(K, A.cols());
  for (Eigen::Index k = 0; k < K; ++k)
  {
    Row<Width> sum = partial[0][static_cast<std::size_t>(k)];
    for (std::size_t part = 1; part < partial.size(); ++part)
    {
      sum += partial[part][static_cast<std::size_t>(k)];
    }
    C.row(k) = sum.head(A.cols()).transpose();
  }
  return C;
}

template<int Width>
void SubtractProductOfWidth(Eigen::Ref<DenseMatrix> A,
  const Eigen::Ref<const DenseMatrix>& B,
  const DenseMatrix& C,
  int parts)
{
  Rows<Width> coefficients(static_cast<std::size_t>(C.rows()), Row<Width>::Zero());
  for (Eigen::Index k = 0; k < C.rows(); ++k)
  {
    coefficients[static_cast<std::size_t>(k)].head(C.cols()) = C.row(k).transpose();
  }
  ForEachRowRange(A.rows(),
    parts,
    [&](int, Eigen::Index first, Eigen::Index count)
    { SubtractRange<Width>(A, B, coefficients, first, count); });
}
} // namespace

//------------------------------------------------------------------------------
int BlockThreads(Eigen::Index n, int requested)
{
  const int threads = ThreadsForWork(n, 4096, requested);
  return static_cast<int>(std::max<Eigen::Index>(1, std::min<Eigen::Index>(threads, n)));
}

//------------------------------------------------------------------------------
DenseMatrix TransposeProduct(const Eigen::Ref<const DenseMatrix>& B,
  const Eigen::Ref<const DenseMatrix>& A,
  int threads)
{
  const Eigen::Index w = A.cols();
  const int parts = BlockThreads(A.rows(), threads);
  if (w == 0 || B.cols() == 0)
  {
    return DenseMatrix::Zero(B.cols(), w);
  }
  switch (KernelWidth(B.cols(), w))
  {
    case 4:
      return TransposeProductOfWidth<4>(B, A, parts);
    case 8:
      return TransposeProductOfWidth<8>(B, A, parts);
    case NarrowBlockWidth:
      return TransposeProductOfWidth<NarrowBlockWidth>(B, A, parts);
    default:
      break;
  }
  std::vector<DenseMatrix> partial(static_cast<std::size_t>(parts));
  ForEachRowRange(A.rows(),
    parts,
    [&](int part, Eigen::Index first, Eigen::Index count)
    {
      partial[static_cast<std::size_t>(part)].noalias() =
        B.middleRows(first, count).transpose() * A.middleRows(first, count);
    });
  for (std::size_t part = 1; part < partial.size(); ++part)
  {
    partial[0] += partial[part];
  }
  return partial[0];
}

//------------------------------------------------------------------------------
void SubtractProduct(Eigen::Ref<DenseMatrix> A,
  const Eigen::Ref<const DenseMatrix>& B,
  const DenseMatrix& C,
  int threads)
{
  const Eigen::Index w = A.cols();
  const int parts = BlockThreads(A.rows(), threads);
  if (w == 0 || B.cols() == 0)
  {
    return;
  }
  switch (KernelWidth(B.cols(), w))
  {
    case 4:
      SubtractProductOfWidth<4>(A, B, C, parts);
      break;
    case 8:
      SubtractProductOfWidth<8>(A, B, C, parts);
      break;
    case NarrowBlockWidth:
      SubtractProductOfWidth<NarrowBlockWidth>(A, B, C, parts);
      break;
    default:
      ForEachRowRange(A.rows(),
        parts,
        [&](int, Eigen::Index first, Eigen::Index count)
        { A.middleRows(first, count).noalias() -= B.middleRows(first, count) * C; });
      break;
  }
}

//------------------------------------------------------------------------------
void SymmetricSparseProduct(const SparseMatrix& A,
  const Eigen::Ref<const DenseMatrix>& X,
  Eigen::Ref<DenseMatrix> out,
  int threads)
{
  constexpr int Width = NarrowBlockWidth;
  const Eigen::Index n = A.rows();
  const int parts = BlockThreads(n, threads);
  if (X.cols() < 8 || parts == 1 || !A.isCompressed())
  {
    out.noalias() = A * X;
    return;
  }
  // Rows of the current 16 columns of X; where fewer are left, the lanes beyond them keep
  // earlier values, which only reach lanes that are not written out.
  Rows<Width> rows(static_cast<std::size_t>(n), Row<Width>::Zero());
  const int* start = A.outerIndexPtr();
  const int* index = A.innerIndexPtr();
  const double* value = A.valuePtr();
  for (Eigen::Index c0 = 0; c0 < X.cols(); c0 += Width)
  {
    const Eigen::Index w = std::min<Eigen::Index>(Width, X.cols() - c0);
    ForEachRowRange(n,
      parts,
      [&](int, Eigen::Index first, Eigen::Index count)
      { CopyIn<Width>(X.block(first, c0, count, w), rows.data() + first); });
    ForEachRowRange(n,
      parts,
      [&](int, Eigen::Index first, Eigen::Index count)
      {
        // A few hundred result rows at a time, then written out column by column.
        constexpr Eigen::Index Chunk = 256;
        Rows<Width> result(static_cast<std::size_t>(Chunk));
        for (Eigen::Index r = first; r < first + count; r += Chunk)
        {
          const Eigen::Index h = std::min(Chunk, first + count - r);
          for (Eigen::Index t = 0; t < h; ++t)
          {
            Row<Width> sum = Row<Width>::Zero();
            for (int p = start[r + t]; p < start[r + t + 1]; ++p)
            {
              sum += value[p] * rows[static_cast<std::size_t>(index[p])];
            }
            result[static_cast<std::size_t>(t)] = sum;
          }
          CopyOut<Width>(result.data(), out.block(r, c0, h, w));
        }
      });
  }
}
} // namespace spectral
