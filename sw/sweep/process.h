#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lancer::sweep {

// Runs argv[0] (searched on PATH) with argv, its stdout and stderr appended to
// `log` (created if missing), in the current directory. Returns its exit status
// (128 + the signal if it was killed; 127 if it could not start).
int runLogged(const std::vector<std::string>& argv, const std::string& log);

// Runs argv and returns its stdout; status set to the exit status.
std::string runCaptured(const std::vector<std::string>& argv, int& status);

// The last non-empty line of a text file ("" if none), for error messages.
std::string lastLine(const std::string& path);

// The line of a log that says what went wrong: the message of the first
// "CMake Error", else the last line with "error", else the last line.
std::string errorLine(const std::string& path);

// A command line as a shell would read it (for logs and Slurm scripts).
std::string shellJoin(const std::vector<std::string>& argv);

// Writes `text` to `path` through a temporary file and a rename, so a reader
// (a resumed sweep, a merge) never sees half a file. Throws InputError.
// The JSON in a file, or null if it is missing or not JSON (a result not written yet).
nlohmann::json readJson(const std::string& path);

void writeAtomically(const std::string& path, const std::string& text);

}  // namespace lancer::sweep
