// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// The seam rule in a serial run (vtkManifoldHarmonicsParallel::WeldPoints): a sphere unwelded the
// way ParaView's OBJ reader unwelds a file with texture indices (every triangle its own three
// points, the triangle soup) against the same sphere welded.
// - WeldSeams (default on): the soup's spectrum equals the sphere's (eigenvalues to 1e-10 of the
//   largest, harmonics as the same subspaces); the output keeps the soup's points, cells and
//   arrays; every copy of a point gets the same harmonics and mass; each welded point counts
//   once (the mass of the counted copies adds up to the sphere's area, and the transform's
//   coefficients have the sphere's Gram matrix); smoothing, the spectral filter and the heat
//   kernel signature give every copy the sphere's value at its point, so the seams stay closed;
//   copies moved apart by less than SeamTolerance are welded, farther ones are not.
// - WeldSeams off: today's behaviour, one component per triangle (all eigenvalues zero) and the
//   warning about connected components.
// The distributed case (2 and 3 processes, both solvers): Testing/ParaView/TestParallelManifold
// Harmonics.py.in and TestSlepcManifoldHarmonics.py.in.

#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicSmoothing.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkSpectralDescriptors.h"
#include "vtkSpectralFilter.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using ManifoldHarmonicsTest::Check;
using ManifoldHarmonicsTest::CountedPoint;

// Whole clusters of the sphere's eigenvalues (l <= 3), whose subspaces are well defined.
constexpr int Harmonics = 16;
const char* const TextureArray = "Texture";

//------------------------------------------------------------------------------
// The triangle soup: triangle t of the sphere on points 3t, 3t + 1, 3t + 2 (exact copies), with
// a point array that differs between the copies of a point (as texture coordinates do).
// Source[i] is the sphere point that soup point i copies.
vtkSmartPointer<vtkPolyData> MakeSoup(vtkPolyData* sphere, std::vector<vtkIdType>& source)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> triangles;
  vtkNew<vtkDoubleArray> texture;
  texture->SetName(TextureArray);
  vtkNew<vtkIdList> ids;
  for (vtkIdType t = 0; t < sphere->GetNumberOfCells(); ++t)
  {
    sphere->GetCellPoints(t, ids);
    triangles->InsertNextCell(3);
    for (vtkIdType c = 0; c < 3; ++c)
    {
      source.push_back(ids->GetId(c));
      texture->InsertNextValue(static_cast<double>(t));
      triangles->InsertCellPoint(points->InsertNextPoint(sphere->GetPoint(ids->GetId(c))));
    }
  }
  auto soup = vtkSmartPointer<vtkPolyData>::New();
  soup->SetPoints(points);
  soup->SetPolys(triangles);
  soup->GetPointData()->AddArray(texture);
  return soup;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> Basis(vtkPolyData* input,
  bool weld,
  std::string* warnings = nullptr,
  double tolerance = 1e-12)
{
  vtkNew<vtkTest::ErrorObserver> messages;
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->AddObserver(vtkCommand::WarningEvent, messages);
  basis->SetNumberOfHarmonics(Harmonics);
  basis->SetWeldSeams(weld);
  basis->SetSeamTolerance(tolerance);
  basis->SetInputData(input);
  basis->Update();
  if (warnings)
  {
    *warnings = messages->GetWarningMessage();
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(basis->GetOutput());
  return output;
}

//------------------------------------------------------------------------------
// max over soup points i and components c of |soupArray(i, c) - sphereArray(Source[i], c)|,
// relative to `scale`; 1 if an array is missing.
double DifferenceAtCopies(vtkDataArray* soupArray,
  vtkDataArray* sphereArray,
  const std::vector<vtkIdType>& source,
  double scale)
{
  if (!soupArray || !sphereArray ||
    soupArray->GetNumberOfComponents() != sphereArray->GetNumberOfComponents() ||
    soupArray->GetNumberOfTuples() != static_cast<vtkIdType>(source.size()))
  {
    return 1.0;
  }
  double difference = 0.0;
  for (vtkIdType i = 0; i < soupArray->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < soupArray->GetNumberOfComponents(); ++c)
    {
      difference = std::max(difference,
        std::abs(soupArray->GetComponent(i, c) - sphereArray->GetComponent(source[i], c)));
    }
  }
  return difference / scale;
}

