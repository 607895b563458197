# rt_set_warnings(target): the project's warning policy, applied to every
# target we own (never to third-party headers, which are SYSTEM includes).
function(rt_set_warnings target)
  # -Wno-missing-field-initializers: Vulkan code initialises create-info
  # structs as `VkFooCreateInfo info{VK_STRUCTURE_TYPE_FOO}`, zeroing the rest.
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion -Wno-missing-field-initializers)
  if(RT_WARNINGS_AS_ERRORS)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
