#pragma once
// Internal: Gmsh's reading and meshing of a geometry file run in a child
// process, so that what a file does to Gmsh cannot end or hang kinetofem.
//
// Gmsh and OpenCASCADE run in the program's own address space, and a file can
// take them where no error is thrown: OpenCASCADE's STEP reader crashes
// (SIGSEGV) on some damaged files, a .geo script can loop for hours, and its
// `Exit` command calls exit() inside the library. mesh_in_child_process runs
// `work` (everything that touches Gmsh for one file) in a forked child
// (fork() before the child initializes Gmsh; no exec, so `work` is an
// ordinary function with the parent's memory), which writes the mesh as a
// binary .msh 4.1 into a private temporary folder (temporary_directory.hpp);
// the parent waits for it and reads the mesh back with read_msh.
//
// The parent waits at most options.time_limit_s (the case key
// mesh.time_limit_s), printing a progress line on stdout every 10 s, then
// kills the child. Every way the child can end becomes one kinetofem::Error
// naming `context` (the file): an Error thrown by `work` is passed on with
// its message unchanged (through a pipe); a signal (a crash), the time limit,
// a missing mesh, or an exit status other than kinetofem's own (a script's
// `Exit`) each get their own message.
//
// Signals: the child is registered with core::KillOnTermination and the
// folder with core::RemoveOnTermination, so SIGINT/SIGTERM/SIGHUP to the
// parent stop the child and remove the folder. The child asks the kernel to
// kill it when the parent dies (PR_SET_PDEATHSIG), so a SIGKILLed parent
// leaves no orphan Gmsh running either.
//
// Threads: only the forking thread exists in the child; the parent's other
// threads (OpenMP, BLAS) must not be needed there. Gmsh runs with one thread
// (General.NumThreads = 1, mesh_geometry.cpp), and the meshes module's own
// test meshes in a child after an OpenMP parallel region of the parent.
#include <functional>
#include <string>

#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes::detail {

// The mesh that `work` returns, computed in a child process as described
// above. `context`: the file, for messages; `extension`: its type, lower case
// (".step"), for the message about a crash.
fem::Mesh mesh_in_child_process(const std::string& context, const std::string& extension,
                                const MeshOptions& options, const std::function<fem::Mesh()>& work);

}  // namespace kinetofem::meshes::detail
