// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Checks of vtkSpectralFilter: identity transfer, exact round trip with m = n, a float basis
// against a double one, linearity, a low-pass of a noisy sphere against
// vtkWindowedSincPolyDataFilter, colour and normal arrays, heat diffusion limits, re-execution of
// the filter alone when its parameters change, the errors and warnings of inputs that lack
// the basis or the coefficients, and the cutoff units: the default cutoff at any scale, relative
// units against the absolute cutoffs they name, negative cutoffs, cutoffs outside the spectrum.

#include "vtkSpectralFilter.h"

#include "ManifoldHarmonicsTestUtilities.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArraySelection.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkLinearSubdivisionFilter.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkMassProperties.h"
#include "vtkMath.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkPlatonicSolidSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTable.h"
#include "vtkTestErrorObserver.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowedSincPolyDataFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using ManifoldHarmonicsTest::AbortAtFirstProgress;
using ManifoldHarmonicsTest::Check;
using ManifoldHarmonicsTest::LinesOnly;
using ManifoldHarmonicsTest::RelativeDifference;

//------------------------------------------------------------------------------
// Counts the executions of an algorithm (its EndEvent).
class ExecutionCounter : public vtkCommand
{
public:
  vtkTypeMacro(ExecutionCounter, vtkCommand);
  static ExecutionCounter* New() { return new ExecutionCounter; }
  void Execute(vtkObject*, unsigned long, void*) override { ++this->Count; }
  int Count = 0;
};

//------------------------------------------------------------------------------
// Basis -> transform -> spectral filter on one mesh.
struct Pipeline
{
  vtkNew<vtkManifoldHarmonicBasis> Basis;
  vtkNew<vtkManifoldHarmonicTransform> Transform;
  vtkNew<vtkSpectralFilter> Filter;

  Pipeline(vtkPolyData* mesh, int harmonics, const std::vector<std::string>& arrays)
  {
    this->Basis->SetInputData(mesh);
    this->Basis->SetNumberOfHarmonics(harmonics);
    this->Transform->SetInputConnection(this->Basis->GetOutputPort());
    for (const auto& name : arrays)
    {
      this->Transform->GetPointDataArraySelection()->EnableArray(name.c_str());
    }
    this->Filter->SetInputConnection(this->Transform->GetOutputPort());
    // The cutoffs of these tests are frequencies (radians per unit length).
    this->Filter->SetCutoffUnitsToAbsoluteFrequency();
  }
  vtkPolyData* Run()
  {
    this->Filter->Update();
    return this->Filter->GetPolyDataOutput();
  }
  // Gain 1 at every frequency.
  void SetIdentity()
  {
    this->Filter->SetFilterKindToCustom();
    this->Filter->RemoveAllControlPoints();
    this->Filter->AddControlPoint(0.0, 1.0);
    this->Filter->AddControlPoint(1.0, 1.0);
  }
};

//------------------------------------------------------------------------------
// A sphere of radius 1 with double points and the arrays A (noise), B (smooth), Sum = A + B,
// Colors (unsigned char RGB) and Normals (float).
vtkSmartPointer<vtkPolyData> MakeSphere(int theta, int phi)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1.0);
  sphere->SetThetaResolution(theta);
  sphere->SetPhiResolution(phi);
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputConnection(sphere->GetOutputPort());
  normals->SplittingOff();
  normals->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(normals->GetOutput());

  const vtkIdType n = mesh->GetNumberOfPoints();
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(7);
  vtkNew<vtkDoubleArray> a;
  a->SetName("A");
  a->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> b;
  b->SetName("B");
  b->SetNumberOfTuples(n);
  vtkNew<vtkDoubleArray> sum;
  sum->SetName("Sum");
  sum->SetNumberOfTuples(n);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    a->SetValue(i, random->GetNextRangeValue(-1.0, 1.0));
    b->SetValue(i, 3.0 * p[2] * p[2] - 1.0 + p[0]);
    sum->SetValue(i, a->GetValue(i) + b->GetValue(i));
    for (int c = 0; c < 3; ++c)
    {
      colors->SetTypedComponent(i, c, static_cast<unsigned char>(127.5 * (p[c] + 1.0)));
    }
  }
  mesh->GetPointData()->AddArray(a);
  mesh->GetPointData()->AddArray(b);
  mesh->GetPointData()->AddArray(sum);
  mesh->GetPointData()->AddArray(colors);
  return mesh;
}

//------------------------------------------------------------------------------
bool AllFinite(vtkDataArray* array)
{
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      if (!std::isfinite(array->GetComponent(i, c)))
      {
        return false;
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
// Gain 1 everywhere with re-injection returns every signal, whatever m.
bool TestIdentity()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 40, { "A", "Colors" });
  pipeline.SetIdentity();
  vtkPolyData* output = pipeline.Run();
  const double points =
    RelativeDifference(output->GetPoints()->GetData(), mesh->GetPoints()->GetData());
  const double a = RelativeDifference(
    output->GetPointData()->GetArray("A_Filtered"), mesh->GetPointData()->GetArray("A"));
  const double colors = RelativeDifference(
    output->GetPointData()->GetArray("Colors_Filtered"), mesh->GetPointData()->GetArray("Colors"));
  std::cout << "Identity (m = 40 of " << mesh->GetNumberOfPoints() << ", re-injection): points "
            << points << ", A " << a << ", Colors " << colors << std::endl;
  bool ok = Check(points < 1e-10, "identity changes the points");
  ok &= Check(a < 1e-10, "identity changes A");
  ok &= Check(colors == 0.0, "identity changes the colours");

  // Without re-injection the same transfer is the projection onto the m harmonics.
  pipeline.Filter->ReinjectHighFrequenciesOff();
  const double projected = RelativeDifference(
    pipeline.Run()->GetPointData()->GetArray("A_Filtered"), mesh->GetPointData()->GetArray("A"));
  std::cout << "Projection of the noise A onto 40 harmonics differs by " << projected << std::endl;
  ok &= Check(projected > 0.1, "without re-injection the noise should be mostly removed");
  return ok;
}

//------------------------------------------------------------------------------
// With m = n the basis is complete: transform then inverse is exact without re-injection.
bool TestCompleteBasis()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(8, 8);
  const int n = static_cast<int>(mesh->GetNumberOfPoints());
  Pipeline pipeline(mesh, n, { "A", "Normals" });
  pipeline.SetIdentity();
  pipeline.Filter->ReinjectHighFrequenciesOff();
  vtkPolyData* output = pipeline.Run();
  const double points =
    RelativeDifference(output->GetPoints()->GetData(), mesh->GetPoints()->GetData());
  const double a = RelativeDifference(
    output->GetPointData()->GetArray("A_Filtered"), mesh->GetPointData()->GetArray("A"));
  const double normals = RelativeDifference(output->GetPointData()->GetArray("Normals_Filtered"),
    mesh->GetPointData()->GetArray("Normals"));
  std::cout << "Complete basis (m = n = " << n << "), no re-injection: points " << points << ", A "
            << a << ", Normals (float) " << normals << std::endl;
  bool ok = Check(points < 1e-10, "round trip with m = n changes the points");
  ok &= Check(a < 1e-10, "round trip with m = n changes A");
  ok &= Check(normals < 1e-6, "round trip with m = n changes the float normals");
  return ok;
}

