# Included from runner/CMakeLists.txt.
add_library(mjf_runner STATIC
  ${CMAKE_CURRENT_SOURCE_DIR}/src/actuation.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/agent_channel.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/bench.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/cli.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/config.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/control_tick.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/follower_motion.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/interrupt.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/leader_acceleration.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/metrics.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/transient_metrics.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/vehicle_accel_limit.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/mujoco_errors.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/network_config.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/output.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/paths.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/plugin_host.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/recorders.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/realism_config.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/run.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/scene.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/shape_config.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/simulation.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/stage_factory.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/summary.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/sweep.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/vehicle_binding.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/vehicle_adapter.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/frame_view.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/replay.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/replay_cli.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/sweep_stats.cc)
target_include_directories(mjf_runner PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
target_compile_definitions(mjf_runner PRIVATE
  MJF_VERSION="${PROJECT_VERSION}"
  MJF_PLUGIN_BUILD_DIR="${MJF_PLUGIN_BUILD_DIR}"
  MJF_SOURCE_MJCF_DIR="${CMAKE_SOURCE_DIR}/mjcf")
find_package(OpenSSL REQUIRED)
find_package(tinyxml2 QUIET)
if(TARGET tinyxml2::tinyxml2)
  set(MJF_TINYXML2 tinyxml2::tinyxml2)
else()
  set(MJF_TINYXML2 tinyxml2)
endif()
target_link_libraries(mjf_runner
  PUBLIC mjf_plugin_abi mjf_realism mjf_network mujoco::mujoco nlohmann_json::nlohmann_json CLI11::CLI11
  PRIVATE mjf_formation_core mjf_render PkgConfig::TOMLPP fmt::fmt OpenSSL::Crypto ${MJF_TINYXML2}
          ${CMAKE_DL_LIBS} Threads::Threads)

add_executable(mjformation ${CMAKE_CURRENT_SOURCE_DIR}/src/main.cc)
target_link_libraries(mjformation PRIVATE mjf_runner)
# Plugins are modules loaded at run time, but `make mjformation` should build them too.
foreach(plugin mjf_guidance mjf_formation mjf_attitude)
  if(TARGET ${plugin})
    add_dependencies(mjformation ${plugin})
  endif()
endforeach()
install(TARGETS mjformation RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/mjcf/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mjformation/mjcf
        FILES_MATCHING PATTERN "*.xml" PATTERN "*.png" PATTERN "*.stl" PATTERN "*.obj")

# mjformation-view: the window of `mjformation view` and `mjformation replay` (GLFW + GLX). A
# separate executable, so that the runner (OSMesa, headless) never loads a second GL
# implementation; it links no offscreen code (--as-needed drops libOSMesa).
find_package(glfw3 3.3 QUIET)
if(TARGET glfw)
  add_executable(mjformation-view ${CMAKE_CURRENT_SOURCE_DIR}/viewer/viewer.cc)
  target_link_libraries(mjformation-view PRIVATE mjf_runner mjf_render glfw fmt::fmt
                        nlohmann_json::nlohmann_json CLI11::CLI11)
  target_link_options(mjformation-view PRIVATE -Wl,--as-needed)
  set_target_properties(mjformation-view PROPERTIES RUNTIME_OUTPUT_DIRECTORY
                                                    ${CMAKE_CURRENT_BINARY_DIR})
  add_dependencies(mjformation mjformation-view)
  install(TARGETS mjformation-view RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
else()
  message(STATUS "GLFW not found (Debian: libglfw3-dev): no mjformation-view window")
endif()

# The MPI transport of `sweep` (issue 11): a module the runner dlopen()s only under mpirun, so
# the executable never needs MPI. Built when Open MPI (libopenmpi-dev) is installed. Kept out of
# the plugin folder, whose every library the plugin registry loads.
find_package(MPI COMPONENTS C QUIET)
set(MJF_MPI_MODULE_BUILD_PATH ${CMAKE_BINARY_DIR}/lib/libmjf_sweep_mpi.so)
target_compile_definitions(mjf_runner PRIVATE
  MJF_MPI_MODULE_BUILD_PATH="${MJF_MPI_MODULE_BUILD_PATH}"
  MJF_MPI_MODULE_INSTALL_PATH="${CMAKE_INSTALL_FULL_LIBDIR}/mjformation/libmjf_sweep_mpi.so")
if(MPI_C_FOUND)
  add_library(mjf_sweep_mpi MODULE ${CMAKE_CURRENT_SOURCE_DIR}/mpi/sweep_mpi.cc)
  target_include_directories(mjf_sweep_mpi PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(mjf_sweep_mpi PRIVATE MPI::MPI_C)
  # The C API only (mpi.h pulls in the removed C++ bindings otherwise); unresolved = link error.
  target_compile_definitions(mjf_sweep_mpi PRIVATE OMPI_SKIP_MPICXX=1 MPICH_SKIP_MPICXX=1)
  target_link_options(mjf_sweep_mpi PRIVATE -Wl,--no-undefined)
  set_target_properties(mjf_sweep_mpi PROPERTIES PREFIX "lib"
    LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/lib CXX_VISIBILITY_PRESET hidden)
  add_dependencies(mjformation mjf_sweep_mpi)
  install(TARGETS mjf_sweep_mpi LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/mjformation)
else()
  message(STATUS "Open MPI not found: `mpirun ... mjformation sweep` unavailable "
                 "(apt-get install libopenmpi-dev)")
endif()
