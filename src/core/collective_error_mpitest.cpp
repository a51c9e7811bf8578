// Under `mpiexec -n 2`: an error on one rank ends the operation on every rank, with the same
// message, as a CollectiveError (the command line then reports it once, from rank 0).
#include <gtest/gtest.h>

#include <new>

#include "core/collective_error.hpp"
#include "core/petsc.hpp"

namespace neomesh {
namespace {

TEST(Collectively, AnErrorOfRankOneReachesEveryRank) {
  try {
    collectively(PETSC_COMM_WORLD, [] {
      if (mpi_rank() == 1) throw Error("rank 1 failed");
    });
    FAIL() << "no error";
  } catch (const CollectiveError& e) {
    EXPECT_STREQ(e.what(), "rank 1 failed");
  }
}

TEST(Collectively, AStandardExceptionOfOneRankBecomesAReadableMessageEverywhere) {
  try {
    collectively(PETSC_COMM_WORLD, [] {
      const Activity reading("reading big.msh");
      if (mpi_rank() == mpi_size() - 1) throw std::bad_alloc();
    });
    FAIL() << "no error";
  } catch (const CollectiveError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("out of memory while reading big.msh"), std::string::npos) << message;
  }
}

TEST(OnRoot, AnErrorOfRankZeroIsThrownOnEveryRank) {
  EXPECT_THROW(on_root(PETSC_COMM_WORLD, [] { fail("cannot write out.msh"); }), CollectiveError);
  EXPECT_NO_THROW(on_root(PETSC_COMM_WORLD, [] {}));
}

}  // namespace
}  // namespace neomesh
