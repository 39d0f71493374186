# Copyright 2026 The mjformation Authors. Licensed under the Apache License, Version 2.0.
#
# mjformation_add_plugin(<target> SOURCES <files>... [LIBS <libraries>...] [NO_INSTALL])
#
# A plugin family as a module the runner dlopen()s: lib<target>.so, linked against
# mjformation::plugin, C++17, no undefined symbols (see below), and exactly one exported symbol, the entry
# point mjf_plugin_entry, however it was written: C++ with MJF_EXPORT_PLUGINS (plugin_util.hpp),
# C with MJF_PLUGIN_EXPORT (plugin.h) or plain C without either. C++ sources are compiled with
# hidden visibility; C sources keep the default, so a plain-C entry point is not hidden, and a
# linker version script then makes every symbol but the entry point local. `cmake --install` puts it in
# <prefix>/lib/mjformation/plugins, where an mjformation installed in the same prefix finds it
# without --plugin-path. Installed with mjformation's package (find_package(mjformation)).
function(mjformation_add_plugin target)
  cmake_parse_arguments(ARG "NO_INSTALL" "" "SOURCES;LIBS" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "mjformation_add_plugin(${target}): SOURCES is required")
  endif()
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE mjformation::plugin ${ARG_LIBS})
  target_compile_features(${target} PRIVATE cxx_std_17)
  # RUNPATH $ORIGIN: a library the family ships beside itself is found wherever the folder goes.
  set_target_properties(${target} PROPERTIES PREFIX "lib" CXX_VISIBILITY_PRESET hidden
                        BUILD_RPATH "$ORIGIN" INSTALL_RPATH "$ORIGIN")
  set(exports "${CMAKE_CURRENT_BINARY_DIR}/${target}_exports.map")
  file(WRITE "${exports}" "{ global: mjf_plugin_entry; local: *; };\n")
  target_link_options(${target} PRIVATE "-Wl,--version-script=${exports}")
  # No undefined symbols, except in mjformation's own Clang sanitizer build, whose runtime the
  # loading executable provides (MJF_MODULES_RESOLVE_AT_LOAD, set by mjformation's CMakeLists).
  if(NOT MJF_MODULES_RESOLVE_AT_LOAD)
    target_link_options(${target} PRIVATE -Wl,--no-undefined)
  endif()
  set_property(TARGET ${target} APPEND PROPERTY LINK_DEPENDS "${exports}")
  if(NOT ARG_NO_INSTALL)
    include(GNUInstallDirs)
    install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/mjformation/plugins)
  endif()
endfunction()