//------------------------------------------------------------------------------
// BasisPrecision Float: the harmonics are a vtkFloatArray, and the coefficients and the
// filtered points and arrays equal those of the double basis to float precision.
bool TestFloatBasis()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline doubles(mesh, 60, { "A", "Normals" });
  Pipeline floats(mesh, 60, { "A", "Normals" });
  floats.Basis->SetBasisPrecisionToFloat();
  for (Pipeline* pipeline : { &doubles, &floats })
  {
    pipeline->Filter->SetFilterKindToLowPass();
    pipeline->Filter->SetCutoff(4.0);
  }
  vtkPolyData* reference = doubles.Run();
  ManifoldHarmonicsTest::Messages errors(floats.Transform);
  errors.Observe(floats.Filter);
  vtkPolyData* output = floats.Run();
  bool ok = Check(!errors->GetError(), "float basis: " + errors->GetErrorMessage());
  const char* name = vtkManifoldHarmonicBasis::HarmonicsArrayName();
  vtkDataArray* floatHarmonics = floats.Basis->GetOutput()->GetPointData()->GetArray(name);
  vtkDataArray* doubleHarmonics = doubles.Basis->GetOutput()->GetPointData()->GetArray(name);
  ok &= Check(vtkFloatArray::SafeDownCast(floatHarmonics) != nullptr,
    "BasisPrecision Float must write the harmonics as a vtkFloatArray");
  ok &= Check(vtkDoubleArray::SafeDownCast(doubleHarmonics) != nullptr,
    "BasisPrecision Double must write the harmonics as a vtkDoubleArray");
  if (!ok)
  {
    return false;
  }
  double worst = 0.0;
  for (const char* coefficients :
    { "Points_Coefficients", "A_Coefficients", "Normals_Coefficients" })
  {
    const double difference =
      RelativeDifference(floats.Transform->GetOutput()->GetFieldData()->GetArray(coefficients),
        doubles.Transform->GetOutput()->GetFieldData()->GetArray(coefficients));
    std::cout << "Float basis: " << coefficients << " differ by " << difference << std::endl;
    worst = std::max(worst, difference);
  }
  const double points =
    RelativeDifference(output->GetPoints()->GetData(), reference->GetPoints()->GetData());
  const double a = RelativeDifference(output->GetPointData()->GetArray("A_Filtered"),
    reference->GetPointData()->GetArray("A_Filtered"));
  std::cout << "Float basis: filtered points differ by " << points << ", A by " << a << std::endl;
  ok &= Check(worst < 1e-5, "float basis: coefficients differ by more than 1e-5");
  ok &= Check(points < 1e-5 && a < 1e-5, "float basis: filtered signals differ by more than 1e-5");
  return ok;
}

//------------------------------------------------------------------------------
bool TestLinearity()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 40, { "A", "B", "Sum" });
  pipeline.Filter->SetFilterKindToLowPass();
  pipeline.Filter->SetCutoff(3.0);
  vtkPointData* pd = pipeline.Run()->GetPointData();
  vtkNew<vtkDoubleArray> sumOfFiltered;
  sumOfFiltered->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    sumOfFiltered->SetValue(i,
      pd->GetArray("A_Filtered")->GetComponent(i, 0) +
        pd->GetArray("B_Filtered")->GetComponent(i, 0));
  }
  const double difference = RelativeDifference(pd->GetArray("Sum_Filtered"), sumOfFiltered);
  std::cout << "Linearity: |F(A+B) - F(A) - F(B)| / |F(A+B)| = " << difference << std::endl;
  return Check(difference < 1e-10, "the filter is not linear");
}

//------------------------------------------------------------------------------
double RadialRMS(vtkPolyData* mesh)
{
  double sum = 0.0;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    sum += std::pow(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - 1.0, 2);
  }
  return std::sqrt(sum / static_cast<double>(mesh->GetNumberOfPoints()));
}

//------------------------------------------------------------------------------
double Volume(vtkPolyData* mesh)
{
  vtkNew<vtkMassProperties> mass;
  mass->SetInputData(mesh);
  mass->Update();
  return mass->GetVolume();
}

//------------------------------------------------------------------------------
// The windowed-sinc smoothing (over a grid of iterations and pass bands) whose radial error is
// closest to `target`.
vtkSmartPointer<vtkPolyData> MatchedWindowedSinc(vtkPolyData* noisy,
  double target,
  int& bestIterations,
  double& bestPassBand)
{
  vtkSmartPointer<vtkPolyData> best;
  double bestDistance = VTK_DOUBLE_MAX;
  for (int iterations : { 10, 20, 50, 100 })
  {
    for (double passBand : { 0.5, 0.2, 0.1, 0.05, 0.02, 0.01 })
    {
      vtkNew<vtkWindowedSincPolyDataFilter> sinc;
      sinc->SetInputData(noisy);
      sinc->SetNumberOfIterations(iterations);
      sinc->SetPassBand(passBand);
      sinc->NormalizeCoordinatesOn();
      sinc->Update();
      const double distance = std::abs(RadialRMS(sinc->GetOutput()) - target);
      if (distance < bestDistance)
      {
        bestDistance = distance;
        best = sinc->GetOutput();
        bestIterations = iterations;
        bestPassBand = passBand;
      }
    }
  }
  return best;
}

//------------------------------------------------------------------------------
// Unit icosphere: the icosahedron split `levels` times, points projected onto the sphere.
vtkSmartPointer<vtkPolyData> MakeIcosphere(int levels)
{
  vtkNew<vtkPlatonicSolidSource> icosahedron;
  icosahedron->SetSolidTypeToIcosahedron();
  icosahedron->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  vtkNew<vtkLinearSubdivisionFilter> subdivide;
  subdivide->SetInputConnection(icosahedron->GetOutputPort());
  subdivide->SetNumberOfSubdivisions(levels);
  subdivide->Update();
  auto sphere = vtkSmartPointer<vtkPolyData>::New();
  sphere->DeepCopy(subdivide->GetOutput());
  sphere->GetPointData()->Initialize();
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    double p[3];
    sphere->GetPoint(i, p);
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    sphere->GetPoints()->SetPoint(i, p[0] / r, p[1] / r, p[2] / r);
  }
  return sphere;
}

//------------------------------------------------------------------------------
// Low-pass of a noisy unit sphere (radial noise, 1% of the radius RMS), against windowed sinc
// tuned to the same noise reduction.
bool TestNoisySphere()
{
  vtkSmartPointer<vtkPolyData> clean = MakeIcosphere(4);
  auto noisy = vtkSmartPointer<vtkPolyData>::New();
  noisy->DeepCopy(clean);
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(12345);
  const double amplitude = 0.01 * std::sqrt(3.0); // uniform in [-a, a]: RMS a / sqrt(3)
  for (vtkIdType i = 0; i < noisy->GetNumberOfPoints(); ++i)
  {
    double p[3];
    noisy->GetPoint(i, p);
    const double scale = 1.0 + random->GetNextRangeValue(-amplitude, amplitude);
    noisy->GetPoints()->SetPoint(i, scale * p[0], scale * p[1], scale * p[2]);
  }

  Pipeline pipeline(noisy, 100, {});
  pipeline.Filter->SetFilterKindToLowPass();
  pipeline.Filter->SetCutoff(6.0);
  vtkPolyData* spectral = pipeline.Run();

  const double noisyRMS = RadialRMS(noisy);
  const double spectralRMS = RadialRMS(spectral);
  int iterations = 0;
  double passBand = 0.0;
  vtkSmartPointer<vtkPolyData> sinc = MatchedWindowedSinc(noisy, spectralRMS, iterations, passBand);
  const double sincRMS = RadialRMS(sinc);
  const double cleanVolume = Volume(clean);
  const double noisyVolume = Volume(noisy);
  const double spectralChange = (Volume(spectral) - noisyVolume) / noisyVolume;
  const double sincChange = (Volume(sinc) - noisyVolume) / noisyVolume;
  std::cout << "Noisy unit sphere, " << noisy->GetNumberOfPoints() << " points, 100 harmonics, "
            << "low-pass cutoff 6:\n"
            << "  radial RMS error: noisy " << noisyRMS << ", spectral " << spectralRMS << " ("
            << noisyRMS / spectralRMS << "x lower), windowed sinc closest to it (pass band "
            << passBand << ", " << iterations << " iterations) " << sincRMS << " ("
            << noisyRMS / sincRMS << "x lower)\n"
            << "  volume change vs. noisy input: spectral " << 100.0 * spectralChange
            << "%, windowed sinc " << 100.0 * sincChange << "%\n"
            << "  volume vs. clean sphere mesh: noisy "
            << 100.0 * (noisyVolume - cleanVolume) / cleanVolume << "%, spectral "
            << 100.0 * (Volume(spectral) - cleanVolume) / cleanVolume << "%, windowed sinc "
            << 100.0 * (Volume(sinc) - cleanVolume) / cleanVolume << "%" << std::endl;
  // The other way round: the low-pass cutoff whose noise reduction is closest to windowed sinc's.
  double matchedCutoff = 0.0;
  double matchedChange = 0.0;
  double matchedRMS = VTK_DOUBLE_MAX;
  for (double cutoff : { 6.0, 7.0, 8.0, 9.0, 10.0 })
  {
    pipeline.Filter->SetCutoff(cutoff);
    vtkPolyData* output = pipeline.Run();
    if (std::abs(RadialRMS(output) - sincRMS) < std::abs(matchedRMS - sincRMS))
    {
      matchedRMS = RadialRMS(output);
      matchedCutoff = cutoff;
      matchedChange = (Volume(output) - noisyVolume) / noisyVolume;
    }
  }
  std::cout << "  low-pass closest to windowed sinc's noise level: cutoff " << matchedCutoff
            << ", radial RMS " << matchedRMS << " (" << noisyRMS / matchedRMS
            << "x lower), volume change " << 100.0 * matchedChange << "%" << std::endl;
  bool ok = Check(noisyRMS / spectralRMS >= 5.0, "low-pass reduces the noise less than 5x");
  ok &= Check(std::abs(sincChange) > std::abs(matchedChange),
    "windowed sinc changes the volume less than the low-pass of the same noise level");
  ok &= Check(std::abs(spectralChange) < 0.005, "low-pass changes the volume by 0.5% or more");
  ok &= Check(std::abs(sincChange) > std::abs(spectralChange),
    "windowed sinc at the same noise reduction changes the volume less than the low-pass");
  return ok;
}

