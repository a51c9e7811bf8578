#include "formats/cgns_library.hpp"

#include <dlfcn.h>

#include "core/error.hpp"

namespace neomesh::cgns_library {

void* symbol(const char* name) {
  // NEOMESH_CGNS_LIBRARY: the shared library's file name (CMakeLists.txt), found by the loader;
  // DEEPBIND: libcgns and its serial HDF5 bind to each other first (cgns_library.hpp).
  static void* const library = [] {
    void* handle = dlopen(NEOMESH_CGNS_LIBRARY, RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
    if (!handle) fail("cannot load the CGNS library {}: {}", NEOMESH_CGNS_LIBRARY, dlerror());
    return handle;
  }();
  void* f = dlsym(library, name);
  if (!f) fail("the CGNS library {} has no function {}", NEOMESH_CGNS_LIBRARY, name);
  return f;
}

}  // namespace neomesh::cgns_library
