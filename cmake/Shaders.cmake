# sward_add_shaders(TARGET target OUTPUT_DIR dir EMBED source.cpp SOURCES a.comp b.vert ... DEPENDS shared headers
#                   FLOW_SOURCES c.vert ...)
# Compiles GLSL to SPIR-V in the build folder at build time. FLOW_SOURCES are compiled a second time with
# SWARD_FLOW defined, as "<name>_flow.<stage>" (the truth pass's motion ground truth, shaders/shared/flow_*.glsl).
# Every shader depends on every shared include, so a change to the GPU layout header rebuilds all of them. EMBED names a C++ source holding every module as an
# array (tools/embed-spirv.py), compiled into sward_engine: programs carry their shaders and look up no folder.
# One GLSL source to `output` with `ARGN` as extra glslangValidator options (defines).
function(sward_compile_shader source output debug_flags depends)
  get_filename_component(name ${output} NAME_WLE)
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.3 -I${CMAKE_CURRENT_SOURCE_DIR} ${ARGN}
            ${debug_flags} -o ${output} ${CMAKE_CURRENT_SOURCE_DIR}/${source}
    DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${source} ${depends}
    COMMENT "GLSL ${name}"
    VERBATIM)
endfunction()

function(sward_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET;OUTPUT_DIR;EMBED" "SOURCES;DEPENDS;FLOW_SOURCES" ${ARGN})
  set(outputs)
  set(debug_flags)
  if(CMAKE_BUILD_TYPE STREQUAL "Debug")
    set(debug_flags -g)
  endif()
  foreach(source ${ARG_SOURCES})
    get_filename_component(name ${source} NAME)
    sward_compile_shader(${source} ${ARG_OUTPUT_DIR}/${name}.spv "${debug_flags}" "${ARG_DEPENDS}")
    list(APPEND outputs ${ARG_OUTPUT_DIR}/${name}.spv)
  endforeach()
  foreach(source ${ARG_FLOW_SOURCES})
    get_filename_component(stem ${source} NAME_WE)
    get_filename_component(stage ${source} LAST_EXT)
    set(output ${ARG_OUTPUT_DIR}/${stem}_flow${stage}.spv)
    sward_compile_shader(${source} ${output} "${debug_flags}" "${ARG_DEPENDS}" -DSWARD_FLOW)
    list(APPEND outputs ${output})
  endforeach()
  add_custom_command(
    OUTPUT ${ARG_EMBED}
    COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tools/embed-spirv.py ${ARG_EMBED} ${outputs}
    DEPENDS ${outputs} ${PROJECT_SOURCE_DIR}/tools/embed-spirv.py
    COMMENT "Embedding SPIR-V"
    VERBATIM)
  add_custom_target(${ARG_TARGET} ALL DEPENDS ${outputs} ${ARG_EMBED})
endfunction()