//------------------------------------------------------------------------------
// max | |v_i| - 1 | over the tuples of a 3-component array.
double MaxUnitDeviation(vtkDataArray* vectors)
{
  double worst = 0.0;
  for (vtkIdType i = 0; i < vectors->GetNumberOfTuples(); ++i)
  {
    worst = std::max(worst, std::abs(vtkMath::Norm(vectors->GetTuple3(i)) - 1.0));
  }
  return worst;
}

//------------------------------------------------------------------------------
// Colour (unsigned char RGB) and normal (float) arrays keep their type and shape.
bool TestColorsAndNormals()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 40, { "Colors", "Normals" });
  pipeline.Filter->SetFilterKindToEnhancement();
  pipeline.Filter->SetCutoff(3.0);
  pipeline.Filter->SetGain(3.0);
  vtkPointData* pd = pipeline.Run()->GetPointData();
  const vtkIdType n = mesh->GetNumberOfPoints();
  vtkDataArray* colors = pd->GetArray("Colors_Filtered");
  vtkDataArray* normals = pd->GetArray("Normals_Filtered");
  bool ok = Check(vtkUnsignedCharArray::SafeDownCast(colors) && colors->GetNumberOfTuples() == n &&
      colors->GetNumberOfComponents() == 3,
    "Colors_Filtered is not an n x 3 unsigned char array");
  ok &= Check(vtkFloatArray::SafeDownCast(normals) && normals->GetNumberOfTuples() == n &&
      normals->GetNumberOfComponents() == 3 && AllFinite(normals),
    "Normals_Filtered is not a finite n x 3 float array");
  ok &= Check(pd->GetNormals() == mesh->GetPointData()->GetNormals(),
    "the input normals are not kept when ReplaceInput is off");
  // Filtered normals are normals: unit length with ReplaceInput off as well as on.
  ok &= Check(normals && MaxUnitDeviation(normals) < 1e-6,
    "Normals_Filtered (ReplaceInput off) are not unit vectors");

  // Enhancement overshoots the colour range: the values are clamped, not wrapped.
  pipeline.Filter->ReplaceInputOn();
  pd = pipeline.Run()->GetPointData();
  colors = pd->GetArray("Colors");
  ok &= Check(vtkUnsignedCharArray::SafeDownCast(colors) &&
      colors != mesh->GetPointData()->GetArray("Colors"),
    "ReplaceInput does not replace the colours with an unsigned char array");
  ok &= Check(!pd->GetArray("Colors_Filtered"), "ReplaceInput still adds Colors_Filtered");
  ok &= Check(vtkFloatArray::SafeDownCast(pd->GetNormals()) &&
      pd->GetNormals() == pd->GetArray("Normals") &&
      pd->GetNormals() != mesh->GetPointData()->GetNormals(),
    "ReplaceInput does not keep the filtered normals as the active normals");
  ok &= Check(pd->GetNormals() && MaxUnitDeviation(pd->GetNormals()) < 1e-6,
    "replaced active normals are not unit vectors");
  double range[2];
  colors->GetRange(range, -1);
  std::cout << "Enhanced colours (gain 3 above cutoff 3): magnitude range [" << range[0] << ", "
            << range[1] << "]" << std::endl;
  return ok;
}

//------------------------------------------------------------------------------
// Mass-weighted mean of each component of `array` on the basis output.
std::vector<double> MassWeightedMean(vtkPolyData* basis, vtkDataArray* array)
{
  vtkDataArray* mass = basis->GetPointData()->GetArray(vtkManifoldHarmonicBasis::MassArrayName());
  std::vector<double> mean(array->GetNumberOfComponents(), 0.0);
  double total = 0.0;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    total += mass->GetComponent(i, 0);
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      mean[c] += mass->GetComponent(i, 0) * array->GetComponent(i, c);
    }
  }
  for (double& value : mean)
  {
    value /= total;
  }
  return mean;
}

//------------------------------------------------------------------------------
// Largest distance of the values of `array` to `mean`.
double DistanceToMean(vtkDataArray* array, const std::vector<double>& mean)
{
  double distance = 0.0;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < array->GetNumberOfComponents(); ++c)
    {
      distance = std::max(distance, std::abs(array->GetComponent(i, c) - mean[c]));
    }
  }
  return distance;
}

//------------------------------------------------------------------------------
bool TestHeatDiffusion()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 40, { "A", "B" });
  pipeline.Filter->SetFilterKindToHeatDiffusion();
  bool ok = true;
  for (double time : { 0.0, 1e-14 })
  {
    pipeline.Filter->SetTime(time);
    vtkPolyData* output = pipeline.Run();
    const double points =
      RelativeDifference(output->GetPoints()->GetData(), mesh->GetPoints()->GetData());
    const double a = RelativeDifference(
      output->GetPointData()->GetArray("A_Filtered"), mesh->GetPointData()->GetArray("A"));
    std::cout << "Heat diffusion t = " << time << ": points " << points << ", A " << a << std::endl;
    ok &= Check(points < 1e-10 && a < 1e-10, "heat diffusion with t -> 0 is not the identity");
  }

  pipeline.Filter->SetTime(1e3);
  vtkPolyData* output = pipeline.Run();
  vtkPolyData* basis = pipeline.Basis->GetPolyDataOutput();
  const char* names[] = { "A", "B" };
  for (const char* name : names)
  {
    vtkDataArray* input = mesh->GetPointData()->GetArray(name);
    const double distance =
      DistanceToMean(output->GetPointData()->GetArray((std::string(name) + "_Filtered").c_str()),
        MassWeightedMean(basis, input));
    std::cout << "Heat diffusion t = 1000: " << name << " within " << distance
              << " of its mass-weighted mean" << std::endl;
    ok &= Check(distance < 1e-8, std::string(name) + " does not tend to its mean");
  }
  const double centroid = DistanceToMean(
    output->GetPoints()->GetData(), MassWeightedMean(basis, mesh->GetPoints()->GetData()));
  std::cout << "Heat diffusion t = 1000: points within " << centroid << " of the centroid"
            << std::endl;
  ok &= Check(centroid < 1e-8, "points do not tend to the centroid");
  return ok;
}

