#pragma once
// Faults the robustness tests inject into a frame (tests/mpi/bad_input.sh, killed_ranks.sh,
// tests/python/test_errors.py): a rank that throws (the others must stop cleanly), dies (mpirun
// must end the job) or meets an MPI error (session/mpi_errors.h must name it), before its first
// brick, or after its first brick's image has gone to the compositor (direct send has then
// started sending it). Read from the environment once, when the session starts; a frame only asks
// the two hooks, which do nothing unless a variable named this rank.
//
//   SORTLAST_TEST_FAIL_RANK=R, SORTLAST_TEST_CRASH_RANK=R, SORTLAST_TEST_MPI_ERROR_RANK=R: before
//   the bricks; SORTLAST_TEST_FAIL_RANK_AFTER_BRICK=R: after each brick.
namespace sortlast {

class FrameFaults {
 public:
  static FrameFaults fromEnvironment(int rank);
  void beforeBricks() const;
  void afterBrick() const;

 private:
  bool fail_ = false, crash_ = false, mpi_error_ = false, fail_after_brick_ = false;
};

}  // namespace sortlast
