// Open MPI as the tuner's transport (fuzzypid/tune/transport.hpp): `mpirun -np N fuzzypid tune ...`
// spreads each generation's runs over N processes. Built with FUZZYPID_WITH_MPI.
//
// MPI is started only in a process mpirun started (OMPI_COMM_WORLD_SIZE is set), so a plain
// `fuzzypid` never touches it. Every rank parses the same arguments and builds the same problem;
// rank 0 runs the search and writes the outputs, the others serve runs and write nothing.
#pragma once

#include "fuzzypid/tune/transport.hpp"

namespace fuzzypid::cli {

// The transport over MPI_COMM_WORLD in a process of an mpirun of two or more ranks (MPI started on
// the first call); null in any other process.
[[nodiscard]] const tune::Transport* mpi_transport();

// Ends MPI at the end of a run that started it (nothing otherwise): MPI_Finalize after a run that
// succeeded; after one that failed with `exit_code`, MPI_Abort with it, so that no rank waits for
// one that has given up (mpirun then exits with the code and names the rank).
void mpi_finish(int exit_code);

}  // namespace fuzzypid::cli