//------------------------------------------------------------------------------
// The slider ranges follow the basis of the last execution: [0, sqrt(lambda_{m-1})] and
// [0, 4 / lambda_1] for a basis with non-constant harmonics; for a basis of the constant harmonic
// alone (its eigenvalue at round-off, of either sign), the ranges of an unexecuted filter, not
// the previous run's nor ranges built from round-off.
bool TestSliderRanges()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 10, {});
  bool ok = true;
  pipeline.Run();
  vtkDataArray* lambda = pipeline.Basis->GetOutput()->GetFieldData()->GetArray(
    vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  const double* frequency = pipeline.Filter->GetFrequencyRange();
  const double* time = pipeline.Filter->GetTimeRange();
  std::cout << "Slider ranges, m = 10: [" << frequency[0] << ", " << frequency[1] << "], ["
            << time[0] << ", " << time[1] << "]" << std::endl;
  ok &= Check(frequency[0] == 0.0 &&
      std::abs(frequency[1] - std::sqrt(lambda->GetTuple1(9))) < 1e-12 * frequency[1] &&
      time[0] == 0.0 && std::abs(time[1] - 4.0 / lambda->GetTuple1(1)) < 1e-12 * time[1],
    "slider ranges of a basis of 10 harmonics");
  pipeline.Basis->SetNumberOfHarmonics(1);
  pipeline.Run();
  frequency = pipeline.Filter->GetFrequencyRange();
  time = pipeline.Filter->GetTimeRange();
  std::cout << "Slider ranges, m = 1 (lambda_0 = "
            << pipeline.Basis->GetOutput()
                 ->GetFieldData()
                 ->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName())
                 ->GetTuple1(0)
            << "): [" << frequency[0] << ", " << frequency[1] << "], [" << time[0] << ", "
            << time[1] << "]" << std::endl;
  ok &= Check(frequency[0] == 0.0 && frequency[1] == 2.0 && time[0] == 0.0 && time[1] == 1.0,
    "slider ranges of a basis of the constant harmonic alone");
  return ok;
}

//------------------------------------------------------------------------------
// The output's coefficients describe its signals, so filters chain: without re-injection, heat
// diffusion for t1 then t2 equals heat diffusion for t1 + t2.
bool TestChaining()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 40, { "A" });
  pipeline.Filter->SetFilterKindToHeatDiffusion();
  pipeline.Filter->SetTime(0.01);
  pipeline.Filter->ReinjectHighFrequenciesOff();
  pipeline.Filter->ReplaceInputOn();
  vtkNew<vtkSpectralFilter> second;
  second->SetInputConnection(pipeline.Filter->GetOutputPort());
  second->SetFilterKindToHeatDiffusion();
  second->SetCutoffUnitsToAbsoluteFrequency();
  second->SetTime(0.02);
  second->ReinjectHighFrequenciesOff();
  second->ReplaceInputOn();
  second->Update();
  vtkNew<vtkPolyData> twice;
  twice->DeepCopy(second->GetOutput());
  pipeline.Filter->SetTime(0.03);
  vtkPolyData* once = pipeline.Run();
  const double points =
    RelativeDifference(twice->GetPoints()->GetData(), once->GetPoints()->GetData());
  const double a =
    RelativeDifference(twice->GetPointData()->GetArray("A"), once->GetPointData()->GetArray("A"));
  std::cout << "Heat diffusion 0.01 then 0.02 vs. 0.03: points " << points << ", A " << a
            << std::endl;
  return Check(points < 1e-10 && a < 1e-10, "chained heat diffusions do not add up");
}

//------------------------------------------------------------------------------
// An abort requested during execution stops the filter after the current signal and leaves
// both outputs empty (VTK's rule: an aborted filter's output is empty), not some arrays
// filtered and others not; the next execution, the flag cleared, is complete.
bool TestAbort()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 20, { "A", "B", "Sum" });
  pipeline.Transform->Update();
  vtkNew<AbortAtFirstProgress> abort;
  const unsigned long observer = pipeline.Filter->AddObserver(vtkCommand::ProgressEvent, abort);
  vtkPolyData* output = pipeline.Run();
  std::cout << "Abort: " << abort->Count << " progress event(s) for 4 signals, "
            << output->GetNumberOfPoints() << " points and "
            << output->GetPointData()->GetNumberOfArrays() << " point arrays out" << std::endl;
  bool ok = Check(abort->Count == 1, "the filter does not stop when asked to abort");
  ok &= Check(output->GetNumberOfPoints() == 0 && output->GetNumberOfCells() == 0 &&
      output->GetPointData()->GetNumberOfArrays() == 0 &&
      output->GetFieldData()->GetNumberOfArrays() == 0,
    "the output of an aborted filter is not empty");
  ok &= Check(pipeline.Filter->GetSpectrumOutput()->GetNumberOfColumns() == 0,
    "the spectrum of an aborted filter is not empty");
  pipeline.Filter->RemoveObserver(observer);
  pipeline.Filter->AbortExecuteOff();
  pipeline.Filter->Modified();
  output = pipeline.Run();
  ok &= Check(output->GetNumberOfPoints() == mesh->GetNumberOfPoints() &&
      output->GetPointData()->GetArray("Sum_Filtered") != nullptr,
    "the run after an abort is not complete");
  return ok;
}

//------------------------------------------------------------------------------
// A point that no triangle uses is not part of the surface and stays where it is.
bool TestUnusedPoint()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  sphere->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->DeepCopy(sphere->GetOutput());
  mesh->GetPointData()->Initialize();
  const vtkIdType stray = mesh->GetPoints()->InsertNextPoint(5.0, 5.0, 5.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const vtkIdType broken = mesh->GetPoints()->InsertNextPoint(nan, nan, nan);
  const vtkIdType n = mesh->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> scalar;
  scalar->SetName("S");
  scalar->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    scalar->SetValue(i, i == broken ? nan : std::sin(0.1 * static_cast<double>(i)));
  }
  mesh->GetPointData()->AddArray(scalar);
  Pipeline pipeline(mesh, 20, { "S" });
  pipeline.Filter->SetCutoff(2.0);
  vtkPolyData* output = pipeline.Run();
  double p[3];
  output->GetPoint(stray, p);
  std::cout << "Unused point after a low-pass: (" << p[0] << ", " << p[1] << ", " << p[2] << ")"
            << std::endl;
  bool ok = Check(p[0] == 5.0 && p[1] == 5.0 && p[2] == 5.0, "the unused point moved");
  // NaN at a point used by no triangle (coordinates and S) stays there.
  bool finite = true;
  vtkDataArray* filtered = output->GetPointData()->GetArray("S_Filtered");
  ok &= Check(filtered != nullptr, "S_Filtered missing");
  for (vtkIdType i = 0; filtered && i < n; ++i)
  {
    output->GetPoint(i, p);
    finite &= i == broken ||
      (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]) &&
        std::isfinite(filtered->GetComponent(i, 0)));
  }
  ok &= Check(finite, "NaN at an unused point spread to the surface");

  // NaN at a point of the surface: the transform of that array is undefined, an error says so.
  scalar->SetValue(0, nan);
  scalar->Modified();
  const ManifoldHarmonicsTest::Messages errors(pipeline.Transform);
  pipeline.Filter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors.Executive);
  pipeline.Run();
  const std::string message = errors->GetErrorMessage();
  ok &= Check(errors->GetError() && message.find("'S'") != std::string::npos &&
      message.find("not finite") != std::string::npos,
    "no error naming the array with NaN on the surface");
  return ok;
}

