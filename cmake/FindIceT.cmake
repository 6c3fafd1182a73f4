# FindIceT: the IceT image compositing library (Moreland et al., Sandia), as
# Lucent's distributed renderer uses it: IceT's core and its MPI communicator.
#
# A standalone IceT installation exports IceTCore and IceTMPI through its
# package configuration; Debian 12 ships IceT only inside ParaView 5.11 (package
# paraview-dev: headers under include/paraview-<version>/vtkicet/src/include,
# libraries libvtkIceTCore-pv<version>). ParaView's own package configuration
# cannot be loaded without its Python modules, so this module looks for the
# bundled copy by pattern, for whichever ParaView version is installed.
#
# Result: IceT_FOUND, IceT_INCLUDE_DIR, and the imported target IceT::IceT
# (core and MPI layer; the caller links MPI itself).

find_package(IceT CONFIG QUIET NO_MODULE)
if(TARGET IceTCore AND TARGET IceTMPI)
  if(NOT TARGET IceT::IceT)
    add_library(IceT::IceT INTERFACE IMPORTED)
    set_target_properties(IceT::IceT PROPERTIES INTERFACE_LINK_LIBRARIES "IceTMPI;IceTCore")
  endif()
  set(IceT_FOUND TRUE)
  return()
endif()

file(GLOB _icet_include_candidates
  /usr/include/paraview-*/vtkicet/src/include
  /usr/local/include/paraview-*/vtkicet/src/include)
find_path(IceT_INCLUDE_DIR NAMES IceT.h IceTMPI.h
  HINTS ${_icet_include_candidates} PATH_SUFFIXES icet IceT)
if(IceT_INCLUDE_DIR)
  # The configured IceTConfig.h of ParaView's copy sits in its build include folder.
  get_filename_component(_icet_root "${IceT_INCLUDE_DIR}/../.." ABSOLUTE)
  find_path(IceT_CONFIG_INCLUDE_DIR NAMES IceTConfig.h
    HINTS "${IceT_INCLUDE_DIR}" "${_icet_root}/include" "${_icet_root}")
endif()

file(GLOB _icet_core_candidates
  /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/libvtkIceTCore-pv*.so
  /usr/lib/libvtkIceTCore-pv*.so /usr/local/lib/libvtkIceTCore-pv*.so)
file(GLOB _icet_mpi_candidates
  /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/libvtkIceTMPI-pv*.so
  /usr/lib/libvtkIceTMPI-pv*.so /usr/local/lib/libvtkIceTMPI-pv*.so)
list(SORT _icet_core_candidates ORDER DESCENDING)
list(SORT _icet_mpi_candidates ORDER DESCENDING)
find_library(IceT_CORE_LIBRARY NAMES IceTCore HINTS ${_icet_core_candidates})
if(NOT IceT_CORE_LIBRARY AND _icet_core_candidates)
  list(GET _icet_core_candidates 0 _first)
  set(IceT_CORE_LIBRARY "${_first}" CACHE FILEPATH "IceT core library" FORCE)
endif()
find_library(IceT_MPI_LIBRARY NAMES IceTMPI HINTS ${_icet_mpi_candidates})
if(NOT IceT_MPI_LIBRARY AND _icet_mpi_candidates)
  list(GET _icet_mpi_candidates 0 _first)
  set(IceT_MPI_LIBRARY "${_first}" CACHE FILEPATH "IceT MPI library" FORCE)
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(IceT
  REQUIRED_VARS IceT_INCLUDE_DIR IceT_CONFIG_INCLUDE_DIR IceT_CORE_LIBRARY IceT_MPI_LIBRARY)

if(IceT_FOUND AND NOT TARGET IceT::IceT)
  add_library(IceT::Core UNKNOWN IMPORTED)
  set_target_properties(IceT::Core PROPERTIES IMPORTED_LOCATION "${IceT_CORE_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${IceT_INCLUDE_DIR};${IceT_CONFIG_INCLUDE_DIR}")
  add_library(IceT::MPI UNKNOWN IMPORTED)
  set_target_properties(IceT::MPI PROPERTIES IMPORTED_LOCATION "${IceT_MPI_LIBRARY}"
    INTERFACE_LINK_LIBRARIES IceT::Core)
  add_library(IceT::IceT INTERFACE IMPORTED)
  set_target_properties(IceT::IceT PROPERTIES INTERFACE_LINK_LIBRARIES "IceT::MPI;IceT::Core")
endif()
mark_as_advanced(IceT_INCLUDE_DIR IceT_CONFIG_INCLUDE_DIR IceT_CORE_LIBRARY IceT_MPI_LIBRARY)
