// The subcommands of `raytracer`; main() picks one by its first argument.
#pragma once

// raytracer SCENE OUTPUT [options]
int runRenderCommand(int argc, char** argv);

// raytracer merge PART.exr... OUTPUT (argv[0] is "merge")
int runMergeCommand(int argc, char** argv);

// raytracer view SCENE [options] (argv[0] is "view")
int runViewCommand(int argc, char** argv);

// raytracer converge SCENE [options] (argv[0] is "converge")
int runConvergeCommand(int argc, char** argv);

// raytracer check SCENE [options] (argv[0] is "check")
int runCheckCommand(int argc, char** argv);
