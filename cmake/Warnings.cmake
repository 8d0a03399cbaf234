# One place for the project's warning flags: every target calls conicloc_warnings().
function(conicloc_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
endfunction()
