// Threading policy of the engine (OpenMP).
//
// Loops shorter than kParallelMin run on one thread: a parallel region costs more than it
// saves below a few thousand cheap iterations, and much more when the cores are busy.
//
// A desktop is never idle (the viewer's own renderer competes with the adapter), and
// libgomp's default is to let a thread that reaches a barrier spin for a long while before
// it sleeps. With one other busy thread on a 2-core machine that spinning thread takes the
// core the late thread needs, and a sphere step went from 3.7 ms to 64 ms (issue 17). Every
// program that links the engine therefore starts OpenMP with a passive wait policy (idle
// threads sleep at once), unless the user set OMP_WAIT_POLICY or GOMP_SPINCOUNT
// themselves. libgomp reads its environment when it is loaded, before main() and before any
// static constructor of ours, so parallel.cpp sets the variable from the executable's
// .preinit_array, which the dynamic loader runs before any shared library's initialiser.
// engine_wait_policy() reports what libgomp was given (and, being referenced from the
// Adapter, keeps that object file in every program that adapts meshes).
#pragma once

#include <cstdint>

namespace dynamesh {

inline constexpr std::int64_t kParallelMin = 4096;

// "passive" when the engine chose the policy; the user's OMP_WAIT_POLICY / GOMP_SPINCOUNT
// otherwise ("user: ..."), or "default" when the executable could not set it.
const char* engine_wait_policy();

}  // namespace dynamesh
