# gusuku_embed_shaders(TARGET <name> SOURCES <a.comp> ...)
#
# Compiles each GLSL compute shader to SPIR-V with glslangValidator at build time and writes it as a C++
# header (`<stem>_spv.h` holding `static const uint32_t k<Stem>Spirv[]`), so that binaries carry their shaders
# and need no shader files at run time. Creates an INTERFACE library <name> whose include path holds the
# headers. Shared GLSL chunks live in shaders/include and are tracked as dependencies of every shader.
function(gusuku_embed_shaders)
  cmake_parse_arguments(ARG "" "TARGET" "SOURCES" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${out_dir})
  file(GLOB shared_chunks ${PROJECT_SOURCE_DIR}/shaders/include/*.glsl)
  set(headers)
  foreach(src ${ARG_SOURCES})
    get_filename_component(stem ${src} NAME_WE)
    # snake_case stem -> CamelCase variable name
    string(REPLACE "_" ";" parts ${stem})
    set(camel "")
    foreach(part ${parts})
      string(SUBSTRING ${part} 0 1 first)
      string(TOUPPER ${first} first)
      string(SUBSTRING ${part} 1 -1 rest)
      string(APPEND camel "${first}${rest}")
    endforeach()
    set(header ${out_dir}/${stem}_spv.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 -Os
              -I${PROJECT_SOURCE_DIR}/shaders/include
              --vn k${camel}Spirv -o ${header} ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${src} ${shared_chunks}
      COMMENT "GLSL -> SPIR-V ${src}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  add_custom_target(${ARG_TARGET}_compile DEPENDS ${headers})
  add_library(${ARG_TARGET} INTERFACE)
  add_dependencies(${ARG_TARGET} ${ARG_TARGET}_compile)
  target_include_directories(${ARG_TARGET} INTERFACE ${out_dir})
endfunction()
