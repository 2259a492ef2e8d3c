# anitet_target_warnings(target): the project's warning set, kept at zero.
function(anitet_target_warnings target)
  target_compile_options(${target} PRIVATE
    $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor>
    $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -Wpedantic>)
  if(ANITET_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
