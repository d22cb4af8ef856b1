// libdabench_mpi.so: the C interface of harness/run/mpi_abi.h over MPI's C API, on
// MPI_COMM_WORLD. Nothing else of dabench is linked in.
#include "harness/run/mpi_abi.h"

#include <mpi.h>

#include <climits>
#include <cstdio>

extern "C" {

int dabench_mpi_abi_version(void) { return DABENCH_MPI_ABI_VERSION; }

int dabench_mpi_init(int* rank, int* size, char* error, int error_capacity) {
  int provided = MPI_THREAD_SINGLE;
  const int status = MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
  if (status != MPI_SUCCESS) {
    std::snprintf(error, static_cast<std::size_t>(error_capacity), "MPI_Init_thread failed (error %d)", status);
    return status;
  }
  if (provided < MPI_THREAD_SERIALIZED) {
    std::snprintf(error, static_cast<std::size_t>(error_capacity),
                  "this MPI gives thread level %d, dabench needs MPI_THREAD_SERIALIZED", provided);
    MPI_Finalize();
    return -1;
  }
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  return 0;
}

int dabench_mpi_host_name(char* name, int capacity) {
  char text[MPI_MAX_PROCESSOR_NAME];
  int length = 0;
  const int status = MPI_Get_processor_name(text, &length);
  if (status != MPI_SUCCESS) return status;
  std::snprintf(name, static_cast<std::size_t>(capacity), "%.*s", length, text);
  return 0;
}

int dabench_mpi_send(const void* data, long long bytes, int destination, int tag) {
  if (bytes < 0 || bytes > INT_MAX) return MPI_ERR_COUNT;
  return MPI_Send(data, static_cast<int>(bytes), MPI_BYTE, destination, tag, MPI_COMM_WORLD);
}

int dabench_mpi_probe(int source, int tag, int wait, int* found_source, int* found_tag, long long* bytes) {
  MPI_Status status;
  const int any_source = source < 0 ? MPI_ANY_SOURCE : source, any_tag = tag < 0 ? MPI_ANY_TAG : tag;
  int found = 1;
  const int error = wait ? MPI_Probe(any_source, any_tag, MPI_COMM_WORLD, &status)
                         : MPI_Iprobe(any_source, any_tag, MPI_COMM_WORLD, &found, &status);
  if (error != MPI_SUCCESS) return error > 0 ? -error : -1;
  if (!found) return 0;
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  *found_source = status.MPI_SOURCE;
  *found_tag = status.MPI_TAG;
  *bytes = count;
  return 1;
}

int dabench_mpi_recv(void* data, long long bytes, int source, int tag) {
  if (bytes < 0 || bytes > INT_MAX) return MPI_ERR_COUNT;
  return MPI_Recv(data, static_cast<int>(bytes), MPI_BYTE, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
}

void dabench_mpi_abort(int code) { MPI_Abort(MPI_COMM_WORLD, code); }

int dabench_mpi_finalize(void) { return MPI_Finalize(); }

}  // extern "C"
