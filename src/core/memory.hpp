// What memory this machine can still give, and what this process holds: for refusing a run
// that will not fit (api/memory_check.hpp) and for spending memory on speed only where it is
// free (solver/component_preconditioner.hpp); and faulting a run's memory in at once.
#pragma once

namespace neomesh {

// Bytes this machine (node) can still give: MemAvailable, or less under a cgroup limit.
// NEOMESH_MEMORY_AVAILABLE_MIB, if set, replaces it (a limit the system does not show).
double available_bytes();

// Bytes this process holds in memory now (its resident set), or 0 where the system does not
// say.
double resident_bytes();

// The resident set this process expects at its peak: the memory check's estimate, set when it
// admits a run (api/memory_check.hpp); 0, the default, expects nothing.
void expect_peak(double bytes);
// Bytes the machine can give beyond what the expected peak still needs from it: what a run
// may spend on speed (solver/component_preconditioner.hpp) without taking memory its own later
// steps need. available_bytes() where no peak is expected.
double spare_bytes();

// For a whole program, never a library (it changes malloc's settings for the process), before
// its threads allocate: from now on malloc keeps the memory it was given, large blocks too,
// instead of handing it back to the kernel at free() (Debian's SuperLU_DIST, through CombBLAS,
// sets the same when it is loaded; this does not rely on it), and every thread allocates from
// the one heap. Threads with heaps (arenas) of their own do not reuse what the main thread
// faulted in: square-midpoint 2048² peaked 160 MiB above the memory faulted in for it.
void keep_freed_memory();

// For a whole program (keep_freed_memory first): `bytes` more memory faulted in now, by every
// OpenMP thread, and kept for the run's arrays. A page's first touch is the kernel's work (on a
// VM the host's as well) on the thread that touches it: on this 2-core VM 0.5-1.3 s per GB on
// one thread and 2.6 times less on two (docs/benchmarks.md, "First touch"). Without this, a
// run's arrays are faulted in by whichever thread writes them first, most often one.
void keep_and_fault_in(double bytes);
// The bytes keep_and_fault_in has faulted in so far: memory this process holds for the run's
// arrays.
double kept_bytes();

}  // namespace neomesh
