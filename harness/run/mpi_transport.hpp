#pragma once
// This process's link to the other ranks of an Open MPI job: byte messages with tags, over
// libdabench_mpi.so (harness/run/mpi_abi.h), loaded with dlopen only when mpirun launched the
// process. Without mpirun nothing is loaded and MPI is never initialised.
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace dabench {

struct MpiModuleFunctions;  // the module's entry points

class MpiTransport {
 public:
  // nullptr unless launched by mpirun (OMPI_COMM_WORLD_SIZE or PMIX_RANK in the environment);
  // then loads the module — $DABENCH_MPI_MODULE, else libdabench_mpi.so beside the program or
  // in ../lib, else the loader's search path — and initialises MPI. Throws InputError (one line)
  // when the module or MPI cannot be loaded.
  static std::unique_ptr<MpiTransport> open_if_launched();
  ~MpiTransport();  // MPI_Finalize
  MpiTransport(const MpiTransport&) = delete;
  MpiTransport& operator=(const MpiTransport&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  std::string host_name() const;

  struct Envelope {
    int source = 0;
    int tag = 0;
    long long bytes = 0;
  };
  // A message from `source` with `tag` (-1: any) waiting to be received, if any (never blocks:
  // MPI's blocking calls spin a core).
  std::optional<Envelope> probe(int source, int tag) const;
  std::string receive(const Envelope& envelope) const;  // the message probe() found
  void send(int destination, int tag, std::string_view bytes) const;
  [[noreturn]] void abort(int code) const;  // ends every rank of the job

 private:
  MpiTransport() = default;
  void* handle_ = nullptr;
  std::unique_ptr<MpiModuleFunctions> functions_;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace dabench
