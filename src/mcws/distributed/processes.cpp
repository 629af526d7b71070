#include "mcws/distributed/processes.h"

#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <optional>
#include <thread>

#include "mcws/core/error.h"
#include "mcws/io/atomic_file.h"

#ifdef MCWS_HAVE_MPI
#include <mpi.h>
#endif

namespace mcws::distributed {
namespace {

/// What launchers put in the environment of the processes they start: Open MPI's mpirun, MPICH's
/// Hydra (and Intel MPI), PMIx-based launchers such as Slurm's srun --mpi=pmix.
constexpr const char* kSizeVariables[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"};
constexpr const char* kRankVariables[] = {"OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"};

/// Values Processes::setUpDone() compares between the processes, at most: the agreement is one
/// collective of a fixed size, whichever process calls it from where.
constexpr std::size_t kMaxSame = 4;

/// The number of processes the launcher announced in the environment, 1 when none.
int announcedSize() {
  for (const char* name : kSizeVariables) {
    if (const char* value = std::getenv(name)) {
      const long size = std::strtol(value, nullptr, 10);
      if (size >= 1 && size <= std::numeric_limits<int>::max()) return static_cast<int>(size);
    }
  }
  return 1;
}

/// FNV-1a hash of bytes, continued from `hash`.
std::uint64_t fnv1a(const char* bytes, std::size_t size,
                    std::uint64_t hash = 14695981039346656037ull) {
  for (std::size_t k = 0; k < size; ++k) {
    hash = (hash ^ static_cast<unsigned char>(bytes[k])) * 1099511628211ull;
  }
  return hash;
}

#ifdef MCWS_HAVE_MPI
/// Hash of the arguments after the program's name, each with its terminating zero byte.
std::uint64_t argumentsHash(int argc, char** argv) {
  std::uint64_t hash = fnv1a("", 0);
  for (int k = 1; k < argc; ++k) hash = fnv1a(argv[k], std::strlen(argv[k]) + 1, hash);
  return hash;
}

/// MPI's message for an error code.
std::string mpiMessage(int code) {
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  return std::string(text, static_cast<std::size_t>(length));
}

/// MPI_Allreduce of `values` in place over every process.
template <typename T>
void allReduce(std::vector<T>& values, MPI_Datatype type, MPI_Op op) {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), type, op,
                MPI_COMM_WORLD);
}

/// Bytes per MPI call: counts are ints.
constexpr std::size_t kMaxPiece = std::size_t{1} << 30;
#endif

}  // namespace

bool builtWithMpi() {
#ifdef MCWS_HAVE_MPI
  return true;
#else
  return false;
#endif
}

bool launchedByMpi() {
  for (const char* name : kSizeVariables) {
    if (std::getenv(name)) return true;
  }
  for (const char* name : kRankVariables) {
    if (std::getenv(name)) return true;
  }
  return false;
}

Processes::Processes(int& argc, char**& argv) : launched_size_(announcedSize()) {
#ifdef MCWS_HAVE_MPI
  if (launchedByMpi()) {
    int provided = 0;
    // SERIALIZED: the sampler's threads write their blocks into the shared file one at a time
    // (SharedFile::writeAt holds a mutex).
    MPI_Init_thread(&argc, &argv, MPI_THREAD_SERIALIZED, &provided);
    initialized_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm local;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
    MPI_Comm_size(local, &local_size_);
    MPI_Comm_free(&local);
    std::uint64_t hash[2] = {argumentsHash(argc, argv), 0};
    hash[1] = ~hash[0];  // the largest hash as the smallest complement: one MIN reduction
    MPI_Allreduce(MPI_IN_PLACE, hash, 2, MPI_UINT64_T, MPI_MIN, MPI_COMM_WORLD);
    same_arguments_ = hash[0] == argumentsHash(argc, argv) && ~hash[1] == hash[0];
    if (provided < MPI_THREAD_SERIALIZED) {
      if (rank_ == 0) {
        std::cerr << "mcws: this MPI library does not let a second thread write (thread level "
                  << provided << " < MPI_THREAD_SERIALIZED)\n";
      }
      MPI_Abort(MPI_COMM_WORLD, 1);
    }
  }
#else
  (void)argc;
  (void)argv;
#endif
}

