#include "mcws/reach/reach_checkpoint.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "mcws/core/error.h"
#include "mcws/core/input_files.h"
#include "mcws/io/atomic_file.h"

namespace mcws {
namespace {

/// The map and samples done of a checkpoint file of run `run`; false when there is no file.
bool readCheckpoint(const ReachCheckpoint& checkpoint, const nlohmann::json& run, ReachMap& map,
                    std::uint64_t& done) {
  std::error_code ec;
  if (!std::filesystem::exists(checkpoint.path, ec)) return false;
  // Not noted as an input: the run rewrites it as it goes.
  requireRegularFile(checkpoint.path, "checkpoint");
  std::ifstream in(checkpoint.path, std::ios::binary);
  if (!in) throw Error("cannot read checkpoint '" + checkpoint.path + "'");
  std::string text;
  map = ReachMap::read(in, checkpoint.path, &text);
  const nlohmann::json header = nlohmann::json::parse(text, nullptr, false);
  if (header.is_discarded() || !header.contains("checkpoint_run") ||
      !header.contains("samples_done") || !header["samples_done"].is_number_unsigned()) {
    throw Error("checkpoint '" + checkpoint.path + "' is a map, not a checkpoint");
  }
  if (header["checkpoint_run"] != run) {
    throw Error("checkpoint '" + checkpoint.path +
                "' is of another run (other robot, grid, samples, seed or processes): remove it "
                "to start again");
  }
  done = header["samples_done"].get<std::uint64_t>();
  return true;
}

}  // namespace

ReachMap buildReachMapInPieces(const Robot& robot, const ReachGrid& grid,
                               const ReachSampling& sampling, const ReachCheckpoint& checkpoint,
                               const std::function<void(std::uint64_t, std::uint64_t)>& progress,
                               std::uint64_t* resumed) {
  if (checkpoint.every == 0) throw Error("checkpoint: samples per piece must be at least 1");
  const nlohmann::json run = nlohmann::json::parse(checkpoint.run, nullptr, false);
  if (run.is_discarded() || !run.is_object()) {
    throw Error("checkpoint: the run's name must be a JSON object, got '" + checkpoint.run + "'");
  }
  ReachMap map(grid);
  std::uint64_t done = 0;
  if (readCheckpoint(checkpoint, run, map, done) && done > sampling.samples) {
    throw Error("checkpoint '" + checkpoint.path + "' has done more samples than the run has");
  }
  if (resumed) *resumed = done;
  if (progress) progress(done, sampling.samples);
  while (done < sampling.samples) {
    ReachSampling piece = sampling;
    piece.first = sampling.first + done;
    piece.samples = std::min(checkpoint.every, sampling.samples - done);
    map.merge(buildReachMap(robot, grid, piece, [&](std::uint64_t piece_done, std::uint64_t) {
      if (progress) progress(done + piece_done, sampling.samples);
    }));
    done += piece.samples;
    std::ostringstream bytes;
    map.write(bytes, nlohmann::json{{"checkpoint_run", run}, {"samples_done", done}}.dump());
    io::AtomicFile file(checkpoint.path);
    const std::string text = bytes.str();
    file.write(text.data(), text.size());
    file.commit();
  }
  map.sort();
  return map;
}

}  // namespace mcws
