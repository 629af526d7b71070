#pragma once
/// \file
/// \brief The processes of one run: the MPI world when the tool was started by `mpirun` (and
/// built with MPI), else this process alone; and the files they write together.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace mcws::distributed {

/// \brief Whether MPI support was built in (CMake option MCWS_WITH_MPI, on when MPI is found).
bool builtWithMpi();

/// \brief Whether this process was started by an MPI launcher (`mpirun`, `mpiexec`, `srun`): it
/// sees the launcher's environment (OMPI_COMM_WORLD_SIZE, PMI_SIZE, PMIX_RANK).
bool launchedByMpi();

/// \brief Thrown by Processes::setUpDone() on the processes whose set-up went well when another
/// process's failed: that one reports; these end with its exit code, silently.
struct OtherProcessFailed {
  int code;
};

/// \brief What the processes agreed on at the end of their set-up.
struct Agreement {
  int first_failed;  ///< the lowest rank whose set-up failed (size() when none)
  int code;          ///< the largest exit code (0 when none failed)
};

/// \brief A run's processes and the collective operations the tools need.
///
/// Made at the start of main(). Started by an MPI launcher, it initialises MPI (and finalises it
/// when destroyed); otherwise, and always in a build without MPI, it is one process of rank 0
/// and every operation is the identity, so a tool's single-process run does not touch MPI at
/// all. The constructor does not throw: a launch on several processes of a build without MPI is
/// reported by require(), inside the tool's error handling.
class Processes {
 public:
  Processes(int& argc, char**& argv);
  /// \brief This process alone, whatever launched it: MPI is not touched (a library caller
  /// such as the Python module, which has no command line of its own to share).
  Processes() = default;
  ~Processes();
  Processes(const Processes&) = delete;
  Processes& operator=(const Processes&) = delete;

  /// \brief \throws mcws::Error when the launcher started several processes but this build has
  /// no MPI (each would write the whole output on its own), or when the processes were given
  /// different arguments (`mpirun -np 1 ... : -np 1 ...` with other flags: their parts would not
  /// fit together).
  void require() const;

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// \brief More than one process.
  bool distributed() const { return size_ > 1; }
  /// \brief The processes on this machine (1 without MPI): tools share its cores among them.
  int localSize() const { return local_size_; }

  /// \brief Collective, once, when a tool has read its command line and inputs: the point where
  /// a failure of any process's set-up becomes every process's (app::run). `same` lists
  /// (flag, value) pairs that must be equal on every process (the SHA-256 of the robot file, of
  /// an input cloud): a stale copy on one node would mix two robots in one output.
  /// \throws OtherProcessFailed when another process's set-up failed; when a `same` value
  ///   differs, mcws::Error "--FLAG: the processes did not all read the same file ..." on rank 0
  ///   and OtherProcessFailed{1} on the others.
  void setUpDone(const std::vector<std::pair<std::string, std::string>>& same = {});
  /// \brief Collective: this process's side of the set-up agreement, with its exit code (0: its
  /// set-up went well). Called by setUpDone(), and by app::run() for a process whose set-up
  /// threw.
  Agreement agreeOnSetUp(int code);
  /// \brief Whether the set-up agreement has taken place, and whether some set-up failed there.
  bool setUpAgreed() const { return agreed_; }
  bool setUpFailed() const { return agreed_ && agreement_.code != 0; }
  int setUpFirstFailed() const { return agreement_.first_failed; }

  /// \brief Ends every process of the run with exit code `code` (MPI_Abort); returns only when
  /// the run is not distributed. For a failure on one rank: the launcher ends the others with
  /// SIGTERM, on which their temporary files are removed (io::AtomicFile).
  void abortAll(int code) const;

