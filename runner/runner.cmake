# Included from runner/CMakeLists.txt.
add_library(mjf_runner STATIC
  ${CMAKE_CURRENT_SOURCE_DIR}/src/actuation.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/agent_channel.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/bench.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/cli.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/config.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/control_tick.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/interrupt.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/metrics.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/mujoco_errors.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/network_config.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/output.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/paths.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/plugin_host.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/recorders.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/run.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/scene.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/shape_config.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/simulation.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/stage_factory.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/summary.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/sweep.cc
  ${CMAKE_CURRENT_SOURCE_DIR}/src/vehicle_binding.cc)
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
  PUBLIC mjf_plugin_abi mjf_network mujoco::mujoco nlohmann_json::nlohmann_json CLI11::CLI11
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
