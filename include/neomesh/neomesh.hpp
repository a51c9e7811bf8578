// neomesh as a library: the whole public API. A program that optimizes a mesh:
//
//   neomesh::Session session(&argc, &argv);   // unless it runs PETSc itself
//   neomesh::Mesh mesh = neomesh::Mesh::read("in.msh");
//   neomesh::Optimizer optimizer(mesh);
//   neomesh::Result result = optimizer.smooth();
//   mesh.write("out.vtu", optimizer.cell_fields());
//
// docs/library.md walks through it; examples/library/ is a complete program.
#pragma once

#include <neomesh/cell_type.hpp>
#include <neomesh/curve.hpp>
#include <neomesh/error.hpp>
#include <neomesh/field.hpp>
#include <neomesh/generate.hpp>
#include <neomesh/level_set.hpp>
#include <neomesh/mesh.hpp>
#include <neomesh/optimizer.hpp>
#include <neomesh/options.hpp>
#include <neomesh/quality.hpp>
#include <neomesh/result.hpp>
#include <neomesh/session.hpp>
#include <neomesh/size_field.hpp>
#include <neomesh/version.hpp>
