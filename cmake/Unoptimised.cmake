# rt_compile_unoptimised(target): compiles a target at -O0 in the optimised
# configurations, for code that only sets up and calls the library (the
# tests, the command line), which keeps its -O2. Such code runs in the same
# time unoptimised (the work is in the library and on the device) and
# compiles in a third to a half of the time: doctest assertions by the
# hundred in one function and CLI11's header-only parser, instantiated in
# every command file, are what optimisers are slowest at.
function(rt_compile_unoptimised target)
  target_compile_options(${target} PRIVATE $<$<CONFIG:RelWithDebInfo,Release>:-O0>)
endfunction()
