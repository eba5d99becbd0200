// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
// Spectral filtering of a surface mesh: basis -> transform -> filter -> .vtp.
//
//   ManifoldHarmonicFilter input.(ply|obj|stl|vtp) output.vtp [options]
//
// The options and their defaults are in PrintUsage below (printed by --help).
//
// The filtered coordinates replace the points; the output also holds the basis arrays and the
// coefficients of the points. Run by CTest on Testing/Data/bunny.ply.

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkManifoldHarmonicBasis.h"
#include "vtkManifoldHarmonicTransform.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPLYReader.h"
#include "vtkPolyData.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkSpectralFilter.h"
#include "vtkTimerLog.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"

#include <vtksys/SystemTools.hxx>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

namespace
{
struct Options
{
  std::string Input;
  std::string Output;
  int Harmonics = vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS;
  std::string KindName = "lowpass";
  int Kind = vtkSpectralFilter::LOW_PASS;
  double Cutoff = -1.0; // < 0: half the highest computed frequency
  double Upper = -1.0;  // < 0: twice the cutoff
  double Gain = 2.0;
  double Time = -1.0; // < 0: ln 2 / cutoff^2
  bool Reinject = true;
  int Threads = 0; // 0: every core
};

// After "--help" and "--harmonics", whose default PrintUsage takes from vtkManifoldHarmonicBasis.
const char* const OptionsHelp =
  "  --kind k        lowpass, highpass, bandpass, bandstop, enhancement, exaggeration, heat,\n"
  "                  custom: a ramp from gain 1 at 0 to 0 at the cutoff (default lowpass)\n"
  "  --cutoff w      cutoff frequency (default: half the highest computed frequency)\n"
  "  --upper w       upper band edge (default: 2 x cutoff)\n"
  "  --gain g        gain of enhancement and exaggeration (default 2)\n"
  "  --time t        heat diffusion time (default ln 2 / cutoff^2: the gain at the cutoff is 1/2)\n"
  "  --no-reinject   drop the frequencies above the last harmonic\n"
  "  --threads t     threads of the eigensolve and the filter stage (default 0: every core)\n";

void PrintUsage(std::ostream& os, const char* program)
{
  os << "Usage: " << program << " input.(ply|obj|stl|vtp) output.vtp [options]\n"
     << "  --help          this text\n"
     << "  --harmonics m   number of harmonics (default "
     << vtkManifoldHarmonicBasis::DEFAULT_NUMBER_OF_HARMONICS << ")\n"
     << OptionsHelp;
}

/// The lower-case extension of a file name, without the dot ("" without one).
std::string Extension(const std::string& fileName)
{
  const std::size_t dot = fileName.find_last_of('.');
  const std::size_t slash = fileName.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return "";
  }
  std::string extension = fileName.substr(dot + 1);
  std::transform(extension.begin(),
    extension.end(),
    extension.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

/// `text` as a number of type T, all of it; false (with a message naming `option`) otherwise.
template<typename T>
bool ReadNumber(const std::string& option, const std::string& text, T& value)
{
  std::istringstream stream(text);
  T parsed;
  if (!(stream >> parsed) || !(stream >> std::ws).eof())
  {
    std::cerr << option << ": '" << text << "' is not a number\n";
    return false;
  }
  value = parsed;
  return true;
}

/// `text` as a finite number >= 0; false (with a message naming `option`) otherwise.
bool ReadNonNegative(const std::string& option, const std::string& text, double& value)
{
  double parsed = 0.0;
  if (!ReadNumber(option, text, parsed))
  {
    return false;
  }
  if (!(parsed >= 0.0) || !std::isfinite(parsed))
  {
    std::cerr << option << ": a finite number >= 0, not " << text << "\n";
    return false;
  }
  value = parsed;
  return true;
}

bool Parse(int argc, char* argv[], Options& options)
{
  const std::map<std::string, int> kinds = { { "lowpass", vtkSpectralFilter::LOW_PASS },
    { "highpass", vtkSpectralFilter::HIGH_PASS },
    { "bandpass", vtkSpectralFilter::BAND_PASS },
    { "bandstop", vtkSpectralFilter::BAND_STOP },
    { "enhancement", vtkSpectralFilter::ENHANCEMENT },
    { "exaggeration", vtkSpectralFilter::BAND_EXAGGERATION },
    { "heat", vtkSpectralFilter::HEAT_DIFFUSION },
    { "custom", vtkSpectralFilter::CUSTOM } };
  if (argc < 3)
  {
    return false;
  }
  options.Input = argv[1];
  options.Output = argv[2];
  if (Extension(options.Output) != "vtp")
  {
    std::cerr << "The output is written as VTK XML polydata: name it .vtp, not " << options.Output
              << "\n";
    return false;
  }
  for (int i = 3; i < argc; ++i)
  {
    const std::string option = argv[i];
    if (option == "--no-reinject")
    {
      options.Reinject = false;
      continue;
    }
    if (i + 1 >= argc)
    {
      std::cerr << option << ": needs a value\n";
      return false;
    }
    const std::string value = argv[++i];
    if (option == "--harmonics")
    {
      if (!ReadNumber(option, value, options.Harmonics))
      {
        return false;
      }
      if (options.Harmonics < 1)
      {
        std::cerr << "--harmonics: at least 1, not " << options.Harmonics << "\n";
        return false;
      }
    }
    else if (option == "--threads")
    {
      if (!ReadNumber(option, value, options.Threads))
      {
        return false;
      }
      if (options.Threads < 0)
      {
        std::cerr << "--threads: at least 0 (every core), not " << options.Threads << "\n";
        return false;
      }
    }
    else if (option == "--kind")
    {
      if (!kinds.count(value))
      {
        std::cerr << "--kind: '" << value << "' is none of lowpass, highpass, bandpass, "
                  << "bandstop, enhancement, exaggeration, heat, custom\n";
        return false;
      }
      options.KindName = value;
      options.Kind = kinds.at(value);
    }
    else if (option == "--cutoff")
    {
      if (!ReadNonNegative(option, value, options.Cutoff))
      {
        return false;
      }
    }
    else if (option == "--upper")
    {
      if (!ReadNonNegative(option, value, options.Upper))
      {
        return false;
      }
    }
    else if (option == "--gain")
    {
      if (!ReadNumber(option, value, options.Gain))
      {
        return false;
      }
    }
    else if (option == "--time")
    {
      if (!ReadNonNegative(option, value, options.Time))
      {
        return false;
      }
    }
    else
    {
      std::cerr << "Unknown option " << option << "\n";
      return false;
    }
  }
  return true;
}

/// Reads a surface with the reader that its extension names, or returns null.
vtkSmartPointer<vtkPolyData> Read(const std::string& fileName)
{
  const std::string extension = Extension(fileName);
  vtkSmartPointer<vtkAlgorithm> reader;
  if (extension == "ply")
  {
    auto ply = vtkSmartPointer<vtkPLYReader>::New();
    ply->SetFileName(fileName.c_str());
    reader = ply;
  }
  else if (extension == "obj")
  {
    auto obj = vtkSmartPointer<vtkOBJReader>::New();
    obj->SetFileName(fileName.c_str());
    reader = obj;
  }
  else if (extension == "stl")
  {
    auto stl = vtkSmartPointer<vtkSTLReader>::New();
    stl->SetFileName(fileName.c_str());
    reader = stl;
  }
  else if (extension == "vtp")
  {
    auto vtp = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    vtp->SetFileName(fileName.c_str());
    reader = vtp;
  }
  else
  {
    std::cerr << "Unknown extension '" << extension << "': use .ply, .obj, .stl or .vtp\n";
    return nullptr;
  }
  reader->Update();
  vtkSmartPointer<vtkPolyData> surface = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  return surface;
}
} // anonymous namespace

int main(int argc, char* argv[])
{
  for (int i = 1; i < argc; ++i)
  {
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h")
    {
      PrintUsage(std::cout, argv[0]);
      return EXIT_SUCCESS;
    }
  }
  Options options;
  if (!Parse(argc, argv, options))
  {
    PrintUsage(std::cerr, argv[0]);
    return EXIT_FAILURE;
  }
  // Refuse an output that cannot be written before the basis is computed.
  const std::string folder =
    vtksys::SystemTools::GetFilenamePath(vtksys::SystemTools::CollapseFullPath(options.Output));
  if (!vtksys::SystemTools::FileIsDirectory(folder))
  {
    std::cerr << "Cannot write " << options.Output << ": no folder " << folder << "\n";
    return EXIT_FAILURE;
  }
  vtkSmartPointer<vtkPolyData> surface = Read(options.Input);
  if (!surface || surface->GetNumberOfPoints() == 0)
  {
    std::cerr << "No surface read from " << options.Input << "\n";
    return EXIT_FAILURE;
  }

  vtkNew<vtkTimerLog> timer;
  timer->StartTimer();
  vtkNew<vtkManifoldHarmonicBasis> basis;
  basis->SetInputData(surface);
  basis->SetNumberOfHarmonics(options.Harmonics);
  basis->SetNumberOfThreads(options.Threads);
  basis->Update();
  timer->StopTimer();
  vtkDataArray* lambda =
    basis->GetOutput()->GetFieldData()->GetArray(vtkManifoldHarmonicBasis::EigenvaluesArrayName());
  if (!lambda)
  {
    std::cerr << "The basis could not be computed.\n";
    return EXIT_FAILURE;
  }
  const vtkIdType m = lambda->GetNumberOfTuples();
  const double highest = std::sqrt(std::max(lambda->GetComponent(m - 1, 0), 0.0));
  std::cout << surface->GetNumberOfPoints() << " points, " << m << " harmonics in "
            << timer->GetElapsedTime() << " s, frequencies up to " << highest << "\n";

  vtkNew<vtkManifoldHarmonicTransform> transform;
  transform->SetInputConnection(basis->GetOutputPort());
  transform->SetNumberOfThreads(options.Threads);

  const double cutoff = options.Cutoff >= 0.0 ? options.Cutoff : 0.5 * highest;
  vtkNew<vtkSpectralFilter> filter;
  filter->SetInputConnection(transform->GetOutputPort());
  filter->SetNumberOfThreads(options.Threads);
  filter->SetFilterKind(options.Kind);
  filter->SetCutoffUnitsToAbsoluteFrequency(); // the options are frequencies
  filter->SetCutoff(cutoff);
  filter->SetUpperCutoff(options.Upper >= 0.0 ? options.Upper : 2.0 * cutoff);
  filter->SetGain(options.Gain);
  const double time =
    options.Time >= 0.0 ? options.Time : (cutoff > 0.0 ? std::log(2.0) / (cutoff * cutoff) : 0.0);
  filter->SetTime(time);
  filter->SetReinjectHighFrequencies(options.Reinject);
  filter->RemoveAllControlPoints();
  filter->AddControlPoint(0.0, 1.0);
  filter->AddControlPoint(cutoff, 0.0);

  if (!filter->GetExecutive()->Update())
  {
    std::cerr << "The spectral filter failed.\n";
    return EXIT_FAILURE;
  }

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputConnection(filter->GetOutputPort());
  writer->SetFileName(options.Output.c_str());
  // Inline binary data: VTK before 9.3.1 cannot read appended data back with expat >= 2.6.
  writer->SetDataModeToBinary();
  if (writer->Write() != 1 || writer->GetErrorCode() != vtkErrorCode::NoError)
  {
    std::cerr << "Could not write " << options.Output << "\n";
    return EXIT_FAILURE;
  }
  std::cout << "Filter " << options.KindName;
  if (options.Kind == vtkSpectralFilter::HEAT_DIFFUSION)
  {
    std::cout << ", time " << time;
  }
  else
  {
    std::cout << ", cutoff " << cutoff;
  }
  std::cout << ": wrote " << options.Output << "\n";
  return EXIT_SUCCESS;
}
