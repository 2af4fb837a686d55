// The processes of one run, for scale-out over machines: `mpirun -np K pronk
// eval|train ...` starts K ranks, each with its own worker threads. A build
// without MPI (PRONK_WITH_MPI off), or a pronk not started by an MPI launcher,
// is one process of rank 0: every call below then works on that one process.
//
// Only the thread that made the Communicator calls it (MPI_THREAD_FUNNELED);
// the rollout's worker threads never do. Messages are text (JSON), so that
// what crosses is what a results file holds, and a rank's numbers reach rank
// 0 to the last bit.
#pragma once

#include <string>
#include <vector>

#include "pronk/error.h"

namespace pronk {

// An error that every rank of the run raised together (rank 0's, given to all
// through a broadcast): each rank can end normally, none is left waiting.
class SharedError : public Error {
 public:
  using Error::Error;
};

class Communicator {
 public:
  // The run's processes. The first call initialises MPI when this process was
  // started by an MPI launcher (mpirun sets OMPI_COMM_WORLD_SIZE or PMI_SIZE)
  // and the build has MPI; MPI is finalised at exit.
  static Communicator& world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool distributed() const { return size_ > 1; }

  // Rank 0 receives every rank's text, in rank order; the others an empty list.
  std::vector<std::string> gather(const std::string& mine) const;
  // Rank 0's text, on every rank (what the others pass is ignored).
  std::string broadcast(const std::string& text) const;
  // Ends every rank of the run with this exit status: one rank's unexpected
  // error must not leave the others waiting in a collective for ever.
  [[noreturn]] void abort(int status) const;

 private:
  Communicator();
  int rank_ = 0;
  int size_ = 1;
};

// Case k of a distributed loop belongs to rank k mod size: the ranks share
// the cases round robin, so each gets a spread of the set, not a block.
std::vector<size_t> casesOfRank(const std::vector<size_t>& cases, int rank, int size);

}  // namespace pronk