Processes::~Processes() {
#ifdef MCWS_HAVE_MPI
  if (initialized_) MPI_Finalize();
#endif
}

void Processes::require() const {
  if (launched_size_ > 1 && !initialized_) {
    throw Error("started on " + std::to_string(launched_size_) +
                " processes, but this build has no MPI support (MCWS_WITH_MPI=OFF or MPI not "
                "found): run it without mpirun, or rebuild with MPI");
  }
  if (initialized_ && launched_size_ > 1 && size_ != launched_size_) {
    throw Error("started as " + std::to_string(launched_size_) + " processes, but MPI sees " +
                std::to_string(size_) +
                ": the launcher is not the one of the MPI library this tool was built with");
  }
  if (!same_arguments_) {
    throw Error("the " + std::to_string(size_) +
                " processes were not all given the same arguments: start them with one command "
                "line (mpirun -np K TOOL FLAGS)");
  }
}

void Processes::setUpDone(const std::vector<std::pair<std::string, std::string>>& same) {
  if (same.size() > kMaxSame) throw Error("setUpDone: at most 4 values to compare");
  std::vector<std::uint64_t> hashes(2 * kMaxSame, std::numeric_limits<std::uint64_t>::max());
  for (std::size_t k = 0; k < same.size(); ++k) {
    const std::uint64_t hash = fnv1a(same[k].second.data(), same[k].second.size());
    hashes[2 * k] = hash;
    hashes[2 * k + 1] = ~hash;  // the largest hash as the smallest complement: one MIN
  }
  const Agreement agreement = agree(0, hashes);
  if (agreement.code != 0) throw OtherProcessFailed{agreement.code};
  for (std::size_t k = 0; k < same.size(); ++k) {
    const std::uint64_t hash = fnv1a(same[k].second.data(), same[k].second.size());
    if (hashes[2 * k] == hash && ~hashes[2 * k + 1] == hash) continue;
    agreement_ = {0, 1};  // rank 0 reports, every process exits with 1
    if (rank_ != 0) throw OtherProcessFailed{1};
    throw Error("--" + same[k].first +
                ": the processes did not all read the same file (a different copy on some "
                "node?): every process must see the same inputs");
  }
}

Agreement Processes::agreeOnSetUp(int code) {
  // The same number of values as setUpDone()'s, none of which lowers a minimum.
  std::vector<std::uint64_t> none(2 * kMaxSame, std::numeric_limits<std::uint64_t>::max());
  return agree(code, none);
}

Agreement Processes::agree(int code, std::vector<std::uint64_t>& hashes) {
  // One MIN over: the failing rank (size when none), the largest code as the smallest
  // complement, and the hashes.
  std::vector<std::uint64_t> values{
      static_cast<std::uint64_t>(code != 0 ? rank_ : size_),
      std::numeric_limits<std::uint64_t>::max() - static_cast<std::uint64_t>(code)};
  values.insert(values.end(), hashes.begin(), hashes.end());
#ifdef MCWS_HAVE_MPI
  if (distributed()) allReduce(values, MPI_UINT64_T, MPI_MIN);
#endif
  agreement_ = {static_cast<int>(values[0]),
                static_cast<int>(std::numeric_limits<std::uint64_t>::max() - values[1])};
  std::copy(values.begin() + 2, values.end(), hashes.begin());
  agreed_ = true;
  return agreement_;
}

void Processes::abortAll(int code) const {
  if (!distributed()) return;
  std::cerr.flush();
#ifdef MCWS_HAVE_MPI
  MPI_Abort(MPI_COMM_WORLD, code);
#else
  (void)code;  // without MPI there is never more than one process
#endif
}

