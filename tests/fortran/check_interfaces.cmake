# ctest -P script: the Fortran module mirrors include/anitet.h (HEADER=..., FORTRAN=...).
# Every function declared with ANITET_API must have an interface bound to its name, and every
# ANITET_ERR_* / version / struct-version constant must have the same value in the module.
# Optional: EXCLUDE, functions Fortran cannot call (anitet_mpi.h's MPI_Comm ones, bound through
# their _f variants); MIN_FUNCTIONS, the fewest declarations expected (default 30: a check that
# the header was parsed at all).
file(READ "${HEADER}" header)
file(READ "${FORTRAN}" fortran)
string(TOLOWER "${fortran}" fortran_lower)

string(REGEX MATCHALL "ANITET_API[^;(]*[ *](anitet_[a-z0-9_]+)\\(" decls "${header}")
set(functions "")
foreach(decl IN LISTS decls)
  string(REGEX MATCH "(anitet_[a-z0-9_]+)\\($" m "${decl}")
  list(APPEND functions "${CMAKE_MATCH_1}")
endforeach()
list(REMOVE_ITEM functions ${EXCLUDE})
if(NOT DEFINED MIN_FUNCTIONS)
  set(MIN_FUNCTIONS 30)
endif()
list(LENGTH functions n)
if(n LESS MIN_FUNCTIONS)
  message(FATAL_ERROR "found only ${n} functions in ${HEADER}: the parser is out of date")
endif()

set(missing "")
foreach(f IN LISTS functions)
  string(FIND "${fortran_lower}" "bind(c, name=\"${f}\")" pos)
  if(pos EQUAL -1)
    list(APPEND missing "${f}")
  endif()
endforeach()

# Interfaces in the module that the header no longer declares.
string(REGEX MATCHALL "bind\\(c, name=\"anitet_[a-z0-9_]+\"\\)" binds "${fortran_lower}")
set(stale "")
foreach(b IN LISTS binds)
  string(REGEX MATCH "anitet_[a-z0-9_]+" name "${b}")
  list(FIND functions "${name}" idx)
  if(idx EQUAL -1)
    list(APPEND stale "${name}")
  endif()
endforeach()

# Integer constants: "#define ANITET_X (-n)" or "#define ANITET_X n".
string(REGEX MATCHALL "#define (ANITET_(ERR_[A-Z_]+|OK|LOG_[A-Z]+|LAYERS_[A-Z_]+|VERSION_MAJOR|VERSION_MINOR|VERSION_PATCH|OPTIONS_VERSION|QUALITY_VERSION|PARTITION_[A-Z]+_VERSION|HALO_[A-Z_]+|TYPE_[A-Z0-9]+|PART_[A-Z_]+|FIELD_[A-Z_]+|MPI_EXCHANGE_TAG|MESH2D_OPTIONS_VERSION|GEO_[A-Z]+)) \\(?-?[0-9]+\\)?" defines "${header}")
set(mismatched "")
foreach(d IN LISTS defines)
  string(REGEX MATCH "#define (ANITET_[A-Z0-9_]+) \\(?(-?[0-9]+)\\)?" m "${d}")
  set(name "${CMAKE_MATCH_1}")
  set(value "${CMAKE_MATCH_2}")
  string(REGEX MATCH "::[ ]*${name}[ ]*=[ ]*(-?[0-9]+)" fm "${fortran}")
  if(NOT fm OR NOT CMAKE_MATCH_1 STREQUAL value)
    list(APPEND mismatched "${name}=${value}")
  endif()
endforeach()
list(LENGTH defines nd)

if(missing OR stale OR mismatched)
  message(FATAL_ERROR "Fortran module and C header differ:\n"
    "  functions without a Fortran interface: ${missing}\n"
    "  Fortran interfaces to no header function: ${stale}\n"
    "  constants missing or different in Fortran: ${mismatched}")
endif()
message(STATUS "${n} functions and ${nd} constants match")