//------------------------------------------------------------------------------
// Whether all copies of each sphere point hold bitwise identical tuples of `array`.
bool IdenticalAtCopies(vtkDataArray* array, const std::vector<vtkIdType>& source, vtkIdType n)
{
  if (!array)
  {
    return false;
  }
  std::vector<vtkIdType> first(n, -1);
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(source.size()); ++i)
  {
    vtkIdType& f = first[source[i]];
    f = f < 0 ? i : f;
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      if (array->GetComponent(i, c) != array->GetComponent(f, c))
      {
        return false;
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool TestSpectrum(vtkPolyData* sphere, vtkPolyData* soup)
{
  vtkDataArray* expected = sphere->GetFieldData()->GetArray("ManifoldHarmonicsEigenvalues");
  vtkDataArray* actual = soup->GetFieldData()->GetArray("ManifoldHarmonicsEigenvalues");
  bool ok = Check(expected && actual && actual->GetNumberOfTuples() == Harmonics &&
      expected->GetNumberOfTuples() == Harmonics,
    "both meshes have " + std::to_string(Harmonics) + " eigenvalues");
  if (!ok)
  {
    return false;
  }
  const double largest = expected->GetTuple1(Harmonics - 1);
  for (vtkIdType k = 0; k < Harmonics; ++k)
  {
    std::ostringstream what;
    what << "welded soup eigenvalue " << k << " " << actual->GetTuple1(k) << " equals the sphere's "
         << expected->GetTuple1(k);
    ok &=
      Check(std::abs(actual->GetTuple1(k) - expected->GetTuple1(k)) <= 1e-10 * largest, what.str());
  }
  return ok;
}

//------------------------------------------------------------------------------
// The soup's harmonics, read at one copy of each sphere point, span the sphere's harmonic
// space: S = H_sphere^T D H_soup is orthogonal (whole clusters: the harmonics may rotate within
// an eigenspace).
bool TestSubspace(vtkPolyData* sphere, vtkPolyData* soup, const std::vector<vtkIdType>& source)
{
  vtkDataArray* h = sphere->GetPointData()->GetArray("ManifoldHarmonics");
  vtkDataArray* d = sphere->GetPointData()->GetArray("ManifoldHarmonicsMass");
  vtkDataArray* g = soup->GetPointData()->GetArray("ManifoldHarmonics");
  if (!Check(h && d && g && g->GetNumberOfComponents() == Harmonics, "harmonics on both meshes"))
  {
    return false;
  }
  std::vector<vtkIdType> copy(sphere->GetNumberOfPoints(), -1);
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(source.size()); ++i)
  {
    copy[source[i]] = i;
  }
  std::vector<double> s(Harmonics * Harmonics, 0.0);
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    for (int k = 0; k < Harmonics; ++k)
    {
      for (int l = 0; l < Harmonics; ++l)
      {
        s[k * Harmonics + l] +=
          h->GetComponent(i, k) * d->GetTuple1(i) * g->GetComponent(copy[i], l);
      }
    }
  }
  double error = 0.0;
  for (int k = 0; k < Harmonics; ++k)
  {
    for (int l = 0; l < Harmonics; ++l)
    {
      double dot = 0.0;
      for (int j = 0; j < Harmonics; ++j)
      {
        dot += s[j * Harmonics + k] * s[j * Harmonics + l];
      }
      error = std::max(error, std::abs(dot - (k == l ? 1.0 : 0.0)));
    }
  }
  return Check(error < 1e-8,
    "the soup's harmonics span the sphere's (S^T S = I to " + std::to_string(error) + ")");
}

