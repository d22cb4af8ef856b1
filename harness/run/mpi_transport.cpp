#include "harness/run/mpi_transport.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "harness/core/errors.hpp"
#include "harness/run/mpi_abi.h"

namespace dabench {

struct MpiModuleFunctions {
  decltype(&dabench_mpi_abi_version) abi_version = nullptr;
  decltype(&dabench_mpi_init) init = nullptr;
  decltype(&dabench_mpi_host_name) host_name = nullptr;
  decltype(&dabench_mpi_send) send = nullptr;
  decltype(&dabench_mpi_probe) probe = nullptr;
  decltype(&dabench_mpi_recv) recv = nullptr;
  decltype(&dabench_mpi_abort) abort = nullptr;
  decltype(&dabench_mpi_finalize) finalize = nullptr;
};

namespace {

constexpr const char* kModuleName = "libdabench_mpi.so";

// The environment variable by which mpirun (Open MPI's, or a PMIx launcher) shows itself.
const char* launcher_variable() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK"}) {
    if (std::getenv(name) != nullptr) return name;
  }
  return nullptr;
}

std::vector<std::string> module_candidates() {
  if (const char* path = std::getenv("DABENCH_MPI_MODULE")) return {path};
  std::vector<std::string> candidates;
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    candidates.push_back((program.parent_path() / kModuleName).string());
    candidates.push_back((program.parent_path().parent_path() / "lib" / kModuleName).string());
  }
  candidates.push_back(kModuleName);  // LD_LIBRARY_PATH and the system's paths
  return candidates;
}

template <class Function>
void bind(void* handle, const char* name, Function& function) {
  function = reinterpret_cast<Function>(dlsym(handle, name));
  if (function == nullptr) throw InputError(fmt::format("mpirun: {} lacks {} (rebuild dabench)", kModuleName, name));
}

}  // namespace

std::unique_ptr<MpiTransport> MpiTransport::open_if_launched() {
  const char* variable = launcher_variable();
  if (variable == nullptr) return nullptr;
  std::unique_ptr<MpiTransport> transport(new MpiTransport());
  std::string failures;
  for (const std::string& candidate : module_candidates()) {
    // RTLD_GLOBAL: Open MPI's own plugins look for libmpi's symbols in the global scope.
    transport->handle_ = dlopen(candidate.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (transport->handle_ != nullptr) break;
    const char* reason = dlerror();
    if (candidate.find('/') == std::string::npos || std::filesystem::exists(candidate)) {
      failures += fmt::format("; {}", reason != nullptr ? reason : candidate);
    }
  }
  if (transport->handle_ == nullptr) {
    throw InputError(fmt::format("launched by mpirun ({} is set) but {} could not be loaded (build dabench with "
                                 "Open MPI's libopenmpi-dev installed, or set DABENCH_MPI_MODULE){}",
                                 variable, kModuleName, failures));
  }
  auto functions = std::make_unique<MpiModuleFunctions>();
  void* handle = transport->handle_;
  bind(handle, "dabench_mpi_abi_version", functions->abi_version);
  bind(handle, "dabench_mpi_init", functions->init);
  bind(handle, "dabench_mpi_host_name", functions->host_name);
  bind(handle, "dabench_mpi_send", functions->send);
  bind(handle, "dabench_mpi_probe", functions->probe);
  bind(handle, "dabench_mpi_recv", functions->recv);
  bind(handle, "dabench_mpi_abort", functions->abort);
  bind(handle, "dabench_mpi_finalize", functions->finalize);
  if (functions->abi_version() != DABENCH_MPI_ABI_VERSION) {
    throw InputError(fmt::format("mpirun: {} has interface version {}, this dabench needs {} (rebuild dabench)",
                                 kModuleName, functions->abi_version(), DABENCH_MPI_ABI_VERSION));
  }
  char error[256] = {};
  if (functions->init(&transport->rank_, &transport->size_, error, sizeof error) != 0) {
    throw InputError(fmt::format("mpirun: {}", error));
  }
  transport->functions_ = std::move(functions);
  return transport;
}

MpiTransport::~MpiTransport() {
  if (functions_) functions_->finalize();
  // The module stays loaded: MPI's threads and atexit handlers may still point into it.
}

std::string MpiTransport::host_name() const {
  char name[256] = {};
  if (functions_->host_name(name, sizeof name) != 0) return "unknown";
  return name;
}

std::optional<MpiTransport::Envelope> MpiTransport::probe(int source, int tag) const {
  Envelope envelope;
  const int found = functions_->probe(source, tag, /*wait=*/0, &envelope.source, &envelope.tag, &envelope.bytes);
  if (found < 0) throw std::runtime_error(fmt::format("MPI probe failed (error {})", -found));
  if (found == 0) return std::nullopt;
  return envelope;
}

std::string MpiTransport::receive(const Envelope& envelope) const {
  std::string bytes(static_cast<std::size_t>(envelope.bytes), '\0');
  const int error = functions_->recv(bytes.data(), envelope.bytes, envelope.source, envelope.tag);
  if (error != 0) throw std::runtime_error(fmt::format("MPI receive from rank {} failed (error {})", envelope.source, error));
  return bytes;
}

void MpiTransport::send(int destination, int tag, std::string_view bytes) const {
  const int error = functions_->send(bytes.data(), static_cast<long long>(bytes.size()), destination, tag);
  if (error != 0) throw std::runtime_error(fmt::format("MPI send to rank {} failed (error {})", destination, error));
}

void MpiTransport::abort(int code) const {
  functions_->abort(code);
  std::_Exit(code);  // MPI_Abort does not return; in case it does
}

}  // namespace dabench
