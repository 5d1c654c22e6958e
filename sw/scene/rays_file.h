#pragma once

#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "common/ray.h"

namespace lancer {

// Reads a rays file (format in traces/README.md): one ray a line, `ox oy oz dx dy dz`,
// decimal or C99 hex floats, `#` starts a comment. Ray ids are the order of the
// rays in the file, from 0. Throws InputError naming the file and line on a
// malformed line, a NaN or infinite component, or a zero direction.
std::vector<Ray> readRaysFile(const std::string& path);
// The same from a stream; `name` stands for the file in messages.
std::vector<Ray> readRays(std::istream& in, const std::string& name);

// Writes rays in the same format, with hex floats so they read back bit-exactly;
// `comment` (may be empty) goes on a leading `#` line.
void writeRaysFile(const std::string& path, const std::vector<Ray>& rays,
                   const std::string& comment = {});
// The same to a stream.
void writeRays(std::ostream& out, const std::vector<Ray>& rays, const std::string& comment = {});

// The one check every ray from any source goes through before it is traced.
// Throws InputError "<where>: ray <index>: ..." for NaN/inf components or a zero direction.
void validateRay(const Ray& ray, size_t index, const std::string& where);

}  // namespace lancer
