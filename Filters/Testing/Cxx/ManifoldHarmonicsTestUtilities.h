// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Checks and comparisons shared by the C++ tests of the filters.
#ifndef ManifoldHarmonicsTestUtilities_h
#define ManifoldHarmonicsTestUtilities_h

#include "vtkDataArray.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

namespace ManifoldHarmonicsTest
{
/// Print what failed (the test fails on the return value and on "ERROR:" in its output).
inline bool Check(bool condition, const std::string& what)
{
  if (!condition)
  {
    std::cerr << "ERROR: " << what << std::endl;
  }
  return condition;
}

/// max |a - b| / max |b| over all values; 1 if an array is missing or the shapes differ.
inline double RelativeDifference(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetNumberOfTuples() != b->GetNumberOfTuples() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents())
  {
    return 1.0;
  }
  double difference = 0.0;
  double scale = 0.0;
  for (vtkIdType i = 0; i < b->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < b->GetNumberOfComponents(); ++c)
    {
      difference = std::max(difference, std::abs(a->GetComponent(i, c) - b->GetComponent(i, c)));
      scale = std::max(scale, std::abs(b->GetComponent(i, c)));
    }
  }
  return difference / scale;
}
} // namespace ManifoldHarmonicsTest

#endif
