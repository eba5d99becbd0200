// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Checks and comparisons shared by the C++ tests of the filters.
#ifndef ManifoldHarmonicsTestUtilities_h
#define ManifoldHarmonicsTestUtilities_h

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTestErrorObserver.h"

#include "Perturbation.h" // Testing/Core: the rounding-level perturbation of generated meshes

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

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

/// One named case of a test file: one property, whose checks its function runs.
struct Case
{
  std::string Name;
  std::function<bool()> Run;
};

/**
 * Run the case named by argv[1], or every case when there is no name (argv[0] is the test's
 * name, as the VTK test driver passes it; a flag such as -T is not a name). CTest runs one case
 * per test (Filters/Testing/Cxx/CMakeLists.txt). Returns EXIT_FAILURE if a case failed or threw,
 * or the name is unknown. With --cases, prints "case <Name>" for each case and runs none
 * (CheckCases.cmake compares them with the cases CTest registers).
 */
inline int RunCases(int argc, char* argv[], const std::vector<Case>& cases)
{
  if (argc > 1 && std::string(argv[1]) == "--cases")
  {
    for (const Case& c : cases)
    {
      std::cout << "case " << c.Name << std::endl;
    }
    return EXIT_SUCCESS;
  }
  const bool one = argc > 1 && argv[1][0] != '-';
  bool found = false;
  bool ok = true;
  for (const Case& c : cases)
  {
    if (one && c.Name != argv[1])
    {
      continue;
    }
    found = true;
    std::cout << c.Name << std::endl;
    try
    {
      ok &= c.Run();
    }
    catch (const std::exception& e)
    {
      ok = Check(false, c.Name + ": unexpected exception: " + e.what());
    }
  }
  if (one && !found)
  {
    Check(false, std::string("unknown test case '") + argv[1] + "'");
    return EXIT_FAILURE;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}

/**
 * The errors and warnings of the algorithms observed, caught instead of printed (a printed
 * "ERROR:" fails the test), and the errors of their executives ("Algorithm ... returned
 * failure"), caught apart. `messages->GetError()` and the like read what the algorithms said.
 * The observers go with the object: an algorithm that outlives it prints again.
 */
class Messages
{
public:
  Messages() = default;
  explicit Messages(vtkAlgorithm* algorithm) { this->Observe(algorithm); }
  Messages(const Messages&) = delete;
  Messages& operator=(const Messages&) = delete;
  ~Messages()
  {
    for (const Observation& observation : this->Observations)
    {
      observation.Subject->RemoveObserver(observation.Tag);
    }
  }

  void Observe(vtkAlgorithm* algorithm)
  {
    this->Add(algorithm, vtkCommand::ErrorEvent, this->Caught);
    this->Add(algorithm, vtkCommand::WarningEvent, this->Caught);
    this->Add(algorithm->GetExecutive(), vtkCommand::ErrorEvent, this->Executive);
  }

  vtkTest::ErrorObserver* operator->() const { return this->Caught; }

  vtkNew<vtkTest::ErrorObserver> Caught;
  vtkNew<vtkTest::ErrorObserver> Executive;

private:
  struct Observation
  {
    vtkSmartPointer<vtkObject> Subject;
    unsigned long Tag;
  };
  void Add(vtkObject* subject, unsigned long event, vtkCommand* observer)
  {
    this->Observations.push_back({ subject, subject->AddObserver(event, observer) });
  }
  std::vector<Observation> Observations;
};

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

/// 1 for a point that sums over points count, 0 for one flagged DUPLICATEPOINT in the point
/// ghost array (a copy of a welded point, or a point another process owns).
inline double CountedPoint(vtkPolyData* mesh, vtkIdType i)
{
  vtkDataArray* ghosts = mesh->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName());
  return ghosts && (static_cast<int>(ghosts->GetTuple1(i)) & vtkDataSetAttributes::DUPLICATEPOINT)
    ? 0.0
    : 1.0;
}

/// The Sphere source's unit sphere with double points (its own copy, not the source's output).
inline vtkSmartPointer<vtkPolyData> UnitSphere(int thetaResolution, int phiResolution)
{
  auto sphere = vtkSmartPointer<vtkSphereSource>::New();
  sphere->SetThetaResolution(thetaResolution);
  sphere->SetPhiResolution(phiResolution);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(sphere->GetOutput());
  return mesh;
}

/// UnitSphere with the point scalar "Height" = z + 0.3 x y (a signal to transform and filter).
inline vtkSmartPointer<vtkPolyData> SphereWithHeight(int thetaResolution, int phiResolution)
{
  vtkSmartPointer<vtkPolyData> mesh = UnitSphere(thetaResolution, phiResolution);
  vtkNew<vtkDoubleArray> height;
  height->SetName("Height");
  height->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    const double* p = mesh->GetPoint(i);
    height->SetValue(i, p[2] + 0.3 * p[0] * p[1]);
  }
  mesh->GetPointData()->AddArray(height);
  return mesh;
}

/**
 * The points of a generated mesh times 1 + 1e-15 u when MANIFOLDHARMONICS_TEST_PERTURBATION is
 * set (Testing/Core/Perturbation.h); unchanged without it. Float points round the perturbation
 * away: it applies to double points.
 */
inline void Perturb(vtkPoints* points)
{
  spectral::testing::RoundingPerturbation factor;
  if (!points || !factor.Active())
  {
    return;
  }
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    for (double& x : p)
    {
      x *= factor();
    }
    points->SetPoint(i, p);
  }
  points->Modified();
}

/// The points joined by one polyline, without polygons: what vtkManifoldHarmonicBasis passes
/// through without a basis (points with vertex cells only are a point cloud, an error).
inline vtkSmartPointer<vtkPolyData> LinesOnly(vtkPoints* points)
{
  auto curve = vtkSmartPointer<vtkPolyData>::New();
  curve->SetPoints(points);
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  lines->InsertNextCell(curve->GetNumberOfPoints());
  for (vtkIdType i = 0; i < curve->GetNumberOfPoints(); ++i)
  {
    lines->InsertCellPoint(i);
  }
  curve->SetLines(lines);
  return curve;
}

/// A ProgressEvent observer that counts the reports strictly inside (0, 1) (the executive
/// reports 0 before RequestData and 1 after) and asks the reporting algorithm to abort at each.
class AbortAtFirstProgress : public vtkCommand
{
public:
  vtkTypeMacro(AbortAtFirstProgress, vtkCommand);
  static AbortAtFirstProgress* New() { return new AbortAtFirstProgress; }
  void Execute(vtkObject* caller, unsigned long, void* callData) override
  {
    const double progress = *static_cast<double*>(callData);
    if (progress > 0.0 && progress < 1.0)
    {
      ++this->Count;
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    }
  }
  int Count = 0;
};
} // namespace ManifoldHarmonicsTest

#endif
