#pragma once

// Where a job writes its waveform (StreamOptions::wavePath): the path itself
// for the first job of the process, then "name.1.fst", "name.2.fst", ... so a
// run of many jobs (an effects run traces a job per ray class and wave) keeps
// every job's waveform instead of overwriting the first with the last.

#include <string>

namespace lancer {

std::string nextWaveFile(const std::string& path);

}  // namespace lancer