//------------------------------------------------------------------------------
bool TestOutputKeepsInput(vtkPolyData* input, vtkPolyData* output)
{
  bool ok = Check(output->GetNumberOfPoints() == input->GetNumberOfPoints(),
    "the output has the soup's " + std::to_string(input->GetNumberOfPoints()) + " points");
  ok &= Check(output->GetNumberOfPolys() == input->GetNumberOfPolys(),
    "the output has the soup's " + std::to_string(input->GetNumberOfPolys()) + " triangles");
  ok &= Check(
    output->GetPointData()->GetArray(TextureArray) == input->GetPointData()->GetArray(TextureArray),
    "the output keeps the soup's point arrays");
  return ok;
}

//------------------------------------------------------------------------------
// Each welded point counts once: the mass of the counted copies adds up to the sphere's area.
bool TestCountedOnce(vtkPolyData* sphere, vtkPolyData* soup)
{
  vtkDataArray* d = sphere->GetPointData()->GetArray("ManifoldHarmonicsMass");
  vtkDataArray* e = soup->GetPointData()->GetArray("ManifoldHarmonicsMass");
  if (!Check(d && e, "mass arrays on both meshes"))
  {
    return false;
  }
  double area = 0.0;
  double counted = 0.0;
  vtkIdType copies = 0;
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    area += d->GetTuple1(i);
  }
  for (vtkIdType i = 0; i < soup->GetNumberOfPoints(); ++i)
  {
    counted += CountedPoint(soup, i) * e->GetTuple1(i);
    copies += CountedPoint(soup, i) > 0.0 ? 1 : 0;
  }
  bool ok = Check(copies == sphere->GetNumberOfPoints(),
    "one counted copy per sphere point: " + std::to_string(copies) + " of " +
      std::to_string(sphere->GetNumberOfPoints()));
  ok &= Check(std::abs(counted - area) <= 1e-12 * area,
    "the counted mass " + std::to_string(counted) + " is the sphere's area " +
      std::to_string(area));
  return ok;
}

//------------------------------------------------------------------------------
// The transform counts each welded point once: the Gram matrix of the coefficients of the
// coordinates (independent of a rotation of the harmonics within an eigenspace) is the sphere's.
bool TestTransform(vtkPolyData* sphere, vtkPolyData* soup)
{
  std::vector<std::vector<double>> grams;
  for (vtkPolyData* mesh : { sphere, soup })
  {
    vtkNew<vtkManifoldHarmonicTransform> transform;
    transform->SetInputData(mesh);
    transform->Update();
    vtkDataArray* c = vtkPolyData::SafeDownCast(transform->GetOutputDataObject(0))
                        ->GetFieldData()
                        ->GetArray("Points_Coefficients");
    if (!Check(c && c->GetNumberOfComponents() == 3, "coefficients of the coordinates"))
    {
      return false;
    }
    std::vector<double> gram(9, 0.0);
    for (vtkIdType k = 0; k < c->GetNumberOfTuples(); ++k)
    {
      for (int a = 0; a < 3; ++a)
      {
        for (int b = 0; b < 3; ++b)
        {
          gram[3 * a + b] += c->GetComponent(k, a) * c->GetComponent(k, b);
        }
      }
    }
    grams.push_back(gram);
  }
  double difference = 0.0;
  double scale = 0.0;
  for (int e = 0; e < 9; ++e)
  {
    difference = std::max(difference, std::abs(grams[1][e] - grams[0][e]));
    scale = std::max(scale, std::abs(grams[0][e]));
  }
  return Check(difference <= 1e-10 * scale,
    "the soup's coefficients have the sphere's Gram matrix (difference " +
      std::to_string(difference / scale) + ")");
}

