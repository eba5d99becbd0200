# The one list of the spectral core's files, relative to this folder. Included by the VTK module
# (Filters/CMakeLists.txt), by the core's own build without VTK (Testing/Core/CMakeLists.txt) and,
# through the core library of that build, by the benchmark (bench/).
#
#   Common/      types, progress and cancellation, threads: what every part uses
#   Operators/   the discrete Laplacians of each kind of mesh (stiffness, mass, what was left out)
#   Solver/      the eigensolver behind one interface: factorizations, bands, verification
#   Filtering/   transforms, filter gains and the re-injection of what the basis misses
set(spectral_core_sources
  Operators/Operators.cxx
  Operators/IntrinsicDelaunay.cxx
  Solver/EigenSolver.cxx
  Solver/Bands.cxx
  Solver/BlockLanczos.cxx
  Solver/SpectraBand.cxx
  Solver/LanczosKernels.cxx
  Solver/Factorization.cxx
  Solver/Verification.cxx
  Solver/SupernodalLDLT.cxx
  Solver/BlockProducts.cxx
  Solver/Memory.cxx
  Filtering/Transfer.cxx
  )
set(spectral_core_headers
  Common/Mesh.h
  Common/Monitor.h
  Common/Threads.h
  Operators/Operators.h
  Operators/IntrinsicDelaunay.h
  Solver/EigenSolver.h
  Solver/Bands.h
  Solver/BlockLanczos.h
  Solver/SpectraBand.h
  Solver/BandWorkspace.h
  Solver/LanczosKernels.h
  Solver/MassMatrix.h
  Solver/Factorization.h
  Solver/Verification.h
  Solver/Diagnostics.h
  Solver/SupernodalLDLT.h
  Solver/BlockProducts.h
  Solver/Memory.h
  Filtering/Transfer.h
  )
