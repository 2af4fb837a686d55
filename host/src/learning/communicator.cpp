#include "pronk/communicator.h"

#include <climits>
#include <cstdlib>
#include <stdexcept>

#ifdef PRONK_WITH_MPI
// The C API only: without these, mpi.h in C++ pulls in the removed C++ bindings.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

#include "pronk/error.h"

namespace pronk {

namespace {

#ifdef PRONK_WITH_MPI
// Started by a launcher: Open MPI sets OMPI_COMM_WORLD_SIZE, PMI-based ones PMI_SIZE.
bool launchedByMpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"}) {
    if (std::getenv(name)) return true;
  }
  return false;
}

// Finalises MPI at exit when this process initialised it.
struct MpiFinalizer {
  bool active = false;
  ~MpiFinalizer() {
    int finalized = 0;
    if (active && MPI_Finalized(&finalized) == MPI_SUCCESS && !finalized) MPI_Finalize();
  }
};

void check(int status, const char* what) {
  if (status != MPI_SUCCESS) throw Error(std::string("MPI: ") + what + " failed");
}

int messageLength(size_t n) {
  if (n > static_cast<size_t>(INT_MAX)) throw Error("MPI: a message of more than 2 GB");
  return static_cast<int>(n);
}
#endif

}  // namespace

Communicator& Communicator::world() {
  static Communicator instance;
  return instance;
}

Communicator::Communicator() {
#ifdef PRONK_WITH_MPI
  static MpiFinalizer finalizer;
  if (!launchedByMpi()) return;
  int initialized = 0;
  check(MPI_Initialized(&initialized), "MPI_Initialized");
  if (!initialized) {
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    finalizer.active = true;
    if (provided < MPI_THREAD_FUNNELED) throw Error("MPI: the library does not allow threads (MPI_THREAD_FUNNELED)");
  }
  check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
#endif
}

std::vector<std::string> Communicator::gather(const std::string& mine) const {
  if (size_ == 1) return {mine};
#ifdef PRONK_WITH_MPI
  const int length = messageLength(mine.size());
  std::vector<int> lengths(root() ? static_cast<size_t>(size_) : 0);
  check(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
  std::vector<int> offsets(lengths.size(), 0);
  size_t total = 0;
  for (size_t r = 0; r < lengths.size(); ++r) {
    offsets[r] = messageLength(total);
    total += static_cast<size_t>(lengths[r]);
  }
  messageLength(total);
  std::string all(total, '\0');
  check(MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
                    MPI_COMM_WORLD),
        "MPI_Gatherv");
  std::vector<std::string> out;
  for (size_t r = 0; r < lengths.size(); ++r) out.push_back(all.substr(static_cast<size_t>(offsets[r]), static_cast<size_t>(lengths[r])));
  return out;
#else
  return {mine};
#endif
}

std::string Communicator::broadcast(const std::string& text) const {
  if (size_ == 1) return text;
#ifdef PRONK_WITH_MPI
  long long length = root() ? static_cast<long long>(text.size()) : 0;
  check(MPI_Bcast(&length, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD), "MPI_Bcast");
  std::string out = root() ? text : std::string(static_cast<size_t>(length), '\0');
  check(MPI_Bcast(out.data(), messageLength(out.size()), MPI_CHAR, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return out;
#else
  return text;
#endif
}

void Communicator::abort(int status) const {
#ifdef PRONK_WITH_MPI
  if (size_ > 1) MPI_Abort(MPI_COMM_WORLD, status);
#endif
  std::exit(status);
}

std::vector<size_t> casesOfRank(const std::vector<size_t>& cases, int rank, int size) {
  if (size < 1 || rank < 0 || rank >= size) throw std::invalid_argument("casesOfRank: rank out of range");
  std::vector<size_t> mine;
  for (size_t k = static_cast<size_t>(rank); k < cases.size(); k += static_cast<size_t>(size)) mine.push_back(cases[k]);
  return mine;
}

}  // namespace pronk
