// SPDX-FileCopyrightText: Copyright (c) Manifold Harmonics developers
// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkManifoldHarmonicsAlgorithm
 * @brief   The contract every filter of the module keeps: output like input, an optional table
 *          port, threads, errors, progress and abort.
 *
 * vtkManifoldHarmonicBasis, vtkManifoldHarmonicTransform, vtkSpectralFilter,
 * vtkManifoldHarmonicSmoothing, vtkSpectralDescriptors and vtkFunctionalMap (whose second input,
 * the source, it reads itself) derive from this class, which holds what they share, each rule
 * once:
 *
 * - Output port 0 is a point set of the input's type (vtkPolyData in, vtkPolyData out, and so on
 *   for every vtkPointSet); a filter built with a table port has a vtkTable on port 1 (the
 *   spectrum of the transform and the spectral filter, ShapeDNA of the descriptors).
 * - NumberOfThreads (default 0: every core) is passed to the core's kernels.
 * - RequestData runs the subclass's Execute and applies one rule afterwards: after an error
 *   (Execute returned 0, or an exception reached it) every output port is empty and the request
 *   fails, with the exception's text in a vtkErrorMacro (DescribeFailure, the one place where
 *   the core's exceptions become messages); after an abort (AbortExecute in a serial run, or the
 *   core's spectral::Cancelled) every output port is empty and the request succeeds, as VTK's
 *   executive has it for an aborted filter. An abort stops the request it was asked in: the next
 *   request starts with AbortExecute cleared (VTK 9.2 leaves it set after an aborted run), and
 *   runs again, with everything downstream (GetMTime: VTK 9.2's executive keeps the emptied
 *   outputs as up to date).
 * - A distributed run (several processes, vtkMultiProcessController) finishes its collective
 *   steps on every process: AbortExecute is honoured in serial runs only (AbortRequested).
 * - The core reports progress, steps and warnings, and polls the abort flag, through the
 *   spectral::Monitor of MakeMonitor.
 *
 * This is an abstract class: use one of the filters.
 */
#ifndef vtkManifoldHarmonicsAlgorithm_h
#define vtkManifoldHarmonicsAlgorithm_h

#include "vtkManifoldHarmonicsModule.h" // For export macro
#include "vtkPointSetAlgorithm.h"
#include "vtkTimeStamp.h"   // For the request after an abort
#include "vtkWeakPointer.h" // For the request after an abort

#include <exception>  // For DescribeFailure
#include <functional> // For Guard
#include <string>     // For DescribeFailure

class vtkMultiProcessController;
class vtkTable;

namespace spectral
{
struct Monitor;
}

class VTKMANIFOLDHARMONICS_EXPORT vtkManifoldHarmonicsAlgorithm : public vtkPointSetAlgorithm
{
public:
  vtkTypeMacro(vtkManifoldHarmonicsAlgorithm, vtkPointSetAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The threads of the core's kernels. 0 (the default) uses every core; a positive value caps
   * the threads. The results do not depend on it beyond rounding.
   */
  vtkSetClampMacro(NumberOfThreads, int, 0, VTK_INT_MAX);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /**
   * Whether the running request should stop: AbortExecute in a serial run; never in a
   * distributed one, whose collective steps must finish on every process.
   */
  bool AbortRequested();

  /**
   * The modified time; after an aborted request, once the executive has marked its emptied
   * outputs as generated, it moves past them (once), so that the next Update runs the filter
   * again, and the filters downstream, without a change of setting.
   */
  vtkMTimeType GetMTime() override;

protected:
  /// The output ports a filter has: the point set alone, or a table on port 1 as well.
  enum OutputPorts
  {
    POINT_SET_ONLY = 1,
    POINT_SET_AND_TABLE = 2
  };
  explicit vtkManifoldHarmonicsAlgorithm(OutputPorts ports = POINT_SET_ONLY);
  ~vtkManifoldHarmonicsAlgorithm() override;

  /**
   * The filter's work on one request. `table` is null without a table port. Returns 1 on success
   * (or after an abort), 0 after an error it reported; may throw (see DescribeFailure).
   */
  virtual int Execute(vtkPointSet* input, vtkPointSet* output, vtkTable* table) = 0;

  /// What the filter does, as the start of its error messages: "<WorkName> failed: ...".
  virtual const char* GetWorkName() = 0;

  /**
   * The error message of an exception (the one place where the core's exceptions become text).
   * The default is "<WorkName> failed: <what>"; a filter adds the cases only it knows.
   */
  virtual std::string DescribeFailure(const std::exception& e);

  /**
   * Runs `work`: an exception becomes an error message (DescribeFailure), spectral::Cancelled
   * marks the request as aborted. \return true when `work` returned normally.
   */
  bool Guard(const std::function<void()>& work);

  /**
   * The core's progress in [0, 1] scaled to [0, `scale`] of the filter's, its step names as
   * progress text, its warnings as vtkWarningMacro, and the filter's abort flag.
   */
  spectral::Monitor MakeMonitor(double scale = 1.0);

  /**
   * An observer of the WarningEvent (or ErrorEvent) of an internal filter (the basis of
   * vtkManifoldHarmonicSmoothing and vtkFunctionalMap): its warnings (errors) become this
   * filter's, so that this filter's observers see them (and the output window shows them once,
   * as it would the internal filter's).
   */
  void ForwardWarning(vtkObject* caller, unsigned long event, void* data);

  /// The controller of a distributed run (more than one process), or null.
  static vtkMultiProcessController* GetDistributedController();

  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestDataObject(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request,
    vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  int NumberOfThreads;

private:
  /// Set when the core threw spectral::Cancelled during the request.
  bool CancelRequested;
  /// When the last request was aborted, and its output port 0 (null once GetMTime moved past it).
  vtkTimeStamp AbortTime;
  vtkWeakPointer<vtkDataObject> AbortedOutput;

  vtkManifoldHarmonicsAlgorithm(const vtkManifoldHarmonicsAlgorithm&) = delete;
  void operator=(const vtkManifoldHarmonicsAlgorithm&) = delete;
};

#endif
