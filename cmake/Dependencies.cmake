# Every external library the toolchain uses, found once here. A missing one
# stops the configure step with the Debian package that provides it.

macro(dem_require found what package)
  if(NOT ${found})
    message(FATAL_ERROR
      "${what} not found. Install it with:\n"
      "  apt-get install ${package}\n"
      "(or run tools/deps, which installs everything the build needs)")
  endif()
endmacro()

find_package(OpenMP COMPONENTS C CXX)
dem_require(OpenMP_C_FOUND "OpenMP (C)" "gcc")
find_package(Threads REQUIRED)

find_package(HDF5 COMPONENTS C HL)
dem_require(HDF5_FOUND "HDF5 C library and its high-level library" "libhdf5-dev")
add_library(dem_hdf5 INTERFACE)
target_include_directories(dem_hdf5 SYSTEM INTERFACE ${HDF5_INCLUDE_DIRS})
target_compile_definitions(dem_hdf5 INTERFACE ${HDF5_DEFINITIONS})
# A program whose DEM_HDF5_PARALLEL property is set (solve, built with MPI)
# links parallel HDF5 instead (below); everything is compiled against the
# serial headers, which declare the same functions (the parallel headers
# add only MPI's), and only solve/h5mpi.c uses the parallel ones.
set(dem_parallel "$<BOOL:$<TARGET_PROPERTY:DEM_HDF5_PARALLEL>>")
foreach(lib ${HDF5_HL_LIBRARIES} ${HDF5_C_LIBRARIES})
  target_link_libraries(dem_hdf5 INTERFACE "$<$<NOT:${dem_parallel}>:${lib}>")
endforeach()

find_package(ZLIB)
dem_require(ZLIB_FOUND "zlib" "zlib1g-dev")

find_package(cJSON QUIET)
find_path(CJSON_HEADER cjson/cJSON.h)
dem_require(CJSON_HEADER "cJSON" "libcjson-dev")
add_library(dem_cjson INTERFACE)
target_link_libraries(dem_cjson INTERFACE cjson)

find_path(GMSH_INCLUDE_DIR gmshc.h)
find_library(GMSH_LIBRARY gmsh)
dem_require(GMSH_INCLUDE_DIR "gmsh C API header gmshc.h" "libgmsh-dev")
dem_require(GMSH_LIBRARY "gmsh library" "libgmsh-dev")
add_library(dem_gmsh INTERFACE)
target_include_directories(dem_gmsh SYSTEM INTERFACE ${GMSH_INCLUDE_DIR})
target_link_libraries(dem_gmsh INTERFACE ${GMSH_LIBRARY})

set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)
find_package(CGAL QUIET)
dem_require(CGAL_FOUND "CGAL" "libcgal-dev")

find_package(VTK 9 QUIET COMPONENTS CommonCore CommonDataModel IOXML IOImage)
dem_require(VTK_FOUND "VTK 9" "libvtk9-dev")

find_library(MATH_LIBRARY m)

# NLopt (calibrate's search), found through its pkg-config file.
find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  pkg_check_modules(NLOPT QUIET IMPORTED_TARGET nlopt)
endif()
dem_require(NLOPT_FOUND "NLopt" "libnlopt-dev")
add_library(dem_nlopt INTERFACE)
target_link_libraries(dem_nlopt INTERFACE PkgConfig::NLOPT)

# MPI (OpenMPI) and parallel HDF5 for solve's ranks: DEM_MPI=AUTO builds
# with them when both are installed (tools/deps installs them), ON requires
# them, OFF builds without.
# A solve built without MPI runs as one process and says so when a launcher
# starts it as several.
set(DEM_MPI AUTO CACHE STRING "Build solve with MPI (OpenMPI): AUTO, ON or OFF")
set_property(CACHE DEM_MPI PROPERTY STRINGS AUTO ON OFF)
add_library(dem_mpi INTERFACE)
if(NOT DEM_MPI STREQUAL "OFF")
  find_package(MPI COMPONENTS C QUIET)
  if(DEM_MPI STREQUAL "ON")
    dem_require(MPI_C_FOUND "MPI (OpenMPI)" "libopenmpi-dev openmpi-bin libhdf5-openmpi-dev")
  endif()
  # Parallel HDF5 (OpenMPI's build), with which every rank writes its
  # own rows of the one run file.
  if(PkgConfig_FOUND)
    pkg_check_modules(HDF5_PAR QUIET hdf5-openmpi)
  endif()
  if(HDF5_PAR_FOUND)
    find_library(HDF5_PAR_LIBRARY hdf5 PATHS ${HDF5_PAR_LIBRARY_DIRS} NO_DEFAULT_PATH)
    find_library(HDF5_PAR_HL_LIBRARY hdf5_hl PATHS ${HDF5_PAR_LIBRARY_DIRS} NO_DEFAULT_PATH)
  endif()
  if(DEM_MPI STREQUAL "ON")
    dem_require(HDF5_PAR_HL_LIBRARY "parallel HDF5 (OpenMPI)" "libhdf5-openmpi-dev")
  endif()
  if(MPI_C_FOUND AND HDF5_PAR_LIBRARY AND HDF5_PAR_HL_LIBRARY)
    target_link_libraries(dem_hdf5 INTERFACE
      "$<${dem_parallel}:${HDF5_PAR_HL_LIBRARY}>" "$<${dem_parallel}:${HDF5_PAR_LIBRARY}>")
    # What solve/h5mpi.c, alone, is compiled against.
    add_library(dem_hdf5_parallel INTERFACE)
    target_include_directories(dem_hdf5_parallel SYSTEM INTERFACE ${HDF5_PAR_INCLUDE_DIRS})
    target_link_libraries(dem_hdf5_parallel INTERFACE MPI::MPI_C)
    target_link_libraries(dem_mpi INTERFACE MPI::MPI_C)
    target_compile_definitions(dem_mpi INTERFACE DEM_MPI)
    set(DEM_WITH_MPI ON)
  endif()
endif()
