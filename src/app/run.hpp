// The `neomesh` command line: parses options (CLI11), hands single-dash options it does
// not know to PETSc, runs one subcommand, and turns every failure into one line
// `neomesh: error: ...` and exit code 1.
#pragma once

namespace neomesh::app {

int run(int argc, char** argv);

}  // namespace neomesh::app