  /// \brief Waits for every process.
  void barrier() const;
  /// \brief Whether `value` is true on every process.
  bool allTrue(bool value) const;
  /// \brief Rank 0's `text`, on every process.
  std::string broadcast(const std::string& text) const;
  /// \brief Rank 0's `value`, on every process.
  std::uint64_t broadcast(std::uint64_t value) const;
  /// \brief Element-wise sums, minima and maxima over the processes, in place.
  void sum(std::vector<std::uint64_t>& values) const;
  void min(std::vector<double>& values) const;
  void max(std::vector<double>& values) const;
  /// \brief Every process's `values`, concatenated in rank order, on every process.
  std::vector<std::uint64_t> gather(const std::vector<std::uint64_t>& values) const;
  /// \brief Sends `bytes` to process `to` (any length), which must receive() them.
  void send(int to, const std::string& bytes) const;
  /// \brief The bytes process `from` sends.
  std::string receive(int from) const;

 private:
  /// The agreement's collective: `code` and `hashes` in, the minimum of `hashes` out.
  Agreement agree(int code, std::vector<std::uint64_t>& hashes);

  int rank_{0};
  int size_{1};
  int local_size_{1};
  bool initialized_{false};    ///< MPI_Init was called here
  int launched_size_{1};       ///< the size the launcher announced
  bool same_arguments_{true};  ///< every process was given this one's arguments
  bool agreed_{false};         ///< agreeOnSetUp() has run
  Agreement agreement_{0, 0};
};

/// \brief Combines a value held by every process into rank 0's, along a binary tree: in round
/// s = 1, 2, 4, ... process r with r mod 2s = s sends `encode()` to r - s, which passes it to
/// `merge`; a process that has sent is done. log2(K) rounds, each process receiving at most that
/// many values and holding one received value at a time. The result is rank 0's value after its
/// merges; `merge` must not depend on the order it sees the values in (the tree fixes that order
/// anyway, for a given K). On one process it does nothing.
void reduceToFirst(const Processes& processes, const std::function<std::string()>& encode,
                   const std::function<void(const std::string&)>& merge);

/// \brief The contiguous share [begin, end) of n items (sample indices) of process `rank` of
/// `size`: the first n % size processes take one more.
struct Block {
  std::uint64_t begin{0}, end{0};
  std::uint64_t size() const { return end - begin; }
};
Block blockOf(std::uint64_t n, int rank, int size);

/// \brief One output file that every process writes its part of, at byte offsets (MPI-IO), and
/// that appears whole when every process has finished, or not at all.
///
/// Rank 0 makes an io::AtomicFile for `path` and gives it its temporary name, which every process
/// opens; commit() closes it on every process and rank 0 renames it onto `path`. A run that fails
/// or is killed leaves no output: a process that fails ends the run (Processes::abortAll()), and
/// rank 0, ended by the launcher with SIGTERM, removes the temporary name. On one process the
/// writes go straight to the io::AtomicFile (pwrite). The path must name a regular file (or a new
/// one): a device or FIFO cannot be written at offsets by several processes.
class SharedFile {
 public:
  /// \brief Collective. \throws mcws::Error naming the path when it cannot be written.
  SharedFile(const Processes& processes, const std::string& path);
  ~SharedFile();
  SharedFile(const SharedFile&) = delete;
  SharedFile& operator=(const SharedFile&) = delete;

  /// \brief Writes `size` bytes at byte `offset` (independent of the other processes).
  /// \throws mcws::Error naming the path on a write error.
  void writeAt(std::uint64_t offset, const void* data, std::size_t size);
  /// \brief Collective: closes the file everywhere, then rank 0 gives it its name; returns when
  /// the file is there. \throws mcws::Error naming the path on failure.
  void commit();

  const std::string& path() const { return path_; }

 private:
  struct Impl;
  const Processes& processes_;
  std::string path_;
  std::unique_ptr<Impl> impl_;
};

/// \brief The threads each process of a run on several processes runs: `requested` (a tool's
/// --threads), or for 0 the cores the launcher bound the process to, else the machine's cores
/// shared among the run's processes on it (at least 1). One process: `requested` as it is.
int threadsPerProcess(int requested, const Processes& processes);

}  // namespace mcws::distributed
