# Warnings and sanitizers, applied per target (never globally) so that
# third-party code keeps its own flags.

function(dlslam_set_compiler_options target)
  get_target_property(type ${target} TYPE)
  if(type STREQUAL "INTERFACE_LIBRARY")
    return()
  endif()
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
    -Wcast-align -Woverloaded-virtual -Wformat=2
    # not -Wnull-dereference: GCC 12 reports false positives inside libstdc++
    $<$<BOOL:${DLSLAM_WERROR}>:-Werror>)
endfunction()

if(DLSLAM_SANITIZE STREQUAL "address")
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
elseif(DLSLAM_SANITIZE STREQUAL "thread")
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
elseif(NOT DLSLAM_SANITIZE STREQUAL "")
  message(FATAL_ERROR "DLSLAM_SANITIZE must be '', 'address' or 'thread', got '${DLSLAM_SANITIZE}'")
endif()
