# Included by both VTK flavours (cmake/LVDIFVTK.cmake and the ParaView plugin's
# Apps/ParaViewPlugin/CMakeLists.txt), whose module Testing folders call it.
# lvdif_add_mpi_test(<executable> SOURCES <src...> LIBRARIES <VTK modules...>
#   TESTS <name> <np> [<name> <np>...] PASS <regex> [ARGS <args...>])
# A VTK module's test program that runs under mpiexec (where Debian's VTK has
# its MPI module): one program (Testing/Support/MPITestUtil.h), one CTest test
# per rank count, passing when rank 0 prints PASS.
find_program(LVDIF_MPIEXEC_FOR_TESTS NAMES mpiexec mpirun)
function(lvdif_add_mpi_test exe)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "PASS" "SOURCES;LIBRARIES;TESTS;ARGS")
  if (NOT TARGET VTK::ParallelMPI OR NOT LVDIF_MPIEXEC_FOR_TESTS)
    return()
  endif ()
  add_executable(${exe} ${arg_SOURCES})
  target_include_directories(${exe} PRIVATE "${PROJECT_SOURCE_DIR}/Testing/Support")
  target_link_libraries(${exe} PRIVATE ${arg_LIBRARIES} VTK::ParallelMPI)
  vtk_module_autoinit(TARGETS ${exe} MODULES ${arg_LIBRARIES} VTK::ParallelMPI)
  while (arg_TESTS)
    list(POP_FRONT arg_TESTS name np)
    add_test(NAME ${name}
      COMMAND "${LVDIF_MPIEXEC_FOR_TESTS}" --allow-run-as-root --oversubscribe -np ${np} $<TARGET_FILE:${exe}> ${arg_ARGS})
    set_tests_properties(${name} PROPERTIES LABELS "vtk;mpi" TIMEOUT 60 PASS_REGULAR_EXPRESSION "${arg_PASS}")
  endwhile ()
endfunction()
