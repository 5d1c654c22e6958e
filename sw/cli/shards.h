#pragma once

// Frames bigger than one machine (lancer run --shard I/N, lancer merge;
// docs/incoherent.md, "Shards"): a shard traces the camera samples
// [I*S/N, (I+1)*S/N) of the frame's S, keyed as in the whole frame, so the
// shards' samples put end to end are the one-machine run's, bit for bit. A
// shard's report carries its range and the run it is a part of; its samples
// (the hardware's and the float reference's, linear) go to <report>.samples.

#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace lancer::cli {

struct Shard {
  int index = 0;
  int count = 1;
};

// "I/N" with 0 <= I < N; InputError naming --shard otherwise.
Shard parseShard(const std::string& text);

// The shard's camera samples of a frame of `samples`: [first, last).
std::pair<size_t, size_t> shardRange(const Shard& shard, size_t samples);

std::string samplesFileOf(const std::string& report);
void writeShardSamples(const std::string& path, std::span<const glm::vec3> hardware,
                       std::span<const glm::vec3> reference);

// lancer merge: the shards' reports (every shard of one run, each once) into
// one report and the frame's samples. InputError naming the file for a report
// that is no shard, shards of different runs, a missing or repeated shard, or
// a samples file of the wrong size.
struct MergedFrame {
  nlohmann::json report;
  std::vector<glm::vec3> hardware, reference;  // the frame's samples
};
MergedFrame mergeShards(const std::vector<std::string>& reports);

}  // namespace lancer::cli
