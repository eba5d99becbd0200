# The one list of the spectral core's files, relative to this folder, compiled once into the
# library ManifoldHarmonicsSpectralCore by CMakeLists.txt beside it (used by the VTK module, the
# core's tests in Testing/Core and the benchmark in bench/).
#
#   Basis.h      the one entry point: mesh + options + monitor -> verified basis
#   Problem.h    its problem stage: checks, unit scale, operators, clamps, memory
#   Streaming.h  filtering signals while the basis streams (BasisSink), never holding it
#   Common/      types, defaults, progress and cancellation, threads: what every part uses
#   Operators/   the discrete Laplacians of each kind of mesh (stiffness, mass, what was left out)
#   Solver/      the eigensolver behind one interface: factorizations, bands, verification,
#                acceptance (accept / relax / fail, signs, Gram check)
#   Filtering/   transforms, filter gains and the re-injection of what the basis misses
#   Distributed/ the SLEPc/PETSc engine over MPI (below, built only with SLEPc)
set(spectral_core_sources
  Basis.cxx
  Problem.cxx
  Common/BasisFile.cxx
  Streaming.cxx
  Common/Seams.cxx
  Common/Threads.cxx
  Operators/Laplacian.cxx
  Operators/Operators.cxx
  Operators/IntrinsicDelaunay.cxx
  Operators/NearestNeighbors.cxx
  Operators/PointCloud.cxx
  Solver/Components.cxx
  Solver/EigenSolver.cxx
  Solver/Bands.cxx
  Solver/BlockLanczos.cxx
  Solver/SpectraBand.cxx
  Solver/LanczosKernels.cxx
  Solver/Factorization.cxx
  Solver/Verification.cxx
  Solver/Acceptance.cxx
  Solver/SupernodalLDLT.cxx
  Solver/BlockProducts.cxx
  Solver/Memory.cxx
  Filtering/Transfer.cxx
  Filtering/Descriptors.cxx
  Filtering/FunctionalMap.cxx
  )
set(spectral_core_headers
  Basis.h
  Problem.h
  Streaming.h
  Common/Constants.h
  Common/Defaults.h
  Common/Eigenvalues.h
  Operators/Laplacian.h
  Common/Mesh.h
  Common/BasisFile.h
  Common/Seams.h
  Common/Monitor.h
  Common/Threads.h
  Operators/Operators.h
  Operators/IntrinsicDelaunay.h
  Operators/NearestNeighbors.h
  Operators/PointCloud.h
  Solver/Components.h
  Solver/EigenSolver.h
  Solver/Bands.h
  Solver/BlockLanczos.h
  Solver/SpectraBand.h
  Solver/BandWorkspace.h
  Solver/LanczosKernels.h
  Solver/MassMatrix.h
  Solver/Factorization.h
  Solver/Verification.h
  Solver/Acceptance.h
  Solver/Diagnostics.h
  Solver/SupernodalLDLT.h
  Solver/BlockProducts.h
  Solver/Memory.h
  Filtering/Transfer.h
  Filtering/Descriptors.h
  Filtering/FunctionalMap.h
  )
# The distributed engine on SLEPc/PETSc (Distributed/Solve.h), without VTK: built only when the
# top level finds SLEPc (MANIFOLDHARMONICS_HAS_SLEPC), by the VTK module (Filters/CMakeLists.txt)
# and by the core's tests (Testing/Core/CMakeLists.txt, TestDistributed under mpiexec).
set(spectral_distributed_sources
  Distributed/Petsc.cxx
  Distributed/Numbering.cxx
  Distributed/Assembly.cxx
  Distributed/Pairs.cxx
  Distributed/Solve.cxx
  )
set(spectral_distributed_headers
  Distributed/Petsc.h
  Distributed/Numbering.h
  Distributed/Assembly.h
  Distributed/Pairs.h
  Distributed/Solve.h
  )
