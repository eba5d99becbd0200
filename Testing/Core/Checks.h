// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Assertions and a case runner for the core tests. Every check prints the measured value and
// its bound; a failed check makes the test exit with EXIT_FAILURE.
//
// MANIFOLDHARMONICS_TEST_THREADS=<n> (n >= 1) in the environment runs every case under a
// ScopedThreadLimit of n: what the core's automatic thread count (0, every core) means, as on a
// machine with n cores (scripts/check-portability.sh runs the counting tests with 1 and 2).
#ifndef spectral_Testing_Checks_h
#define spectral_Testing_Checks_h

#include "Common/Mesh.h"
#include "Common/Threads.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

namespace spectral
{
namespace testing
{
/// Number of failed checks so far.
inline int& Failures()
{
  static int count = 0;
  return count;
}

/// Record a property: print it, count it as failed if ok is false.
inline void Check(bool ok, const std::string& what)
{
  std::printf("  [%s] %s\n", ok ? " ok " : "FAIL", what.c_str());
  if (!ok)
  {
    ++Failures();
  }
}

/// Check value <= bound (false for NaN), printing both.
inline void CheckBelow(double value, double bound, const std::string& what)
{
  char buffer[96];
  std::snprintf(buffer, sizeof(buffer), ": %.3e <= %.1e", value, bound);
  Check(value <= bound, what + buffer);
}

/// Check |value - expected| <= tolerance (false for NaN), printing the values.
inline void CheckNear(double value, double expected, double tolerance, const std::string& what)
{
  char buffer[128];
  std::snprintf(buffer,
    sizeof(buffer),
    ": %.12g vs %.12g (|diff| %.2e <= %.1e)",
    value,
    expected,
    std::abs(value - expected),
    tolerance);
  Check(std::abs(value - expected) <= tolerance, what + buffer);
}

/// Check that f() throws an exception of type E.
template<typename E, typename F>
void CheckThrows(F f, const std::string& what)
{
  try
  {
    f();
  }
  catch (const E& e)
  {
    Check(true, what + " (threw: " + e.what() + ")");
    return;
  }
  catch (const std::exception& e)
  {
    Check(false, what + " threw the wrong exception: " + e.what());
    return;
  }
  Check(false, what + " did not throw");
}

/// Largest off-diagonal entry of a stiffness matrix (positive = a negative edge weight).
inline double LargestOffDiagonal(const SparseMatrix& L)
{
  double largest = -1e300;
  for (int col = 0; col < L.outerSize(); ++col)
  {
    for (SparseMatrix::InnerIterator it(L, col); it; ++it)
    {
      if (it.row() != it.col())
      {
        largest = std::max(largest, it.value());
      }
    }
  }
  return largest;
}

/// max |L - L^T| and max |L 1|, relative to max |L_ii|.
inline void CheckStiffness(const SparseMatrix& L, const std::string& what)
{
  const double scale = L.diagonal().cwiseAbs().maxCoeff();
  const SparseMatrix asym = L - SparseMatrix(L.transpose());
  CheckBelow(asym.coeffs().size() ? asym.coeffs().cwiseAbs().maxCoeff() / scale : 0.0,
    1e-14,
    what + ": L symmetric");
  CheckBelow((L * Vector::Ones(L.rows())).cwiseAbs().maxCoeff() / scale, 1e-12, what + ": L 1 = 0");
  Check(L.coeffs().allFinite(), what + ": L finite");
}

/// One named test case: a function that calls the checks.
struct Case
{
  const char* Name;
  void (*Run)();
};

/**
 * Run the case named by argv[1], or every case without an argument. Returns EXIT_FAILURE if a
 * check failed, a case threw, or the name is unknown.
 */
template<std::size_t N>
int RunCases(int argc, char* argv[], const Case (&cases)[N])
{
  const char* threads = std::getenv("MANIFOLDHARMONICS_TEST_THREADS");
  const ScopedThreadLimit limit(threads ? std::atoi(threads) : 0);
  bool found = false;
  for (const Case& c : cases)
  {
    if (argc > 1 && std::strcmp(argv[1], c.Name) != 0)
    {
      continue;
    }
    found = true;
    std::printf("%s\n", c.Name);
    try
    {
      c.Run();
    }
    catch (const std::exception& e)
    {
      Check(false, std::string("unexpected exception: ") + e.what());
    }
  }
  if (!found)
  {
    std::printf("unknown test case '%s'\n", argc > 1 ? argv[1] : "");
    return EXIT_FAILURE;
  }
  if (Failures() > 0)
  {
    std::printf("%d check(s) failed\n", Failures());
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
} // namespace testing
} // namespace spectral

#endif