//------------------------------------------------------------------------------
// Two spheres apart and a single harmonic: it is the constant of the larger sphere, so the
// smaller sphere has no harmonic. Its points must not move (re-injection would scale them
// toward the origin), and the basis says so.
bool TestUnrepresentedComponent()
{
  vtkNew<vtkSphereSource> large;
  large->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  large->SetThetaResolution(24);
  large->SetPhiResolution(24);
  large->Update();
  vtkNew<vtkSphereSource> small;
  small->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  small->SetCenter(4.0, 1.0, 2.0);
  small->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->DeepCopy(large->GetOutput());
  mesh->GetPointData()->Initialize();
  const vtkIdType offset = mesh->GetNumberOfPoints();
  vtkPolyData* second = small->GetOutput();
  for (vtkIdType i = 0; i < second->GetNumberOfPoints(); ++i)
  {
    mesh->GetPoints()->InsertNextPoint(second->GetPoint(i));
  }
  const vtkIdType numCells = second->GetNumberOfCells();
  for (vtkIdType c = 0; c < numCells; ++c)
  {
    vtkNew<vtkIdList> ids;
    second->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      ids->SetId(k, ids->GetId(k) + offset);
    }
    mesh->GetPolys()->InsertNextCell(ids);
  }
  Pipeline pipeline(mesh, 1, {});
  vtkNew<vtkTest::ErrorObserver> warnings;
  pipeline.Basis->AddObserver(vtkCommand::WarningEvent, warnings);
  pipeline.Filter->SetCutoff(0.5);
  vtkPolyData* output = pipeline.Run();
  double moved = 0.0;
  for (vtkIdType i = offset; output && i < output->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    output->GetPoint(i, a);
    mesh->GetPoint(i, b);
    moved = std::max(moved, std::sqrt(vtkMath::Distance2BetweenPoints(a, b)));
  }
  std::cout << "Largest move of the sphere without a harmonic: " << moved << std::endl;
  bool ok =
    Check(output && output->GetNumberOfPoints() == mesh->GetNumberOfPoints() && moved == 0.0,
      "points of a component no harmonic represents moved");
  ok &= Check(
    warnings->GetWarningMessage().find("none of the 1 harmonics represents") != std::string::npos,
    "no warning about the component without a harmonic");
  return ok;
}

//------------------------------------------------------------------------------
// The filter keeps the edge lengths behind the Nyquist frequency between executions: a new
// input geometry (here the sphere scaled by 2, which halves the Nyquist frequency and so
// changes the re-injected part) must give what a new filter gives.
bool TestNyquistFollowsInput()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 30, {});
  pipeline.Filter->SetFilterKindToHeatDiffusion();
  pipeline.Filter->SetTime(0.002);
  pipeline.Run();
  pipeline.Filter->SetTime(0.003); // re-executes the filter alone, on the kept sums
  pipeline.Run();

  vtkNew<vtkPolyData> scaled;
  scaled->DeepCopy(mesh);
  for (vtkIdType i = 0; i < scaled->GetNumberOfPoints(); ++i)
  {
    double p[3];
    scaled->GetPoint(i, p);
    scaled->GetPoints()->SetPoint(i, 2.0 * p[0], 2.0 * p[1], 2.0 * p[2]);
  }
  pipeline.Basis->SetInputData(scaled);
  vtkPolyData* reused = pipeline.Run();
  Pipeline fresh(scaled, 30, {});
  fresh.Filter->SetFilterKindToHeatDiffusion();
  fresh.Filter->SetTime(0.003);
  const double difference =
    RelativeDifference(reused->GetPoints()->GetData(), fresh.Run()->GetPoints()->GetData());
  std::cout << "Filter re-run on a scaled input vs a new filter: " << difference << std::endl;
  return Check(difference < 1e-12, "the filter re-used the Nyquist frequency of its old input");
}

//------------------------------------------------------------------------------
// pi / (mean edge length of the polygons), computed here from the cells.
double NyquistOfPolygons(vtkPolyData* mesh)
{
  double sum = 0.0;
  double count = 0.0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double a[3];
      double b[3];
      mesh->GetPoint(ids->GetId(k), a);
      mesh->GetPoint(ids->GetId((k + 1) % ids->GetNumberOfIds()), b);
      sum += std::sqrt(vtkMath::Distance2BetweenPoints(a, b));
      count += 1.0;
    }
  }
  return vtkMath::Pi() / (sum / count);
}

//------------------------------------------------------------------------------
// Another input object with the same MTime as the last one (both share the points, modified
// last) but other polygons: the filter must walk its edges, not keep the first input's Nyquist
// frequency (which sets the re-injection gain and the slider ranges).
bool TestNyquistSameMTime()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(40);
  sphere->SetPhiResolution(40);
  sphere->Update();
  Pipeline pipeline(sphere->GetOutput(), 20, {});
  pipeline.Transform->Update();
  vtkNew<vtkPolyData> whole;
  whole->ShallowCopy(pipeline.Transform->GetOutput());
  // The polar caps: the triangles around the two poles (points 0 and 1 of vtkSphereSource).
  vtkNew<vtkCellArray> capPolygons;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < whole->GetNumberOfCells(); ++c)
  {
    whole->GetCellPoints(c, ids);
    if (ids->IsId(0) >= 0 || ids->IsId(1) >= 0)
    {
      capPolygons->InsertNextCell(ids);
    }
  }
  vtkNew<vtkPolyData> caps;
  caps->ShallowCopy(whole); // the basis and the coefficients, with other polygons
  caps->SetPolys(capPolygons);
  whole->GetPoints()->Modified();

  vtkNew<vtkSpectralFilter> filter;
  filter->SetInputData(whole);
  filter->Update();
  const double first = filter->GetNyquistFrequency();
  bool ok = Check(caps->GetMTime() == whole->GetMTime(), "set-up: equal MTimes");
  filter->SetInputData(caps);
  filter->Update();
  const double expected = NyquistOfPolygons(caps);
  std::cout << "Nyquist frequency: whole sphere " << first << " (expected "
            << NyquistOfPolygons(whole) << "), polar caps " << filter->GetNyquistFrequency()
            << " (expected " << expected << ")" << std::endl;
  ok &= Check(std::abs(first - NyquistOfPolygons(whole)) < 1e-12 * first,
    "the Nyquist frequency of the whole sphere is not pi / mean edge length");
  ok &= Check(std::abs(filter->GetNyquistFrequency() - expected) < 1e-12 * expected,
    "a new input with the MTime of the last one kept the last one's Nyquist frequency");
  return ok;
}

//------------------------------------------------------------------------------
// NumberOfThreads (transform and filter): 0 (all cores) by default, never negative, and the
// results of one and two threads agree to round-off.
bool TestNumberOfThreads()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 30, { "A" });
  bool ok = Check(
    pipeline.Transform->GetNumberOfThreads() == 0 && pipeline.Filter->GetNumberOfThreads() == 0,
    "NumberOfThreads does not default to 0");
  pipeline.Filter->SetNumberOfThreads(-3);
  ok &= Check(pipeline.Filter->GetNumberOfThreads() == 0, "a negative NumberOfThreads is kept");
  // A cutoff that keeps the harmonics up to degree 3 (the default 1 leaves the centroid only,
  // whose coordinates are round-off).
  pipeline.Filter->SetCutoff(4.0);
  pipeline.Transform->SetNumberOfThreads(1);
  pipeline.Filter->SetNumberOfThreads(1);
  vtkNew<vtkPolyData> one;
  one->DeepCopy(pipeline.Run());
  pipeline.Transform->SetNumberOfThreads(2);
  pipeline.Filter->SetNumberOfThreads(2);
  vtkPolyData* two = pipeline.Run();
  const double points =
    RelativeDifference(two->GetPoints()->GetData(), one->GetPoints()->GetData());
  const double a = RelativeDifference(
    two->GetPointData()->GetArray("A_Filtered"), one->GetPointData()->GetArray("A_Filtered"));
  std::cout << "One thread vs two: points " << points << ", A " << a << std::endl;
  ok &= Check(points < 1e-12 && a < 1e-12, "one and two threads disagree");
  return ok;
}

