// The tuner's transport over Open MPI (mpi_transport.hpp).
#include "mpi_transport.hpp"

#include <mpi.h>

#include <climits>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace fuzzypid::cli {

namespace {

// Every message of the tuner travels with this tag on MPI_COMM_WORLD.
constexpr int kTag = 7341;

bool g_started = false;
tune::Transport g_transport;

// MPI's default error handler (MPI_ERRORS_ARE_FATAL) ends the job on a failed call, as the
// transport's contract asks; a message too long for one call is refused the same way.
void send(int to, const std::vector<double>& message) {
  if (message.size() > static_cast<std::size_t>(INT_MAX)) {
    std::fprintf(stderr, "fuzzypid tune: a message of %zu doubles is too long for MPI\n",
                 message.size());
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
  MPI_Send(message.data(), static_cast<int>(message.size()), MPI_DOUBLE, to, kTag, MPI_COMM_WORLD);
}

std::vector<double> receive(int from) {
  MPI_Status status;
  MPI_Probe(from, kTag, MPI_COMM_WORLD, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_DOUBLE, &count);
  std::vector<double> message(static_cast<std::size_t>(count < 0 ? 0 : count));
  MPI_Recv(message.data(), count, MPI_DOUBLE, from, kTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return message;
}

}  // namespace

const tune::Transport* mpi_transport() {
  if (g_started) return g_transport.size > 1 ? &g_transport : nullptr;
  if (std::getenv("OMPI_COMM_WORLD_SIZE") == nullptr) return nullptr;
  // Messages leave from the thread that runs the search only; the runs' threads never call MPI.
  int provided = 0;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    std::fprintf(stderr, "fuzzypid: MPI_Init_thread failed\n");
    std::exit(1);
  }
  g_started = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_transport.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_transport.size);
  g_transport.send = send;
  g_transport.receive = receive;
  return g_transport.size > 1 ? &g_transport : nullptr;
}

void mpi_finish(int exit_code) {
  if (!g_started) return;
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized != 0) return;
  if (exit_code != 0 && g_transport.size > 1) MPI_Abort(MPI_COMM_WORLD, exit_code);
  MPI_Finalize();
}

}  // namespace fuzzypid::cli
