# Warnings, ccache and sanitizers for every Vesica target.

find_program(VESICA_CCACHE ccache)
if(VESICA_CCACHE)
  set(CMAKE_C_COMPILER_LAUNCHER "${VESICA_CCACHE}")
  set(CMAKE_CXX_COMPILER_LAUNCHER "${VESICA_CCACHE}")
endif()

# Applied per target (vesica_target_defaults) so third-party headers are not held to our flags.
add_library(vesica_warnings INTERFACE)
target_compile_options(vesica_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow=local)

if(VESICA_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif()

# vesica_target_defaults(target): warnings and the project include root.
function(vesica_target_defaults target)
  target_link_libraries(${target} PRIVATE vesica_warnings)
endfunction()