//------------------------------------------------------------------------------
// Changing the filter's parameters re-executes the filter alone.
bool TestInteractive()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 40, { "A" });
  vtkNew<ExecutionCounter> basisRuns;
  vtkNew<ExecutionCounter> transformRuns;
  vtkNew<ExecutionCounter> filterRuns;
  pipeline.Basis->AddObserver(vtkCommand::EndEvent, basisRuns);
  pipeline.Transform->AddObserver(vtkCommand::EndEvent, transformRuns);
  pipeline.Filter->AddObserver(vtkCommand::EndEvent, filterRuns);
  pipeline.Run();
  pipeline.Filter->SetCutoff(2.0);
  pipeline.Run();
  pipeline.Filter->SetFilterKindToBandStop();
  pipeline.Filter->SetUpperCutoff(4.0);
  pipeline.Filter->ReplaceInputOn();
  pipeline.Run();
  pipeline.Filter->SetFilterKindToCustom();
  pipeline.Filter->SetNumberOfControlPoints(3);
  pipeline.Filter->SetControlPoint(0, 0.0, 1.0);
  pipeline.Filter->SetControlPoint(1, 3.0, 1.0);
  pipeline.Filter->SetControlPoint(2, 5.0, 0.0);
  pipeline.Run();
  pipeline.Run();
  std::cout << "Executions after 5 updates and 4 parameter changes: basis " << basisRuns->Count
            << ", transform " << transformRuns->Count << ", filter " << filterRuns->Count
            << std::endl;
  bool ok = Check(basisRuns->Count == 1, "parameter changes re-execute the basis");
  ok &= Check(transformRuns->Count == 1, "parameter changes re-execute the transform");
  ok &= Check(filterRuns->Count == 4, "the filter does not re-execute exactly once per change");
  return ok;
}

//------------------------------------------------------------------------------
// The text of a VTK error or warning without its "ERROR: In file, line" prefix, which the test
// harness would take for a failure.
std::string AfterLocation(const std::string& message)
{
  const std::size_t start = message.find("): ");
  return start == std::string::npos ? message : message.substr(start + 2);
}

//------------------------------------------------------------------------------
bool TestMissingInputs()
{
  bool ok = true;
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkSpectralFilter> filter;
  const ManifoldHarmonicsTest::Messages errors(filter);
  filter->SetInputConnection(sphere->GetOutputPort());
  filter->Update();
  std::cout << "Expected error:" << AfterLocation(errors->GetErrorMessage());
  ok &= Check(
    errors->CheckErrorMessage("ManifoldHarmonicBasis") == 0, "no clear error without the basis");

  // The basis without the transform: nothing to filter, a warning, and the input passes.
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputConnection(sphere->GetOutputPort());
  basis->SetNumberOfHarmonics(10);
  filter->SetInputConnection(basis->GetOutputPort());
  filter->Update();
  std::cout << "Expected warning:" << AfterLocation(errors->GetWarningMessage());
  ok &= Check(errors->CheckWarningMessage("ManifoldHarmonicTransform") == 0,
    "no warning without coefficients");
  ok &= Check(filter->GetOutput()->GetNumberOfPoints() == sphere->GetOutput()->GetNumberOfPoints(),
    "the input does not pass through");

  // Points without polygons: the basis passes them through without a basis (a warning of its
  // own); the filter's error says so instead of asking for the basis that is upstream.
  vtkSmartPointer<vtkPolyData> cloud = LinesOnly(sphere->GetOutput()->GetPoints());
  vtkNew<vtkTest::ErrorObserver> basisWarnings;
  basis->AddObserver(vtkCommand::WarningEvent, basisWarnings);
  basis->SetInputData(cloud);
  filter->Update();
  std::cout << "Expected error:" << AfterLocation(errors->GetErrorMessage());
  ok &= Check(basisWarnings->GetWarning(), "set-up: the basis warns about the missing polygons");
  ok &=
    Check(errors->CheckErrorMessage("the input has no polygons or volume cells, so "
                                    "ManifoldHarmonicBasis passed it through without a basis") == 0,
      "the error does not say that the input has no polygons");
  return ok;
}

//------------------------------------------------------------------------------
// A sphere of radius `scale` (24 x 16, double points) whose points are moved along the radius by
// up to 2% of it: noise for a low pass to remove.
vtkSmartPointer<vtkPolyData> MakeNoisySphere(double scale)
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  vtkNew<vtkMinimalStandardRandomSequence> random;
  random->SetSeed(11);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    const double radial = scale * (1.0 + 0.02 * (2.0 * random->GetValue() - 1.0));
    random->Next();
    const double norm = vtkMath::Norm(p);
    points->InsertNextPoint(radial * p[0] / norm, radial * p[1] / norm, radial * p[2] / norm);
  }
  mesh->SetPoints(points);
  return mesh;
}

//------------------------------------------------------------------------------
// Basis (36 harmonics: the complete clusters l <= 5 of the sphere), transform and a filter with
// its default settings on `mesh`: the filtered points.
vtkSmartPointer<vtkDataArray> DefaultLowPass(vtkPolyData* mesh)
{
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(mesh);
  basis->SetNumberOfHarmonics(36);
  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputConnection(basis->GetOutputPort());
  vtkNew<vtkSpectralFilter> filter;
  filter->SetInputConnection(transform->GetOutputPort());
  filter->Update();
  vtkSmartPointer<vtkDataArray> points =
    vtk::TakeSmartPointer(filter->GetOutput()->GetPoints()->GetData()->NewInstance());
  points->DeepCopy(filter->GetOutput()->GetPoints()->GetData());
  return points;
}

//------------------------------------------------------------------------------
// The default cutoff means the same on every model: a noisy sphere scaled by 1e-6, 1 and 1e6 is
// smoothed alike (up to the scale), neither collapsed to its centroid nor left unchanged. (The
// frequencies scale as 1 / size, so no absolute cutoff can do this.)
bool TestDefaultCutoffAtAnyScale()
{
  bool ok = true;
  vtkSmartPointer<vtkPolyData> unit = MakeNoisySphere(1.0);
  vtkSmartPointer<vtkDataArray> reference = DefaultLowPass(unit);
  // At scale 1: smoothed (the radial noise of up to 0.02 mostly removed), not collapsed.
  double noiseBefore = 0.0;
  double noiseAfter = 0.0;
  for (vtkIdType i = 0; i < unit->GetNumberOfPoints(); ++i)
  {
    double p[3];
    double q[3];
    unit->GetPoint(i, p);
    reference->GetTuple(i, q);
    noiseBefore = std::max(noiseBefore, std::abs(vtkMath::Norm(p) - 1.0));
    noiseAfter = std::max(noiseAfter, std::abs(vtkMath::Norm(q) - 1.0));
  }
  std::cout << "Default low pass of a noisy unit sphere: radial noise " << noiseBefore << " -> "
            << noiseAfter << std::endl;
  ok &= Check(noiseAfter < 0.75 * noiseBefore && noiseAfter > 1e-4,
    "the default filter does not smooth a noisy unit sphere (radial noise " +
      std::to_string(noiseBefore) + " -> " + std::to_string(noiseAfter) + ")");
  for (double scale : { 1e-6, 1e6 })
  {
    vtkSmartPointer<vtkDataArray> scaled = DefaultLowPass(MakeNoisySphere(scale));
    vtkNew<vtkDoubleArray> back;
    back->SetNumberOfComponents(3);
    back->SetNumberOfTuples(scaled->GetNumberOfTuples());
    for (vtkIdType i = 0; i < scaled->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        back->SetComponent(i, c, scaled->GetComponent(i, c) / scale);
      }
    }
    const double difference = RelativeDifference(back, reference);
    std::cout << "Default low pass at scale " << scale << " against scale 1: " << difference
              << std::endl;
    ok &= Check(difference < 1e-6,
      "the default filter at scale " + std::to_string(scale) +
        " differs from scale 1 by " + std::to_string(difference));
  }
  return ok;
}

