#pragma once

// Dual precision (docs/accuracy.md, "Dual precision"): a narrow intersection
// unit in front of the full-width one. The narrow unit sees each lattice input
// with its low bits dropped (positions and directions kept to `narrowBits`),
// knows only that the true value lies in the interval those bits leave, and
// rejects a ray-triangle pair only when every full-width input in those
// intervals gives a miss. Everything else (every hit, and every pair it cannot
// settle) is re-tested at full width: the escalation a chip would pay for.
// The model evaluates fx::intersect's steps in interval arithmetic, so a
// rejection is a proof that the full-width test misses.

#include "golden/records.h"

namespace lancer::fx {

// True if the narrow unit proves that fx::intersect(ray, tri) misses. With
// narrowBits >= the format's width nothing is dropped and the answer is exact
// for every pair that misses for its edge signs or its t (a miss for a zero
// determinant or beyond the segment's end is left to the full unit).
bool narrowRejects(const QRay& ray, const QTriangle& tri, int narrowBits);

}  // namespace lancer::fx
