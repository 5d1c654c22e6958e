#pragma once

// One job of a sweep, run the same way by every executor: the width's own
// `lancer` (crack-rays for the crack set, then `run --report`, and for the
// traversal units `trace --report` of the float structure on the same rays),
// its report written to <out>/jobs/<key>.json, or on failure
// <out>/jobs/<key>.error.json naming the width and the job.

#include <string>

#include <nlohmann/json.hpp>

#include "sweep/spec.h"

namespace lancer::sweep {

// What a job's result depends on beyond its key; a resumed sweep reruns a job
// whose recorded inputs differ.
nlohmann::json jobInputs(const Spec& spec, const Job& job);

std::string jobResultPath(const std::string& out, const Job& job);
std::string jobErrorPath(const std::string& out, const Job& job);
std::string cameraRaysPath(const std::string& out, const Spec& spec, int scene, int chunk);

// Whether the job's result exists and was made from the same inputs.
bool jobDone(const std::string& out, const Spec& spec, const Job& job);

// Runs the job; returns "" on success, else the error (also written to the error file).
std::string executeJob(const std::string& out, const Spec& spec, const Job& job);

}  // namespace lancer::sweep
