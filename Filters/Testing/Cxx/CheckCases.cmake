# The cases a test file of the filters runs (its case table, printed by `<driver> <File> --cases`)
# must be those Filters/Testing/Cxx/CMakeLists.txt registers as CTests, so that no case goes
# unrun and no registered name is unknown:
#   cmake -DDRIVER=<vtkManifoldHarmonicsCxxTests> -DFILE=<TestName> -DCASES=<a|b|...> -P CheckCases.cmake
if (NOT DEFINED DRIVER OR NOT DEFINED FILE OR NOT DEFINED CASES)
  message(FATAL_ERROR "CheckCases.cmake needs -DDRIVER, -DFILE and -DCASES")
endif ()
execute_process(
  COMMAND "${DRIVER}" "${FILE}" --cases
  RESULT_VARIABLE _result
  OUTPUT_VARIABLE _output)
string(REGEX MATCHALL "case [A-Za-z0-9_]+" _lines "${_output}")
set(_listed)
foreach (_line IN LISTS _lines)
  string(REPLACE "case " "" _name "${_line}")
  list(APPEND _listed "${_name}")
endforeach ()
string(REPLACE "|" ";" _registered "${CASES}")
list(SORT _listed)
list(SORT _registered)
if (NOT _result EQUAL 0)
  message(FATAL_ERROR "${FILE} --cases failed: ${_result}")
elseif (NOT _listed STREQUAL _registered)
  message(FATAL_ERROR "${FILE} runs the cases '${_listed}', CTest registers '${_registered}'")
endif ()
message("${FILE}: ${_listed}")
