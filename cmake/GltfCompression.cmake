# The decoders for the glTF loader's compressed geometry (docs/scenes.md):
# libdraco (KHR_draco_mesh_compression) and meshoptimizer
# (EXT_meshopt_compression). Debian 12's libdraco-dev and
# libmeshoptimizer-dev install CMake package configs; when a config is
# missing, the library and header are looked up by name instead. Defines
# the interface target blurcull_gltf_compression (once).
#
# libdraco is linked from a copy of its static archive without its glTF and
# file-I/O members: Debian's libdraco (built with its glTF transcoder) holds
# its own copy of tinygltf, whose classes differ from libtinygltf's. Linked
# as is (shared, or the whole archive), the loader's tinygltf calls can land
# in draco's copy (they did: external .bin files stopped loading). The
# decoder and encoder need none of those members.

find_package(draco CONFIG QUIET)
set(blurcull_draco_hint "")
if(TARGET draco::draco_static)
  get_target_property(blurcull_draco_hint draco::draco_static IMPORTED_LOCATION_NONE)
endif()
if(blurcull_draco_hint AND EXISTS "${blurcull_draco_hint}")
  set(BLURCULL_DRACO_ARCHIVE "${blurcull_draco_hint}" CACHE FILEPATH "libdraco's static archive")
else()
  find_library(BLURCULL_DRACO_ARCHIVE NAMES libdraco.a)
endif()
find_path(BLURCULL_DRACO_INCLUDE_DIR draco/compression/decode.h)
if(NOT BLURCULL_DRACO_ARCHIVE OR NOT BLURCULL_DRACO_INCLUDE_DIR)
  message(FATAL_ERROR "blurcull: libdraco (static archive and headers) not found (Debian: libdraco-dev; "
                      "scripts/install-deps.sh installs it)")
endif()
set(blurcull_draco_copy ${CMAKE_BINARY_DIR}/blurcull_draco/libblurcull_draco.a)
if(NOT EXISTS ${blurcull_draco_copy} OR ${BLURCULL_DRACO_ARCHIVE} IS_NEWER_THAN ${blurcull_draco_copy})
  file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/blurcull_draco)
  configure_file(${BLURCULL_DRACO_ARCHIVE} ${blurcull_draco_copy} COPYONLY)
  execute_process(COMMAND ${CMAKE_AR} t ${blurcull_draco_copy} OUTPUT_VARIABLE blurcull_draco_members
                  RESULT_VARIABLE blurcull_ar_result)
  if(NOT blurcull_ar_result EQUAL 0)
    message(FATAL_ERROR "blurcull: cannot list ${BLURCULL_DRACO_ARCHIVE} with ${CMAKE_AR}")
  endif()
  string(REPLACE "\n" ";" blurcull_draco_members "${blurcull_draco_members}")
  list(FILTER blurcull_draco_members INCLUDE REGEX "gltf|_io\\.cc\\.o$")
  if(blurcull_draco_members)
    execute_process(COMMAND ${CMAKE_AR} d ${blurcull_draco_copy} ${blurcull_draco_members}
                    RESULT_VARIABLE blurcull_ar_result)
    if(NOT blurcull_ar_result EQUAL 0)
      message(FATAL_ERROR "blurcull: cannot remove draco's glTF members from ${blurcull_draco_copy}")
    endif()
  endif()
endif()
add_library(blurcull_draco STATIC IMPORTED GLOBAL)
set_target_properties(blurcull_draco PROPERTIES IMPORTED_LOCATION ${blurcull_draco_copy}
                      INTERFACE_INCLUDE_DIRECTORIES ${BLURCULL_DRACO_INCLUDE_DIR})
set(blurcull_draco_target blurcull_draco)

find_package(meshoptimizer CONFIG QUIET)
if(TARGET meshoptimizer::meshoptimizer)
  set(blurcull_meshopt_target meshoptimizer::meshoptimizer)
else()
  find_path(BLURCULL_MESHOPT_INCLUDE_DIR meshoptimizer.h)
  find_library(BLURCULL_MESHOPT_LIBRARY meshoptimizer)
  if(NOT BLURCULL_MESHOPT_INCLUDE_DIR OR NOT BLURCULL_MESHOPT_LIBRARY)
    message(FATAL_ERROR "blurcull: meshoptimizer not found (Debian: libmeshoptimizer-dev; scripts/install-deps.sh "
                        "installs it)")
  endif()
  add_library(blurcull_meshopt UNKNOWN IMPORTED)
  set_target_properties(blurcull_meshopt PROPERTIES IMPORTED_LOCATION ${BLURCULL_MESHOPT_LIBRARY}
                        INTERFACE_INCLUDE_DIRECTORIES ${BLURCULL_MESHOPT_INCLUDE_DIR})
  set(blurcull_meshopt_target blurcull_meshopt)
endif()

add_library(blurcull_gltf_compression INTERFACE)
target_link_libraries(blurcull_gltf_compression INTERFACE ${blurcull_draco_target} ${blurcull_meshopt_target})