//------------------------------------------------------------------------------
// Relative units are the absolute cutoffs they name: harmonic index k is omega_k, a fractional
// index lies between two harmonics, a fraction f is f omega_max, a relative heat time T is
// T / lambda_1, band edges alike; and the slider ranges follow the units.
bool TestCutoffUnits()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Pipeline pipeline(mesh, 30, { "A" });
  pipeline.Run();
  vtkDataArray* eigenvalues = pipeline.Basis->GetOutput()->GetFieldData()->GetArray(
    vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  const auto omega = [eigenvalues](int k) { return std::sqrt(eigenvalues->GetTuple1(k)); };
  const double lambda1 = eigenvalues->GetTuple1(1);
  vtkSpectralFilter* filter = pipeline.Filter;
  // Runs the filter in `units` with (cutoff, upper, time), then in absolute frequencies with
  // (absolute, absoluteUpper, absoluteTime), and compares the points and the filtered A.
  const auto same = [&pipeline, filter](int units, double cutoff, double upper, double time, double absolute,
                      double absoluteUpper, double absoluteTime, const std::string& what)
  {
    filter->SetCutoffUnits(units);
    filter->SetCutoff(cutoff);
    filter->SetUpperCutoff(upper);
    filter->SetTime(time);
    vtkNew<vtkPolyData> relative;
    relative->DeepCopy(pipeline.Run());
    filter->SetCutoffUnitsToAbsoluteFrequency();
    filter->SetCutoff(absolute);
    filter->SetUpperCutoff(absoluteUpper);
    filter->SetTime(absoluteTime);
    vtkPolyData* output = pipeline.Run();
    const double points =
      RelativeDifference(relative->GetPoints()->GetData(), output->GetPoints()->GetData());
    const double a = RelativeDifference(relative->GetPointData()->GetArray("A_Filtered"),
      output->GetPointData()->GetArray("A_Filtered"));
    std::cout << "  " << what << ": points " << points << ", A " << a << std::endl;
    return Check(points <= 1e-14 && a <= 1e-14, what + " is not the absolute cutoff it names");
  };
  std::cout << "Relative units against the absolute cutoffs they name:" << std::endl;
  bool ok = true;
  filter->SetFilterKindToLowPass();
  ok &= same(vtkSpectralFilter::HARMONIC_INDEX, 10, 1, 0, omega(10), 1, 0, "harmonic index 10");
  ok &= same(vtkSpectralFilter::HARMONIC_INDEX, 10.25, 1, 0, 0.75 * omega(10) + 0.25 * omega(11),
    1, 0, "harmonic index 10.25");
  ok &= same(vtkSpectralFilter::FRACTION_OF_HIGHEST, 0.4, 1, 0, 0.4 * omega(29), 1, 0,
    "fraction 0.4");
  filter->SetFilterKindToBandPass();
  ok &= same(vtkSpectralFilter::HARMONIC_INDEX, 4, 15, 0, omega(4), omega(15), 0,
    "band of harmonics [4, 15]");
  ok &= same(vtkSpectralFilter::FRACTION_OF_HIGHEST, 0.3, 0.7, 0, 0.3 * omega(29),
    0.7 * omega(29), 0, "band of fractions [0.3, 0.7]");
  filter->SetFilterKindToHeatDiffusion();
  ok &= same(vtkSpectralFilter::FRACTION_OF_HIGHEST, 1, 1, 0.3, 1, 1, 0.3 / lambda1,
    "relative heat time 0.3");
  ok &= same(vtkSpectralFilter::HARMONIC_INDEX, 1, 1, 0.3, 1, 1, 0.3 / lambda1,
    "relative heat time 0.3 (harmonic units)");
  // The sliders in each unit.
  const auto ranges = [&pipeline, filter](
                        int units, double frequency, double time, const std::string& what)
  {
    filter->SetCutoffUnits(units);
    pipeline.Run();
    const double* f = filter->GetFrequencyRange();
    const double* t = filter->GetTimeRange();
    std::cout << "  slider ranges, " << what << ": [" << f[0] << ", " << f[1] << "], [" << t[0]
              << ", " << t[1] << "]" << std::endl;
    return Check(f[0] == 0.0 && std::abs(f[1] - frequency) <= 1e-12 * frequency && t[0] == 0.0 &&
        std::abs(t[1] - time) <= 1e-12 * time,
      "slider ranges in " + what);
  };
  ok &= ranges(vtkSpectralFilter::ABSOLUTE_FREQUENCY, omega(29), 4.0 / lambda1, "frequencies");
  ok &= ranges(vtkSpectralFilter::FRACTION_OF_HIGHEST, 1.0, 4.0, "fractions");
  ok &= ranges(vtkSpectralFilter::HARMONIC_INDEX, 29.0, 4.0, "harmonic indices");
  return ok;
}

//------------------------------------------------------------------------------
// A basis (sphere, m = 20), its transform and a filter with an observer of its errors and
// warnings, in the filter's default units.
struct Observed
{
  vtkNew<vtkManifoldHarmonicBasis> Basis;
  vtkNew<vtkManifoldHarmonicTransform> Transform;
  vtkNew<vtkSpectralFilter> Filter;
  // The filter's errors and warnings, and apart its executive's report of a failed execution.
  ManifoldHarmonicsTest::Messages Messages;

  explicit Observed(vtkPolyData* mesh, int harmonics = 20)
  {
    this->Basis->SetInputData(mesh);
    this->Basis->SetNumberOfHarmonics(harmonics);
    this->Transform->SetInputConnection(this->Basis->GetOutputPort());
    this->Filter->SetInputConnection(this->Transform->GetOutputPort());
    this->Messages.Observe(this->Filter);
    this->Transform->Update();
  }
  /// Whether the filter succeeded; the messages are those of this execution.
  bool Run()
  {
    this->Messages->Clear();
    return this->Filter->GetExecutive()->Update() != 0;
  }
  /// omega_k of the basis.
  double Omega(int k)
  {
    return std::sqrt(this->Basis->GetOutput()
                       ->GetFieldData()
                       ->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName())
                       ->GetTuple1(k));
  }
};

//------------------------------------------------------------------------------
// How a number appears in the filter's messages (the default stream format).
std::string Printed(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

//------------------------------------------------------------------------------
// A negative cutoff, upper cutoff or time is an error that fails the filter (not a value
// clamped to 0 in silence).
bool TestNegativeCutoffs()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Observed run(mesh);
  bool ok = true;
  const auto refused = [&run](const std::string& what)
  {
    const bool succeeded = run.Run();
    std::cout << "Expected error (" << what << "):" << AfterLocation(run.Messages->GetErrorMessage());
    return Check(!succeeded && run.Messages->GetError() &&
        run.Messages->GetErrorMessage().find("-1") != std::string::npos,
      what + " is not an error naming the value");
  };
  run.Filter->SetCutoff(-1.0);
  ok &= Check(run.Filter->GetCutoff() == -1.0, "SetCutoff(-1) changed the value");
  ok &= refused("Cutoff -1");
  run.Filter->SetCutoff(0.5);
  run.Filter->SetFilterKindToBandPass();
  run.Filter->SetCutoff(-1.0);
  ok &= refused("band pass from Cutoff -1");
  run.Filter->SetCutoff(0.0);
  run.Filter->SetUpperCutoff(-1.0);
  ok &= refused("band pass up to UpperCutoff -1");
  run.Filter->SetFilterKindToHeatDiffusion();
  run.Filter->SetTime(-1.0);
  ok &= refused("Time -1");
  // A negative value the kind does not use is no error.
  run.Filter->SetTime(0.5);
  ok &= Check(run.Run() && !run.Messages->GetError(),
    "heat diffusion fails on an UpperCutoff it does not use");
  return ok;
}