//------------------------------------------------------------------------------
// Filtering keeps the seams closed: each copy gets the sphere's filtered value at its point
// (smoothing, a low-pass spectral filter between the l = 2 and l = 3 clusters, heat kernel
// signature). Points are compared to 1e-9 of the radius.
bool TestDownstream(vtkPolyData* sphereBasis,
  vtkPolyData* soupBasis,
  vtkPolyData* sphere,
  vtkPolyData* soup,
  const std::vector<vtkIdType>& source)
{
  const vtkIdType n = sphere->GetNumberOfPoints();
  bool ok = true;
  std::vector<vtkSmartPointer<vtkPolyData>> smoothed;
  for (vtkPolyData* mesh : { sphere, soup })
  {
    vtkNew<vtkManifoldHarmonicSmoothing> smoothing;
    smoothing->SetNumberOfHarmonics(Harmonics);
    smoothing->SetInputData(mesh);
    smoothing->Update();
    smoothed.push_back(vtkPolyData::SafeDownCast(smoothing->GetOutputDataObject(0)));
  }
  ok &= Check(smoothed[1]->GetNumberOfPoints() == soup->GetNumberOfPoints() &&
      IdenticalAtCopies(smoothed[1]->GetPoints()->GetData(), source, n),
    "smoothing gives every copy of a point the same coordinates");
  ok &= Check(
    DifferenceAtCopies(
      smoothed[1]->GetPoints()->GetData(), smoothed[0]->GetPoints()->GetData(), source, 1.0) < 1e-9,
    "smoothing the soup moves each copy where smoothing the sphere moves its point");

  std::vector<vtkSmartPointer<vtkPolyData>> filtered;
  for (vtkPolyData* mesh : { sphereBasis, soupBasis })
  {
    vtkNew<vtkManifoldHarmonicTransform> transform;
    transform->SetInputData(mesh);
    vtkNew<vtkSpectralFilter> filter;
    filter->SetInputConnection(transform->GetOutputPort());
    filter->ReplaceInputOn();
    // omega = sqrt(l (l + 1)) on the unit sphere: 2.45 for l = 2, 3.46 for l = 3.
    filter->SetCutoffUnitsToAbsoluteFrequency();
    filter->SetCutoff(3.0);
    filter->Update();
    filtered.push_back(vtkPolyData::SafeDownCast(filter->GetOutputDataObject(0)));
  }
  ok &= Check(IdenticalAtCopies(filtered[1]->GetPoints()->GetData(), source, n),
    "the spectral filter (re-injection on) gives every copy of a point the same coordinates");
  ok &= Check(
    DifferenceAtCopies(
      filtered[1]->GetPoints()->GetData(), filtered[0]->GetPoints()->GetData(), source, 1.0) < 1e-9,
    "the spectral filter moves each copy where it moves the sphere's point");

  std::vector<vtkDataArray*> signatures;
  std::vector<vtkSmartPointer<vtkSpectralDescriptors>> descriptors;
  for (vtkPolyData* mesh : { sphereBasis, soupBasis })
  {
    auto descriptor = vtkSmartPointer<vtkSpectralDescriptors>::New();
    descriptor->SetInputData(mesh);
    descriptor->Update();
    descriptors.push_back(descriptor);
    signatures.push_back(vtkDataSet::SafeDownCast(descriptor->GetOutputDataObject(0))
                           ->GetPointData()
                           ->GetArray(vtkSpectralDescriptors::HeatKernelSignatureArrayName()));
  }
  ok &= Check(signatures[0] && signatures[1] &&
      DifferenceAtCopies(signatures[1], signatures[0], source, signatures[0]->GetRange(0)[1]) <
        1e-9,
    "the heat kernel signature of each copy is the sphere's at its point");
  return ok;
}

