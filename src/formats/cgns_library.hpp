// The CGNS library, loaded on the first .cgns file with dlopen(RTLD_DEEPBIND), not linked.
// Debian's libcgns brings a serial HDF5 while PETSc loads an MPI HDF5: linked, both were in
// every process, and one run crashed in the dynamic loader. Loaded apart, they are there only
// when a .cgns file is read or written, and DEEPBIND makes libcgns and its HDF5 bind to each
// other before the HDF5 already loaded. (dlmopen into a namespace of its own loaded and worked
// too, but its second libc crashed processes at exit; the static libcgns.a is not built for a
// shared library.) So each call cg_xxx(...) of a CGNS function neomesh uses is redirected (a
// macro per function, after cgnslib.h, which gives the types and signatures) to the loaded
// library's cg_xxx; where the library cannot be loaded, an Error says so in one line. A
// function is only called through these macros, never taken by address.
#pragma once

#include <cgnslib.h>

namespace neomesh::cgns_library {

// The address of `name` in the CGNS library, loaded on first use. Throws Error.
void* symbol(const char* name);

template <typename F>
F* function(const char* name) {
  return reinterpret_cast<F*>(symbol(name));
}

}  // namespace neomesh::cgns_library

// (cgnslib.h's declaration of `name` is not expanded again: a macro's name in its own expansion
// stays as it is.)
#define NEOMESH_CGNS_CALL(name, ...) \
  (::neomesh::cgns_library::function<decltype(::name)>(#name)(__VA_ARGS__))
#define cg_open(...) NEOMESH_CGNS_CALL(cg_open, __VA_ARGS__)
#define cg_close(...) NEOMESH_CGNS_CALL(cg_close, __VA_ARGS__)
#define cg_get_error(...) NEOMESH_CGNS_CALL(cg_get_error, __VA_ARGS__)
#define cg_base_write(...) NEOMESH_CGNS_CALL(cg_base_write, __VA_ARGS__)
#define cg_boco_gridlocation_read(...) NEOMESH_CGNS_CALL(cg_boco_gridlocation_read, __VA_ARGS__)
#define cg_boco_gridlocation_write(...) NEOMESH_CGNS_CALL(cg_boco_gridlocation_write, __VA_ARGS__)
#define cg_boco_info(...) NEOMESH_CGNS_CALL(cg_boco_info, __VA_ARGS__)
#define cg_boco_read(...) NEOMESH_CGNS_CALL(cg_boco_read, __VA_ARGS__)
#define cg_boco_write(...) NEOMESH_CGNS_CALL(cg_boco_write, __VA_ARGS__)
#define cg_conn_info(...) NEOMESH_CGNS_CALL(cg_conn_info, __VA_ARGS__)
#define cg_conn_read(...) NEOMESH_CGNS_CALL(cg_conn_read, __VA_ARGS__)
#define cg_conn_write(...) NEOMESH_CGNS_CALL(cg_conn_write, __VA_ARGS__)
#define cg_coord_read(...) NEOMESH_CGNS_CALL(cg_coord_read, __VA_ARGS__)
#define cg_coord_write(...) NEOMESH_CGNS_CALL(cg_coord_write, __VA_ARGS__)
#define cg_elements_read(...) NEOMESH_CGNS_CALL(cg_elements_read, __VA_ARGS__)
#define cg_famname_read(...) NEOMESH_CGNS_CALL(cg_famname_read, __VA_ARGS__)
#define cg_famname_write(...) NEOMESH_CGNS_CALL(cg_famname_write, __VA_ARGS__)
#define cg_field_info(...) NEOMESH_CGNS_CALL(cg_field_info, __VA_ARGS__)
#define cg_field_read(...) NEOMESH_CGNS_CALL(cg_field_read, __VA_ARGS__)
#define cg_field_write(...) NEOMESH_CGNS_CALL(cg_field_write, __VA_ARGS__)
#define cg_goto(...) NEOMESH_CGNS_CALL(cg_goto, __VA_ARGS__)
#define cg_nbases(...) NEOMESH_CGNS_CALL(cg_nbases, __VA_ARGS__)
#define cg_nbocos(...) NEOMESH_CGNS_CALL(cg_nbocos, __VA_ARGS__)
#define cg_nconns(...) NEOMESH_CGNS_CALL(cg_nconns, __VA_ARGS__)
#define cg_ncoords(...) NEOMESH_CGNS_CALL(cg_ncoords, __VA_ARGS__)
#define cg_nfields(...) NEOMESH_CGNS_CALL(cg_nfields, __VA_ARGS__)
#define cg_npe(...) NEOMESH_CGNS_CALL(cg_npe, __VA_ARGS__)
#define cg_nsections(...) NEOMESH_CGNS_CALL(cg_nsections, __VA_ARGS__)
#define cg_nsols(...) NEOMESH_CGNS_CALL(cg_nsols, __VA_ARGS__)
#define cg_nzones(...) NEOMESH_CGNS_CALL(cg_nzones, __VA_ARGS__)
#define cg_poly_elements_read(...) NEOMESH_CGNS_CALL(cg_poly_elements_read, __VA_ARGS__)
#define cg_poly_section_write(...) NEOMESH_CGNS_CALL(cg_poly_section_write, __VA_ARGS__)
#define cg_section_read(...) NEOMESH_CGNS_CALL(cg_section_read, __VA_ARGS__)
#define cg_section_write(...) NEOMESH_CGNS_CALL(cg_section_write, __VA_ARGS__)
#define cg_sol_info(...) NEOMESH_CGNS_CALL(cg_sol_info, __VA_ARGS__)
#define cg_sol_write(...) NEOMESH_CGNS_CALL(cg_sol_write, __VA_ARGS__)
#define cg_zone_read(...) NEOMESH_CGNS_CALL(cg_zone_read, __VA_ARGS__)
#define cg_zone_type(...) NEOMESH_CGNS_CALL(cg_zone_type, __VA_ARGS__)
#define cg_zone_write(...) NEOMESH_CGNS_CALL(cg_zone_write, __VA_ARGS__)
#define cg_ElementTypeName(...) NEOMESH_CGNS_CALL(cg_ElementTypeName, __VA_ARGS__)
#define cg_ElementDataSize(...) NEOMESH_CGNS_CALL(cg_ElementDataSize, __VA_ARGS__)
