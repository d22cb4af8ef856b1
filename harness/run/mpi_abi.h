#pragma once
// The C interface of libdabench_mpi.so (harness/run/mpi_module.cpp), the only code that links
// Open MPI. dabench loads it with dlopen only when mpirun launched it (harness/run/mpi_transport.hpp),
// so a user who never runs under mpirun needs no MPI library at run time. Plain C types, so the
// module and the program need not share a compiler's C++ ABI. Every function returning int
// returns 0 on success and a nonzero MPI error code otherwise, unless it says differently.
#ifdef __cplusplus
extern "C" {
#endif

// Bumped whenever a signature below changes; the loader refuses a module of another version.
#define DABENCH_MPI_ABI_VERSION 1

int dabench_mpi_abi_version(void);
// MPI_Init_thread asking for MPI_THREAD_SERIALIZED (threads call MPI one at a time); fails
// with a message in `error` when MPI cannot give that.
int dabench_mpi_init(int* rank, int* size, char* error, int error_capacity);
// MPI_Get_processor_name (the host), NUL-terminated.
int dabench_mpi_host_name(char* name, int capacity);
// Blocking send of `bytes` bytes to `destination` with `tag` (bytes < 2^31).
int dabench_mpi_send(const void* data, long long bytes, int destination, int tag);
// Looks for a message from `source` with `tag` (-1: any); `wait` nonzero blocks until one
// comes. Returns 1 and fills found_source, found_tag and bytes when one waits, 0 when none,
// a negative MPI error code on failure.
int dabench_mpi_probe(int source, int tag, int wait, int* found_source, int* found_tag, long long* bytes);
// Receives the message that probe found (its exact source, tag and size).
int dabench_mpi_recv(void* data, long long bytes, int source, int tag);
// MPI_Abort of the whole job.
void dabench_mpi_abort(int code);
int dabench_mpi_finalize(void);

#ifdef __cplusplus
}
#endif
