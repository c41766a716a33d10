# The layering the build relies on (docs/architecture.md): kernels/ include neither engine/ nor systems/;
# engine/ includes nothing from systems/ (the runtime knows no physics; the composition root in systems/
# picks the models). Run by CTest as layering_check: cmake -DRIFT_SOURCE_DIR=<repo> -P layering_check.cmake
set(violations "")
function(check_layer layer forbidden_regex what)
  file(GLOB_RECURSE files "${RIFT_SOURCE_DIR}/${layer}/*.cpp" "${RIFT_SOURCE_DIR}/${layer}/*.hpp"
       "${RIFT_SOURCE_DIR}/${layer}/*.in")
  foreach(f ${files})
    file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"](${forbidden_regex})/")
    foreach(line ${lines})
      file(RELATIVE_PATH rel "${RIFT_SOURCE_DIR}" "${f}")
      list(APPEND violations "${rel}: ${line}  (${what})")
    endforeach()
  endforeach()
  set(violations "${violations}" PARENT_SCOPE)
endfunction()
check_layer(kernels "engine|systems" "kernels are stateless functions over spans: no engine or systems types")
check_layer(engine "systems" "the engine knows no physics: move the code to systems/, or hand it in as the composition root does (engine/world.hpp WorldBuilder)")
if(violations)
  list(JOIN violations "\n  " text)
  message(FATAL_ERROR "layering broken:\n  ${text}")
endif()
message(STATUS "layering holds: kernels/ include neither engine/ nor systems/, engine/ nothing from systems/")