//------------------------------------------------------------------------------
// A cutoff below the first non-zero frequency or above the highest computed one is a warning
// that names both frequencies and what happens; so is a basis of constant harmonics only.
bool TestCutoffsOutsideTheSpectrum()
{
  vtkSmartPointer<vtkPolyData> mesh = MakeSphere(24, 16);
  Observed run(mesh);
  bool ok = true;
  const double first = run.Omega(1);
  const double highest = run.Omega(19);
  const auto warns = [&run](const std::vector<std::string>& parts, const std::string& what)
  {
    const bool succeeded = run.Run();
    const std::string message = run.Messages->GetWarningMessage();
    std::cout << "Expected warning (" << what << "):" << AfterLocation(message);
    bool all = succeeded && !run.Messages->GetError();
    for (const std::string& part : parts)
    {
      all &= Check(message.find(part) != std::string::npos, what + ": no '" + part + "'");
    }
    return Check(all, what + " does not warn as it should");
  };
  // Default units (a fraction of the highest computed frequency).
  run.Filter->SetCutoff(1e-3);
  ok &= warns({ "Cutoff 0.001", Printed(1e-3 * highest), "below the first non-zero frequency " +
                  Printed(first),
                "centroid" },
    "low pass below the first non-zero frequency");
  run.Filter->SetCutoff(1.5);
  ok &= warns({ "Cutoff 1.5", Printed(1.5 * highest),
                "above the highest computed frequency " + Printed(highest) },
    "low pass above the highest computed frequency");
  // As a harmonic index beyond the last harmonic (19 of 20).
  run.Filter->SetCutoffUnitsToHarmonicIndex();
  run.Filter->SetCutoff(25);
  ok &= warns(
    { "Cutoff 25", "beyond the last computed harmonic, 19" }, "low pass beyond the last harmonic");
  run.Filter->SetCutoffUnitsToAbsoluteFrequency();
  run.Filter->SetFilterKindToBandPass();
  run.Filter->SetCutoff(0.5 * (first + highest));
  run.Filter->SetUpperCutoff(2.0 * highest);
  ok &= warns({ "UpperCutoff " + Printed(2.0 * highest), "above the highest computed frequency" },
    "band pass beyond the highest computed frequency");
  // Inside the spectrum: no warning.
  run.Filter->SetFilterKindToLowPass();
  run.Filter->SetCutoff(0.5 * (first + highest));
  ok &= Check(run.Run() && !run.Messages->GetWarning() && !run.Messages->GetError(),
    "a cutoff inside the spectrum warns: " + run.Messages->GetWarningMessage());

  // 40 separate triangles: every harmonic is constant on its triangle, all eigenvalues are zero.
  vtkNew<vtkPolyData> debris;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> triangles;
  for (int t = 0; t < 40; ++t)
  {
    const double x = 2.0 * t;
    const vtkIdType ids[3] = { points->InsertNextPoint(x, 0, 0),
      points->InsertNextPoint(x + 1, 0, 0), points->InsertNextPoint(x, 1, 0) };
    triangles->InsertNextCell(3, ids);
  }
  debris->SetPoints(points);
  debris->SetPolys(triangles);
  vtkNew<vtkTest::ErrorObserver> basisWarnings; // the basis's own, about the components
  Observed constant(debris, 10);
  constant.Basis->AddObserver(vtkCommand::WarningEvent, basisWarnings);
  constant.Basis->Modified();
  const bool succeeded = constant.Run();
  std::cout << "Expected warning (constant harmonics only):"
            << AfterLocation(constant.Messages->GetWarningMessage());
  ok &= Check(succeeded &&
      constant.Messages->GetWarningMessage().find("no non-constant harmonic") != std::string::npos,
    "a basis of constant harmonics only does not warn");
  // What the warning says the default low pass does: the points of each of the 10 triangles
  // with a harmonic go to its centroid; the 30 others, which the basis left out, stay.
  ok &= Check(
    constant.Messages->GetWarningMessage().find(
      "the points of each component with a harmonic move to its centroid") != std::string::npos,
    "the warning does not say that the points move to their component's centroid");
  vtkPointSet* collapsed = vtkPointSet::SafeDownCast(constant.Filter->GetOutput());
  int atCentroid = 0;
  int stayed = 0;
  for (vtkIdType t = 0; succeeded && t < 40; ++t)
  {
    const double x = 2.0 * static_cast<double>(t);
    const double centroid[3] = { x + 1.0 / 3.0, 1.0 / 3.0, 0.0 };
    double toCentroid = 0.0;
    double moved = 0.0;
    for (vtkIdType c = 0; c < 3; ++c)
    {
      double p[3], q[3];
      collapsed->GetPoint(3 * t + c, p);
      points->GetPoint(3 * t + c, q);
      toCentroid = std::max(toCentroid, std::sqrt(vtkMath::Distance2BetweenPoints(p, centroid)));
      moved = std::max(moved, std::sqrt(vtkMath::Distance2BetweenPoints(p, q)));
    }
    atCentroid += toCentroid < 1e-5 ? 1 : 0; // float points
    stayed += moved == 0.0 ? 1 : 0;
  }
  ok &= Check(atCentroid == 10 && stayed == 30,
    std::to_string(atCentroid) + " triangles went to their centroid (not 10), " +
      std::to_string(stayed) + " stayed (not 30)");

  // Rounding-sized eigenvalues (set by hand: what a machine may return for the zero ones) that
  // a tiny cutoff splits: the components of the harmonics above it would go to the origin.
  vtkNew<vtkPolyData> rounded;
  rounded->ShallowCopy(constant.Transform->GetOutput());
  vtkNew<vtkDoubleArray> tiny;
  tiny->SetName(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  for (int k = 0; k < 10; ++k)
  {
    tiny->InsertNextValue(1e-12 * k);
  }
  vtkNew<vtkFieldData> fields;
  fields->DeepCopy(rounded->GetFieldData());
  fields->AddArray(tiny); // replaces the basis's eigenvalues
  rounded->SetFieldData(fields);
  vtkNew<vtkSpectralFilter> split;
  const ManifoldHarmonicsTest::Messages splitMessages(split);
  split->SetInputData(rounded);
  split->SetCutoffUnitsToAbsoluteFrequency();
  split->SetCutoff(std::sqrt(4.5e-12));
  split->SetTransition(0.0);
  split->Update();
  std::cout << "Expected warning (rounding-sized eigenvalues split by the cutoff):"
            << AfterLocation(splitMessages->GetWarningMessage());
  ok &= Check(!splitMessages->GetError() &&
      splitMessages->GetWarningMessage().find("5 of the 10 constant harmonic(s)") !=
        std::string::npos &&
      splitMessages->GetWarningMessage().find("towards the origin") != std::string::npos,
    "a cutoff among rounding-sized eigenvalues does not warn that components go to the origin");
  return ok;
}
} // anonymous namespace

//------------------------------------------------------------------------------
int TestSpectralFilter(int argc, char* argv[])
{
  return ManifoldHarmonicsTest::RunCases(argc,
    argv,
    {
      { "Identity", TestIdentity },
      { "CompleteBasis", TestCompleteBasis },
      { "FloatBasis", TestFloatBasis },
      { "Linearity", TestLinearity },
      { "NoisySphere", TestNoisySphere },
      { "ColorsAndNormals", TestColorsAndNormals },
      { "HeatDiffusion", TestHeatDiffusion },
      { "Chaining", TestChaining },
      { "UnrepresentedComponent", TestUnrepresentedComponent },
      { "UnusedPoint", TestUnusedPoint },
      { "NyquistFollowsInput", TestNyquistFollowsInput },
      { "NyquistSameMTime", TestNyquistSameMTime },
      { "NumberOfThreads", TestNumberOfThreads },
      { "Abort", TestAbort },
      { "Interactive", TestInteractive },
      { "MissingInputs", TestMissingInputs },
      { "SliderRanges", TestSliderRanges },
      { "DefaultCutoffAtAnyScale", TestDefaultCutoffAtAnyScale },
      { "CutoffUnits", TestCutoffUnits },
      { "NegativeCutoffs", TestNegativeCutoffs },
      { "CutoffsOutsideTheSpectrum", TestCutoffsOutsideTheSpectrum },
    });
}