//------------------------------------------------------------------------------
// SeamTolerance: every copy but the first of each point moved by half of 1e-4 of the diagonal
// (in directions that vary from copy to copy) is welded with SeamTolerance 1e-4, onto the first
// copy's coordinates: the sphere's spectrum; the default 1e-12 keeps the copies apart.
bool TestTolerance(vtkPolyData* sphereBasis,
  vtkPolyData* soup,
  const std::vector<vtkIdType>& source)
{
  auto moved = vtkSmartPointer<vtkPolyData>::New();
  moved->DeepCopy(soup);
  const double step = 0.5e-4 * soup->GetLength() / std::sqrt(3.0);
  std::vector<bool> seen(sphereBasis->GetNumberOfPoints(), false);
  for (vtkIdType i = 0; i < moved->GetNumberOfPoints(); ++i)
  {
    if (seen[source[i]])
    {
      double x[3];
      moved->GetPoint(i, x);
      for (int d = 0; d < 3; ++d)
      {
        x[d] += ((i >> d) & 1 ? step : -step) * (d == 2 && i % 3 == 0 ? 0.5 : 1.0);
      }
      moved->GetPoints()->SetPoint(i, x);
    }
    seen[source[i]] = true;
  }
  std::string warnings;
  bool ok = TestSpectrum(sphereBasis, Basis(moved, true, &warnings, 1e-4));
  ok &= Check(warnings.find("connected components") == std::string::npos,
    "copies 0.5e-4 of the diagonal apart are one point with SeamTolerance 1e-4: " + warnings);
  ok &= Check(warnings.find("seams left open") == std::string::npos,
    "welded copies are reported as open seams: " + warnings);
  Basis(moved, true, &warnings);
  ok &= Check(warnings.find("connected components") != std::string::npos,
    "copies 0.5e-4 of the diagonal apart stay apart with the default SeamTolerance");
  // They are reported as seams left open, with a tolerance that welds them.
  const std::string above = "raise SeamTolerance above ";
  const std::size_t at = warnings.find(above);
  ok &= Check(warnings.find("seams left open") != std::string::npos && at != std::string::npos,
    "copies 0.5e-4 of the diagonal apart are not reported as seams left open: " + warnings);
  if (at != std::string::npos)
  {
    const double gap = std::stod(warnings.substr(at + above.size()));
    ok &=
      Check(gap > 0.25e-4 && gap < 0.51e-4, "the largest gap reported is " + std::to_string(gap));
    ok &= TestSpectrum(sphereBasis, Basis(moved, true, &warnings, 1.01 * gap));
  }
  return ok;
}

//------------------------------------------------------------------------------
// WeldSeams off: today's behaviour, one component per triangle, with the warning.
bool TestKeepSeamsOpen(vtkPolyData* soup)
{
  std::string warnings;
  vtkSmartPointer<vtkPolyData> open = Basis(soup, false, &warnings);
  vtkDataArray* lambda = open->GetFieldData()->GetArray("ManifoldHarmonicsEigenvalues");
  bool ok = Check(lambda && lambda->GetNumberOfTuples() > 0, "eigenvalues with WeldSeams off");
  double largest = 0.0;
  for (vtkIdType k = 0; lambda && k < lambda->GetNumberOfTuples(); ++k)
  {
    largest = std::max(largest, std::abs(lambda->GetTuple1(k)));
  }
  ok &= Check(largest < 1e-8,
    "WeldSeams off: every eigenvalue is a component's zero (largest " + std::to_string(largest) +
      ")");
  const std::string components = std::to_string(soup->GetNumberOfPolys()) + " connected components";
  ok &= Check(warnings.find(components) != std::string::npos,
    "WeldSeams off: a warning names the " + components);
  ok &= Check(!open->GetPointData()->GetArray(vtkDataSetAttributes::GhostArrayName()),
    "WeldSeams off: no point is flagged a duplicate");
  ok &= Check(warnings.find("seams left open") == std::string::npos,
    "WeldSeams off: seams kept open on purpose are reported: " + warnings);
  return ok;
}

//------------------------------------------------------------------------------
// The smoothing passes WeldSeams on to its basis: off, the soup's 672 components leave only
// constant harmonics, an error.
bool TestSmoothingSwitch(vtkPolyData* soup)
{
  vtkNew<vtkManifoldHarmonicSmoothing> smoothing;
  const ManifoldHarmonicsTest::Messages messages(smoothing);
  smoothing->SetNumberOfHarmonics(Harmonics);
  smoothing->WeldSeamsOff();
  smoothing->SetInputData(soup);
  smoothing->Update();
  return Check(messages->GetErrorMessage().find("are all constant") != std::string::npos,
    "smoothing with WeldSeams off: only constant harmonics on the soup, an error");
}

