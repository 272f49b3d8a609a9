# kinetofem_embed_text(TARGET FILE FUNCTION) — compiles the text of FILE into
# TARGET as the function
#     std::string_view FUNCTION();   (FUNCTION qualified: ns::name)
# which returns the file's bytes exactly (its size included). The function is
# declared by hand in a header of the module; the definition is generated into
# the build tree (a raw string literal) and regenerated whenever FILE changes,
# so the program carries its data files and needs no source tree at run time.
set(KINETOFEM_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/embed_text.cmake)

function(kinetofem_embed_text target file function)
  get_filename_component(input ${file} ABSOLUTE)
  string(REPLACE "::" "_" stem ${function})
  set(output ${CMAKE_CURRENT_BINARY_DIR}/embedded/${stem}.cpp)
  file(RELATIVE_PATH shown ${PROJECT_SOURCE_DIR} ${input})
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DINPUT=${input} -DOUTPUT=${output} -DFUNCTION=${function}
            -DSHOWN=${shown} -P ${KINETOFEM_EMBED_SCRIPT}
    DEPENDS ${input} ${KINETOFEM_EMBED_SCRIPT}
    COMMENT "Embedding ${shown} as ${function}()"
    VERBATIM)
  target_sources(${target} PRIVATE ${output})
endfunction()
