# Finds OpenVDB for the optional interop module IO/OpenVDB.
# Debian ships OpenVDB without a config file, only a FindOpenVDB.cmake module
# (which needs libboost-iostreams-dev), so that module's folder is put on the
# module path. Sets LVDIF_HAVE_OPENVDB (and LVDIF_VDB_PRINT, OpenVDB's own
# checker, for the tests); cmake/LVDIFVTK.cmake leaves IO/OpenVDB out when it is OFF.
set(LVDIF_HAVE_OPENVDB OFF)
if (LVDIF_OPENVDB)
  if (NOT TARGET OpenVDB::openvdb)
    find_file(LVDIF_FIND_OPENVDB FindOpenVDB.cmake
      PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB /usr/local/lib/cmake/OpenVDB NO_DEFAULT_PATH)
    if (LVDIF_FIND_OPENVDB)
      get_filename_component(dir "${LVDIF_FIND_OPENVDB}" DIRECTORY)
      list(APPEND CMAKE_MODULE_PATH "${dir}")
      find_package(OpenVDB QUIET)
    endif ()
  endif ()
  if (TARGET OpenVDB::openvdb)
    set(LVDIF_HAVE_OPENVDB ON)
    find_program(LVDIF_VDB_PRINT vdb_print)
  else ()
    message(STATUS "LVDIF: OpenVDB not found (libopenvdb-dev, libboost-iostreams-dev): IO/OpenVDB skipped")
  endif ()
endif ()