//------------------------------------------------------------------------------
bool TestPrintSelf()
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  vtkNew<vtkManifoldHarmonicSmoothing> smoothing;
  std::ostringstream basisText;
  std::ostringstream smoothingText;
  basis->Print(basisText);
  smoothing->Print(smoothingText);
  bool ok = Check(basisText.str().find("WeldSeams: On") != std::string::npos &&
      basisText.str().find("SeamTolerance: 1e-12") != std::string::npos,
    "the basis prints WeldSeams and SeamTolerance");
  ok &= Check(smoothingText.str().find("WeldSeams: On") != std::string::npos &&
      smoothingText.str().find("SeamTolerance: 1e-12") != std::string::npos,
    "the smoothing prints WeldSeams and SeamTolerance");
  return ok;
}

//------------------------------------------------------------------------------
// What the cases compare: the sphere, its soup (source: the sphere's point of each soup point),
// their bases with WeldSeams on, and the warnings of the soup's basis.
struct SoupOfSphere
{
  vtkSmartPointer<vtkPolyData> Sphere = ManifoldHarmonicsTest::UnitSphere(24, 16);
  std::vector<vtkIdType> Source;
  vtkSmartPointer<vtkPolyData> Soup = MakeSoup(this->Sphere, this->Source);
  vtkSmartPointer<vtkPolyData> SphereBasis = Basis(this->Sphere, true);
  std::string Warnings;
  vtkSmartPointer<vtkPolyData> SoupBasis = Basis(this->Soup, true, &this->Warnings);
};
} // anonymous namespace

//------------------------------------------------------------------------------
int TestWeldSeams(int argc, char* argv[])
{
  using Soup = SoupOfSphere;
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "Spectrum",
        [] {
          const Soup s;
          bool ok = TestSpectrum(s.SphereBasis, s.SoupBasis);
          ok &= Check(s.Warnings.find("connected components") == std::string::npos,
            "the welded soup is one component (no warning about components): " + s.Warnings);
          return ok;
        } },
      { "Subspace",
        [] {
          const Soup s;
          return TestSubspace(s.SphereBasis, s.SoupBasis, s.Source);
        } },
      { "OutputKeepsInput",
        [] {
          const Soup s;
          return TestOutputKeepsInput(s.Soup, s.SoupBasis);
        } },
      { "CopiesIdentical",
        [] {
          const Soup s;
          bool ok =
            Check(IdenticalAtCopies(s.SoupBasis->GetPointData()->GetArray("ManifoldHarmonics"),
                    s.Source,
                    s.Sphere->GetNumberOfPoints()),
              "every copy of a point has the same harmonics");
          ok &=
            Check(IdenticalAtCopies(s.SoupBasis->GetPointData()->GetArray("ManifoldHarmonicsMass"),
                    s.Source,
                    s.Sphere->GetNumberOfPoints()),
              "every copy of a point has the same mass");
          return ok;
        } },
      { "CountedOnce",
        [] {
          const Soup s;
          return TestCountedOnce(s.SphereBasis, s.SoupBasis);
        } },
      { "Transform",
        [] {
          const Soup s;
          return TestTransform(s.SphereBasis, s.SoupBasis);
        } },
      { "Downstream",
        [] {
          const Soup s;
          return TestDownstream(s.SphereBasis, s.SoupBasis, s.Sphere, s.Soup, s.Source);
        } },
      { "Tolerance",
        [] {
          const Soup s;
          return TestTolerance(s.SphereBasis, s.Soup, s.Source);
        } },
      { "KeepSeamsOpen", [] { return TestKeepSeamsOpen(SoupOfSphere().Soup); } },
      { "SmoothingSwitch", [] { return TestSmoothingSwitch(SoupOfSphere().Soup); } },
      { "PrintSelf", TestPrintSelf },
    });
}
