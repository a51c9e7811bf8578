// What memory this machine can still give, and what this process holds: for refusing a run
// that will not fit (api/memory_check.hpp) and for spending memory on speed only where it is
// free (solver/component_preconditioner.hpp).
#pragma once

namespace neomesh {

// Bytes this machine (node) can still give: MemAvailable, or less under a cgroup limit.
// NEOMESH_MEMORY_AVAILABLE_MIB, if set, replaces it (a limit the system does not show).
double available_bytes();

// Bytes this process holds in memory now (its resident set), or 0 where the system does not
// say.
double resident_bytes();

}  // namespace neomesh
