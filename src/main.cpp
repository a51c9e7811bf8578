#include "app/run.hpp"

int main(int argc, char** argv) {
  return neomesh::app::run(argc, argv);
}