void Processes::barrier() const {
#ifdef MCWS_HAVE_MPI
  if (initialized_) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

std::string Processes::broadcast(const std::string& text) const {
#ifdef MCWS_HAVE_MPI
  if (distributed()) {
    std::uint64_t length = broadcast(static_cast<std::uint64_t>(text.size()));
    std::string out = rank_ == 0 ? text : std::string(length, '\0');
    MPI_Bcast(out.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD);
    return out;
  }
#endif
  return text;
}

std::uint64_t Processes::broadcast(std::uint64_t value) const {
#ifdef MCWS_HAVE_MPI
  if (distributed()) MPI_Bcast(&value, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
#endif
  return value;
}

bool Processes::allTrue(bool value) const {
#ifdef MCWS_HAVE_MPI
  if (distributed()) {
    int all = value ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all == 1;
  }
#endif
  return value;
}

void Processes::sum(std::vector<std::uint64_t>& values) const {
#ifdef MCWS_HAVE_MPI
  if (distributed()) allReduce(values, MPI_UINT64_T, MPI_SUM);
#else
  (void)values;
#endif
}

void Processes::min(std::vector<double>& values) const {
#ifdef MCWS_HAVE_MPI
  if (distributed()) allReduce(values, MPI_DOUBLE, MPI_MIN);
#else
  (void)values;
#endif
}

void Processes::max(std::vector<double>& values) const {
#ifdef MCWS_HAVE_MPI
  if (distributed()) allReduce(values, MPI_DOUBLE, MPI_MAX);
#else
  (void)values;
#endif
}

std::vector<std::uint64_t> Processes::gather(const std::vector<std::uint64_t>& values) const {
#ifdef MCWS_HAVE_MPI
  if (distributed()) {
    const int count = static_cast<int>(values.size());
    std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(counts.size(), 0);
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    for (std::size_t r = 1; r < counts.size(); ++r) offsets[r] = offsets[r - 1] + counts[r - 1];
    std::vector<std::uint64_t> all(static_cast<std::size_t>(offsets.back() + counts.back()));
    MPI_Allgatherv(values.data(), count, MPI_UINT64_T, all.data(), counts.data(), offsets.data(),
                   MPI_UINT64_T, MPI_COMM_WORLD);
    return all;
  }
#endif
  return values;
}

void Processes::send(int to, const std::string& bytes) const {
#ifdef MCWS_HAVE_MPI
  std::uint64_t length = bytes.size();
  MPI_Send(&length, 1, MPI_UINT64_T, to, 0, MPI_COMM_WORLD);
  for (std::size_t at = 0; at < bytes.size(); at += kMaxPiece) {
    const std::size_t piece = std::min(kMaxPiece, bytes.size() - at);
    MPI_Send(bytes.data() + at, static_cast<int>(piece), MPI_BYTE, to, 0, MPI_COMM_WORLD);
  }
#else
  (void)to;
  (void)bytes;
  throw Error("no other process to send to in a build without MPI");
#endif
}

std::string Processes::receive(int from) const {
#ifdef MCWS_HAVE_MPI
  std::uint64_t length = 0;
  MPI_Recv(&length, 1, MPI_UINT64_T, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  std::string bytes(length, '\0');
  for (std::size_t at = 0; at < bytes.size(); at += kMaxPiece) {
    const std::size_t piece = std::min(kMaxPiece, bytes.size() - at);
    MPI_Recv(bytes.data() + at, static_cast<int>(piece), MPI_BYTE, from, 0, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
  }
  return bytes;
#else
  (void)from;
  throw Error("no other process to receive from in a build without MPI");
#endif
}

void reduceToFirst(const Processes& processes, const std::function<std::string()>& encode,
                   const std::function<void(const std::string&)>& merge) {
  const int rank = processes.rank();
  for (int step = 1; step < processes.size(); step *= 2) {
    if (rank % (2 * step) == step) {
      processes.send(rank - step, encode());
      return;
    }
    if (rank % (2 * step) == 0 && rank + step < processes.size()) {
      merge(processes.receive(rank + step));
    }
  }
}

Block blockOf(std::uint64_t n, int rank, int size) {
  const auto r = static_cast<std::uint64_t>(rank), k = static_cast<std::uint64_t>(size);
  const std::uint64_t base = n / k, extra = n % k;
  const std::uint64_t begin = r * base + std::min(r, extra);
  return {begin, begin + base + (r < extra ? 1 : 0)};
}

struct SharedFile::Impl {
  std::optional<io::AtomicFile> file;  ///< rank 0's: the temporary name and the final rename
#ifdef MCWS_HAVE_MPI
  MPI_File handle{MPI_FILE_NULL};
#endif
};

SharedFile::SharedFile(const Processes& processes, const std::string& path)
    : processes_(processes), path_(path), impl_(std::make_unique<Impl>()) {
  std::string name;
  if (processes.rank() == 0) {
    impl_->file.emplace(path);
    if (processes.distributed()) name = impl_->file->temporaryPath();
  }
#ifdef MCWS_HAVE_MPI
  if (processes.distributed()) {
    name = processes.broadcast(name);
    const int code =
        MPI_File_open(MPI_COMM_WORLD, name.c_str(), MPI_MODE_WRONLY, MPI_INFO_NULL, &impl_->handle);
    if (code != MPI_SUCCESS) {
      throw Error("cannot write '" + path_ + "' on process " + std::to_string(processes.rank()) +
                  ": " + mpiMessage(code));
    }
  }
#endif
}

SharedFile::~SharedFile() {
  // Without commit() the run is failing: no collective close (the other processes may not come
  // to it); rank 0's io::AtomicFile removes the temporary name.
}

void SharedFile::writeAt(std::uint64_t offset, const void* data, std::size_t size) {
  const char* bytes = static_cast<const char*>(data);
#ifdef MCWS_HAVE_MPI
  if (processes_.distributed()) {
    while (size > 0) {
      const std::size_t piece = std::min(size, kMaxPiece);
      MPI_Status status;
      const int code = MPI_File_write_at(impl_->handle, static_cast<MPI_Offset>(offset), bytes,
                                         static_cast<int>(piece), MPI_BYTE, &status);
      int written = 0;
      if (code == MPI_SUCCESS) MPI_Get_count(&status, MPI_BYTE, &written);
      if (code != MPI_SUCCESS || static_cast<std::size_t>(written) != piece) {
        throw Error("cannot write '" + path_ + "' on process " + std::to_string(processes_.rank()) +
                    ": " + (code != MPI_SUCCESS ? mpiMessage(code) : "short write"));
      }
      offset += piece;
      bytes += piece;
      size -= piece;
    }
    return;
  }
#endif
  const int fd = ::fileno(impl_->file->stream());
  while (size > 0) {
    const ssize_t written = ::pwrite(fd, bytes, size, static_cast<off_t>(offset));
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) {
      throw Error("cannot write '" + path_ +
                  "': " + (written < 0 ? std::strerror(errno) : "nothing written"));
    }
    offset += static_cast<std::uint64_t>(written);
    bytes += written;
    size -= static_cast<std::size_t>(written);
  }
}

void SharedFile::commit() {
  bool closed = true;
  std::string failure;
#ifdef MCWS_HAVE_MPI
  if (processes_.distributed()) {
    const int code = MPI_File_close(&impl_->handle);
    closed = code == MPI_SUCCESS;
    if (!closed) failure = mpiMessage(code);
  }
#endif
  // The name is given only when every process has closed its part.
  if (!processes_.allTrue(closed)) {
    throw Error("cannot write '" + path_ + "': " +
                (closed ? "another process could not finish its part"
                        : "process " + std::to_string(processes_.rank()) + ": " + failure));
  }
  if (processes_.rank() == 0) impl_->file->commit();
  processes_.barrier();  // every process returns with the file in place
}

int threadsPerProcess(int requested, const Processes& processes) {
  if (requested > 0 || !processes.distributed()) return requested;
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  cpu_set_t allowed;
  const int shared = std::max(1, cores / processes.localSize());
  if (::sched_getaffinity(0, sizeof allowed, &allowed) == 0 && CPU_COUNT(&allowed) < cores)
    return std::max(1, std::min(CPU_COUNT(&allowed), shared));  // bound to a socket: still shared
  return shared;
}

}  // namespace mcws::distributed
